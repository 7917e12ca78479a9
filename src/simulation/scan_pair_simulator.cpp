#include <pcl_crf/simulation/scan_pair_simulator.h>
#include <pcl_crf/simulation/rigid_math.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace pcl_crf {
namespace simulation {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

/** Sub-streams of pair k: each part of a pair draws from its own stream, so
 *  e.g. the beam count changes the scans but not the scene. */
enum StreamPurpose : std::uint64_t
{
  kChoiceStream = 0,    // scene type, moving count, travel distance
  kWorldStream = 1,     // the static street
  kTrafficStream = 2,   // the moving objects
  kSourceScanStream = 3,
  kTargetScanStream = 4,
  kOdometryStream = 5
};

/** Relative frequency of each concrete scene type in a Mixed dataset, in the
 *  order of concreteSceneTypes() (outline, crossing, overtaking, opposite,
 *  pedestrians, static). */
const std::vector<double> kMixedSceneWeights{2.0, 2.0, 2.0, 2.0, 2.0, 1.0};

/** Variance floor of the written odometry covariance [m^2, rad^2]. */
constexpr double kMinOdometryVariance = 1e-6;

/** Moving-object count range when moving_count is -1. */
constexpr int kMinRandomMoving = 1;
constexpr int kMaxRandomMoving = 4;

[[noreturn]] void
fail (const std::string& what)
{
  throw SimulationError (what);
}

/** \a value as %g prints it, for messages ("1000", "1e+09"). */
std::string
number (double value)
{
  char text[32];
  std::snprintf (text, sizeof (text), "%g", value);
  return text;
}

void
requireFinite (double value, const char* what)
{
  if (!std::isfinite (value))
    fail (std::string (what) + " must be a finite number");
}

/** The transform rebuilt from its (x, y, theta) as the dataset reader does
 *  (makeRigid2d), so that a re-read pair differs from this one by at most an
 *  ulp or so of the rotation entries (atan2 (sin t, cos t) may differ from t in
 *  the last bit). */
Rigid2d
canonical (const Rigid2d& T)
{
  const Eigen::Vector3d v = toXYTheta (T);
  return makeRigid2d (v.x (), v.y (), v.z ());
}

/** \a scan with a point at the maximum range for every beam without a return (its
 *  points' beams in \a beams), labelled as the static world (id 0): point k moves to
 *  index beams[k]. */
void
addNoReturnPoints (const SensorInfo& sensor, const std::vector<int>& beams, Eigen::Matrix2Xd& scan,
                   std::vector<int>& labels)
{
  Eigen::Matrix2Xd all (2, sensor.beam_count);
  std::vector<int> all_labels (static_cast<std::size_t> (sensor.beam_count), 0);
  for (int b = 0; b < sensor.beam_count; ++b) {
    const double angle = sensor.angle_min + b * sensor.angle_increment;
    all.col (b) << storedCoordinate (sensor.range_max * std::cos (angle)),
        storedCoordinate (sensor.range_max * std::sin (angle));
  }
  for (std::size_t k = 0; k < beams.size (); ++k) {
    all.col (beams[k]) = scan.col (static_cast<Eigen::Index> (k));
    all_labels[static_cast<std::size_t> (beams[k])] = labels[k];
  }
  scan = std::move (all);
  labels = std::move (all_labels);
}

/** Both scans of \a pair with their beams without a return as points at the maximum
 *  range (LaserConfig::no_return_points); the true matches follow their points. */
void
keepNoReturnBeams (ScanPair& pair, const std::vector<int>& source_beams, const std::vector<int>& target_beams)
{
  addNoReturnPoints (pair.sensor, source_beams, pair.source, pair.source_object);
  addNoReturnPoints (pair.sensor, target_beams, pair.target, pair.target_object);
  std::vector<int> matches (static_cast<std::size_t> (pair.source.cols ()), kNoMatch);
  for (std::size_t k = 0; k < source_beams.size (); ++k) {
    const int j = pair.source_match[k];
    matches[static_cast<std::size_t> (source_beams[k])] =
        j == kNoMatch ? kNoMatch : target_beams[static_cast<std::size_t> (j)];
  }
  pair.source_match = std::move (matches);
}

}  // namespace

void
validateSimulatorConfig (const SimulatorConfig& c)
{
  const LaserConfig& l = c.laser;
  if (l.beam_count < 2 || l.beam_count > kMaxSimulatedBeams)
    fail ("beam count (--beams) must be in 2.." + std::to_string (kMaxSimulatedBeams) + ", got " +
          std::to_string (l.beam_count));
  requireFinite (l.field_of_view, "field of view (--fov)");
  if (l.field_of_view <= 0.0 || l.field_of_view > kTwoPi + 1e-9)
    fail ("field of view (--fov) must be in (0, 360] degrees");
  requireFinite (l.range_max, "maximum range (--range)");
  if (l.range_max <= 0.0 || l.range_max > kMaxSimulatedRange)
    fail ("maximum range (--range) must be in (0, " + number (kMaxSimulatedRange) + "] m, got " +
          number (l.range_max));
  requireFinite (l.range_noise, "range noise (--noise)");
  if (l.range_noise < 0.0)
    fail ("range noise (--noise) must not be negative");
  if (l.range_noise >= l.range_max)
    fail ("range noise (--noise) must be below the maximum range (--range), got " + number (l.range_noise) +
          " m against " + number (l.range_max) + " m");
  requireFinite (l.dropout_probability, "dropout probability (--dropout)");
  if (l.dropout_probability < 0.0 || l.dropout_probability >= 1.0)
    fail ("dropout probability (--dropout) must be in [0, 1)");
  requireFinite (c.ego_speed, "ego speed (--speed)");
  if (c.ego_speed < 0.0)
    fail ("ego speed (--speed) must not be negative");
  requireFinite (c.ego_yaw_rate, "ego yaw rate (--yaw-rate)");
  if (c.spacing == ScanSpacing::Travel) {
    if (c.ego_speed <= 0.0)
      fail ("travel spacing needs a positive ego speed (--speed); use --spacing consecutive for a "
            "standing sensor");
    requireFinite (c.travel_min, "travel distance (--travel)");
    requireFinite (c.travel_max, "travel distance (--travel)");
    if (c.travel_min <= 0.0 || c.travel_max < c.travel_min || c.travel_max > kMaxSimulatedTravel)
      fail ("travel distances (--travel MIN,MAX) must satisfy 0 < MIN <= MAX <= " +
            number (kMaxSimulatedTravel) + " m, got " + number (c.travel_min) + "," + number (c.travel_max));
    if (c.travel_min / c.ego_speed < kMinSimulatedScanInterval)
      fail ("the shortest time between the scans, travel / speed (--travel MIN / --speed), must be at least " +
            number (kMinSimulatedScanInterval) + " s, got " + number (c.travel_min / c.ego_speed) + " s");
  }
  else {
    requireFinite (c.scan_rate, "scan rate (--scan-rate)");
    if (c.scan_rate < kMinSimulatedScanRate || 1.0 / c.scan_rate < kMinSimulatedScanInterval)
      fail ("scan rate (--scan-rate) must be in [" + number (kMinSimulatedScanRate) + ", " +
            number (1.0 / kMinSimulatedScanInterval) + "] Hz, got " + number (c.scan_rate));
    if (c.ego_speed / c.scan_rate > kMaxSimulatedTravel)
      fail ("the ego would travel " + number (c.ego_speed / c.scan_rate) + " m between the scans (--speed / "
            "--scan-rate), more than " + number (kMaxSimulatedTravel) + " m");
  }
  if (c.moving_count < -1)
    fail ("moving object count (--moving) must be >= 0, or -1 for a random count in 1..4");
  if (c.scene == SceneType::Static && c.moving_count > 0)
    fail ("the static scene has no moving objects; drop --moving or choose another --scene");
  requireFinite (c.traffic.object_speed, "object speed (--object-speed)");
  if (c.traffic.object_speed > kMaxSimulatedObjectSpeed ||
      (c.traffic.object_speed >= 0.0 && c.traffic.object_speed < kMinSimulatedObjectSpeed))
    fail ("object speed (--object-speed) must be in [" + number (kMinSimulatedObjectSpeed) + ", " +
          number (kMaxSimulatedObjectSpeed) + "] m/s (an object standing still is part of the static world; "
          "negative: drawn per kind), got " + number (c.traffic.object_speed));
  requireFinite (c.traffic.legged_pedestrian_fraction, "legged pedestrian fraction");
  if (c.traffic.legged_pedestrian_fraction < 0.0 || c.traffic.legged_pedestrian_fraction > 1.0)
    fail ("legged pedestrian fraction must be in [0, 1]");
  for (int k = 0; k < 3; ++k) {
    requireFinite (c.odometry_noise[k], "odometry noise (--odom-noise)");
    if (c.odometry_noise[k] < 0.0)
      fail ("odometry noise (--odom-noise) must not be negative");
  }
  if (c.name_prefix.find_first_of ("/\\") != std::string::npos)
    fail ("name prefix (--name-prefix) must not contain a path separator");
}

double
matchTolerance (double range, double angle_increment, double range_noise)
{
  return 2.0 * range * angle_increment + 3.0 * range_noise + 0.02;
}

void
assignTrueMatches (ScanPair& pair, double range_noise)
{
  std::map<int, std::vector<int>> target_by_object;
  for (std::size_t j = 0; j < pair.target_object.size (); ++j)
    target_by_object[pair.target_object[j]].push_back (static_cast<int> (j));
  pair.source_match.assign (static_cast<std::size_t> (pair.source.cols ()), kNoMatch);
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i) {
    const int id = pair.source_object[static_cast<std::size_t> (i)];
    const int object = pair.objectIndex (id);
    const auto candidates = target_by_object.find (id);
    if (object < 0 || candidates == target_by_object.end ())
      continue;
    const Eigen::Vector2d q =
        transformPoint (pair.objects[static_cast<std::size_t> (object)].T_target_source, pair.source.col (i));
    int best = kNoMatch;
    double best_squared = 0.0;
    for (int j : candidates->second) {
      const double d2 = squaredDistance2 (pair.target.col (j), q);
      if (best == kNoMatch || d2 < best_squared) {
        best = j;
        best_squared = d2;
      }
    }
    const double tolerance = matchTolerance (std::sqrt (dot2 (q, q)), pair.sensor.angle_increment, range_noise);
    if (best != kNoMatch && best_squared <= tolerance * tolerance)
      pair.source_match[static_cast<std::size_t> (i)] = best;
  }
}

ScanPairSimulator::ScanPairSimulator (const SimulatorConfig& config)
{
  setConfig (config);
}

void
ScanPairSimulator::setConfig (const SimulatorConfig& config)
{
  validateSimulatorConfig (config);
  config_ = config;
}

std::string
ScanPairSimulator::pairName (std::size_t index) const
{
  char digits[32];
  std::snprintf (digits, sizeof (digits), "%04llu", static_cast<unsigned long long> (index));
  return config_.name_prefix + digits;
}

ScanPair
ScanPairSimulator::simulate (std::size_t index, PairSummary* summary, PairScene* pair_scene) const
{
  const SimulatorConfig& c = config_;
  const std::uint64_t k = static_cast<std::uint64_t> (index);

  // ---- per-pair choices: scene type, number of moving objects, time between scans
  RandomStream choice (c.seed, k, kChoiceStream);
  const std::size_t drawn_type = choice.choose (kMixedSceneWeights);
  const int drawn_count = choice.uniformInt (kMinRandomMoving, kMaxRandomMoving);
  const double drawn_travel = choice.uniform (c.travel_min, c.travel_max);
  const SceneType type = c.scene == SceneType::Mixed ? concreteSceneTypes ()[drawn_type] : c.scene;
  const double duration = c.spacing == ScanSpacing::Travel ? drawn_travel / c.ego_speed : 1.0 / c.scan_rate;

  UrbanSceneSpec spec;
  spec.type = type;
  spec.mix_types = c.scene == SceneType::Mixed;
  spec.moving_count = type == SceneType::Static ? 0 : (c.moving_count >= 0 ? c.moving_count : drawn_count);
  spec.ego.speed = c.ego_speed;
  spec.ego.yaw_rate = c.ego_yaw_rate;
  spec.duration = duration;
  const double ego_travel = c.ego_speed * duration;
  spec.x_min = -(c.laser.range_max + 10.0);
  spec.x_max = ego_travel + c.laser.range_max + 10.0;
  spec.traffic = c.traffic;

  RandomStream world_rng (c.seed, k, kWorldStream), traffic_rng (c.seed, k, kTrafficStream);
  const Scene scene = generateUrbanScene (spec, world_rng, traffic_rng);

  // ---- the two scans
  const Rigid2d pose0 = spec.ego.poseAt (0.0), pose1 = spec.ego.poseAt (duration);
  const LaserScanner scanner (c.laser);
  RandomStream source_rng (c.seed, k, kSourceScanStream), target_rng (c.seed, k, kTargetScanStream);
  const SimulatedScan source = scanner.scan (scene.at (0.0), pose0, source_rng);
  const SimulatedScan target = scanner.scan (scene.at (duration), pose1, target_rng);

  ScanPair pair;
  pair.name = pairName (index);
  if (source.points.cols () == 0 || target.points.cols () == 0)
    fail ("pair " + pair.name + ": a scan has no return at all; increase the range (--range) or lower the dropout");
  pair.sensor = c.laser.sensorInfo ();
  pair.source = source.points;
  pair.target = target.points;

  // ---- objects hit by at least one point, renumbered 0 (world), 1, 2, ... in scene order
  std::map<int, int> new_id;
  Scene visible_scene;
  for (const auto& object : scene.getObjects ()) {
    const bool seen = std::count (source.object_ids.begin (), source.object_ids.end (), object.id) > 0 ||
                      std::count (target.object_ids.begin (), target.object_ids.end (), object.id) > 0;
    if (!seen && !object.is_static)
      continue;
    ObjectTruth truth;
    truth.id = object.is_static ? 0 : static_cast<int> (pair.objects.size ());
    truth.is_static = object.is_static;
    truth.kind = object.kind;
    // T_target_source = pose_sensor1^-1 * O1 * O0^-1 * pose_sensor0
    const Rigid2d O0 = object.poseAt (0.0), O1 = object.poseAt (duration);
    truth.T_target_source =
        canonical (composeRigid (composeRigid (invertRigid (pose1), O1), composeRigid (invertRigid (O0), pose0)));
    new_id[object.id] = truth.id;
    pair.objects.push_back (truth);
    SceneObject renamed = object;
    renamed.id = truth.id;
    visible_scene.addObject (std::move (renamed));
  }
  for (int id : source.object_ids)
    pair.source_object.push_back (new_id.at (id));
  for (int id : target.object_ids)
    pair.target_object.push_back (new_id.at (id));

  // ---- odometry: the true sensor motion plus Gaussian noise per component
  RandomStream odometry_rng (c.seed, k, kOdometryStream);
  const Eigen::Vector3d truth = toXYTheta (composeRigid (invertRigid (pose0), pose1));
  Eigen::Vector3d measured;
  for (int i = 0; i < 3; ++i)
    measured[i] = truth[i] + c.odometry_noise[i] * odometry_rng.normal ();
  pair.odometry.T_source_target = canonical (makeRigid2d (measured.x (), measured.y (), measured.z ()));
  pair.odometry.covariance.setZero ();
  for (int i = 0; i < 3; ++i)
    pair.odometry.covariance (i, i) = std::max (c.odometry_noise[i] * c.odometry_noise[i], kMinOdometryVariance);
  pair.odometry.interval = duration;

  assignTrueMatches (pair, c.laser.range_noise);
  if (c.laser.no_return_points)
    keepNoReturnBeams (pair, source.beams, target.beams);

  if (pair_scene) {
    pair_scene->scene = std::move (visible_scene);
    pair_scene->sensor_pose_source = pose0;
    pair_scene->sensor_pose_target = pose1;
    pair_scene->duration = duration;
  }
  if (summary) {
    *summary = PairSummary ();
    summary->name = pair.name;
    summary->scene = type;
    summary->duration = duration;
    summary->ego_travel = ego_travel;
    summary->moving_placed = static_cast<int> (scene.getObjects ().size ()) - 1;
    summary->moving_visible = static_cast<int> (pair.objects.size ()) - 1;
    for (const auto& object : pair.objects)
      if (!object.is_static)
        summary->moving_kinds.push_back (object.kind);
    summary->source_points = static_cast<int> (pair.source.cols ());
    summary->target_points = static_cast<int> (pair.target.cols ());
    summary->matched = static_cast<int> (
        std::count_if (pair.source_match.begin (), pair.source_match.end (), [] (int m) { return m != kNoMatch; }));
  }
  return pair;
}

std::vector<ScanPair>
ScanPairSimulator::simulateDataset (std::size_t first, std::size_t count, std::vector<PairSummary>* summaries) const
{
  std::vector<ScanPair> pairs;
  pairs.reserve (count);
  if (summaries)
    summaries->assign (count, PairSummary ());
  for (std::size_t k = 0; k < count; ++k)
    pairs.push_back (simulate (first + k, summaries ? &(*summaries)[k] : nullptr));
  return pairs;
}

}  // namespace simulation
}  // namespace pcl_crf
