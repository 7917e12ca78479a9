// Tests of the urban-scene laser simulator (pcl_crf::simulation).
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/laser_scanner.h>
#include <pcl_crf/simulation/random_stream.h>
#include <pcl_crf/simulation/rigid_math.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>
#include <pcl_crf/simulation/scene.h>
#include <pcl_crf/simulation/urban_scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <set>
#include <unistd.h>

namespace {

namespace sim = pcl_crf::simulation;
using pcl_crf::ScanPair;

constexpr double kPi = 3.14159265358979323846;

/** A config without randomness in the measurements. */
sim::SimulatorConfig
noiseFreeConfig (sim::SceneType scene, std::uint64_t seed)
{
  sim::SimulatorConfig config;
  config.scene = scene;
  config.seed = seed;
  config.laser.range_noise = 0.0;
  config.laser.dropout_probability = 0.0;
  config.traffic.legged_pedestrian_fraction = 0.0;  // rigid pedestrians only
  return config;
}

sim::SceneObject
wallObject (double x)
{
  sim::SceneObject wall;
  wall.id = 0;
  wall.kind = "world";
  wall.is_static = true;
  wall.geometry.addSegment ({x, -1000.0}, {x, 1000.0});
  return wall;
}

double
distanceToSegment (const Eigen::Vector2d& p, const sim::Segment& s)
{
  const Eigen::Vector2d e = s.b - s.a;
  const double t = std::clamp ((p - s.a).dot (e) / e.squaredNorm (), 0.0, 1.0);
  return (s.a + t * e - p).norm ();
}

/** Distance from a world point to the surface of an object's outline. */
double
distanceToSurface (const Eigen::Vector2d& p, const sim::Geometry& world_geometry)
{
  double best = std::numeric_limits<double>::infinity ();
  for (const auto& s : world_geometry.segments)
    best = std::min (best, distanceToSegment (p, s));
  for (const auto& c : world_geometry.circles)
    best = std::min (best, std::abs ((p - c.centre).norm () - c.radius));
  return best;
}

bool
sameMotion (const pcl_crf::Rigid2d& a, const pcl_crf::Rigid2d& b, double tolerance)
{
  return (a.matrix () - b.matrix ()).cwiseAbs ().maxCoeff () <= tolerance;
}

/** Equal pairs: everything identical, motions within \a motion_tolerance
 *  (0: bitwise; a pair read back from disk rebuilds its rotations from angles). */
bool
samePair (const ScanPair& a, const ScanPair& b, double motion_tolerance = 0.0)
{
  if (a.name != b.name || a.objects.size () != b.objects.size ())
    return false;
  for (std::size_t k = 0; k < a.objects.size (); ++k)
    if (a.objects[k].id != b.objects[k].id || a.objects[k].kind != b.objects[k].kind ||
        a.objects[k].is_static != b.objects[k].is_static ||
        !sameMotion (a.objects[k].T_target_source, b.objects[k].T_target_source, motion_tolerance))
      return false;
  return a.source.cols () == b.source.cols () && a.target.cols () == b.target.cols () && a.source == b.source &&
         a.target == b.target && a.source_object == b.source_object && a.target_object == b.target_object &&
         a.source_match == b.source_match &&
         sameMotion (a.odometry.T_source_target, b.odometry.T_source_target, motion_tolerance) &&
         a.odometry.covariance == b.odometry.covariance && a.sensor.beam_count == b.sensor.beam_count &&
         a.sensor.angle_min == b.sensor.angle_min && a.sensor.angle_increment == b.sensor.angle_increment &&
         a.sensor.range_max == b.sensor.range_max;
}

std::filesystem::path
freshTempDir (const std::string& name)
{
  const auto dir = std::filesystem::temp_directory_path () /
                   ("pcl_crf_" + name + "_" + std::to_string (static_cast<long> (::getpid ())));
  std::filesystem::remove_all (dir);
  std::filesystem::create_directories (dir);
  return dir;
}

// ---------------------------------------------------------------- random numbers
TEST (SimulatorRandom, StreamsAreReproducibleAndWellDistributed)
{
  sim::RandomStream a (5, 3, 1), b (5, 3, 1), c (5, 4, 1);
  double sum = 0.0, sum2 = 0.0, usum = 0.0;
  bool differs = false;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = a.normal ();
    EXPECT_EQ (x, b.normal ());
    differs = differs || x != c.normal ();
    sum += x;
    sum2 += x * x;
    const double u = a.uniform ();
    EXPECT_EQ (u, b.uniform ());
    EXPECT_GE (u, 0.0);
    EXPECT_LT (u, 1.0);
    usum += u;
    c.uniform ();
  }
  EXPECT_TRUE (differs);
  EXPECT_NEAR (sum / n, 0.0, 0.03);
  EXPECT_NEAR (sum2 / n, 1.0, 0.05);
  EXPECT_NEAR (usum / n, 0.5, 0.01);
  // mt19937_64 is fixed by the standard: its 10000th output for the default seed.
  std::mt19937_64 reference;
  reference.discard (9999);
  EXPECT_EQ (reference (), 9981545732273789042ULL);
}

TEST (SimulatorRigidMath, AgreesWithEigen)
{
  const pcl_crf::Rigid2d A = pcl_crf::makeRigid2d (1.5, -2.0, 0.7), B = pcl_crf::makeRigid2d (-0.3, 4.0, -2.1);
  EXPECT_LT ((sim::composeRigid (A, B).matrix () - (A * B).matrix ()).cwiseAbs ().maxCoeff (), 1e-14);
  EXPECT_LT ((sim::invertRigid (A).matrix () - A.inverse ().matrix ()).cwiseAbs ().maxCoeff (), 1e-14);
  const Eigen::Vector2d p (3.0, -1.0);
  EXPECT_LT ((sim::transformPoint (A, p) - A * p).norm (), 1e-14);
  EXPECT_DOUBLE_EQ (sim::dot2 (p, Eigen::Vector2d (2.0, 5.0)), 1.0);
  EXPECT_DOUBLE_EQ (sim::squaredDistance2 (p, Eigen::Vector2d (0.0, 3.0)), 25.0);
}

// ---------------------------------------------------------------- ray casting
TEST (SimulatorRayCasting, WallAtKnownDistanceGivesExactRange)
{
  sim::Scene scene;
  scene.addObject (wallObject (10.0));
  const sim::SceneSnapshot snapshot = scene.at (0.0);
  for (double angle : {0.0, 0.3, -0.7, 1.2}) {
    const sim::RayHit hit = snapshot.castRay ({{0.0, 0.0}, {std::cos (angle), std::sin (angle)}}, 30.0);
    ASSERT_TRUE (hit.valid ());
    EXPECT_EQ (hit.object_id, 0);
    EXPECT_NEAR (hit.range, 10.0 / std::cos (angle), 1e-12);
  }
  EXPECT_FALSE (snapshot.castRay ({{0.0, 0.0}, {-1.0, 0.0}}, 30.0).valid ());  // behind
  EXPECT_FALSE (snapshot.castRay ({{0.0, 0.0}, {std::cos (1.3), std::sin (1.3)}}, 30.0).valid ());  // beyond range

  sim::LaserConfig config;
  config.beam_count = 181;
  config.range_noise = 0.0;
  config.dropout_probability = 0.0;
  const sim::LaserScanner scanner (config);
  sim::RandomStream rng (1);
  const sim::SimulatedScan scan = scanner.scan (snapshot, pcl_crf::Rigid2d::Identity (), rng);
  ASSERT_GT (scan.points.cols (), 0);
  const double increment = config.sensorInfo ().angle_increment;
  for (Eigen::Index k = 0; k < scan.points.cols (); ++k) {
    const double angle = -kPi / 2 + scan.beams[k] * increment;
    EXPECT_LE (10.0 / std::cos (angle), 30.0 + 1e-9);
    EXPECT_NEAR (scan.points (0, k), 10.0, 1e-6);
    EXPECT_NEAR (scan.points.col (k).norm (), 10.0 / std::cos (angle), 1e-5);
  }
  // Exactly the beams whose wall distance is within range: |angle| <= acos(1/3).
  const int expected = 2 * static_cast<int> (std::floor (std::acos (10.0 / 30.0) / increment)) + 1;
  EXPECT_EQ (scan.points.cols (), expected);
}

TEST (SimulatorRayCasting, SensorPoseMovesTheRay)
{
  sim::Scene scene;
  scene.addObject (wallObject (10.0));
  sim::LaserConfig config;
  config.beam_count = 3;
  config.range_noise = 0.0;
  config.dropout_probability = 0.0;
  sim::RandomStream rng (1);
  // Sensor at (4, 1) facing +x: the middle beam measures 6 m straight ahead.
  const auto scan = sim::LaserScanner (config).scan (scene.at (0.0), pcl_crf::makeRigid2d (4.0, 1.0, 0.0), rng);
  ASSERT_EQ (scan.points.cols (), 1);
  EXPECT_EQ (scan.beams[0], 1);
  EXPECT_NEAR (scan.points (0, 0), 6.0, 1e-6);
  EXPECT_NEAR (scan.points (1, 0), 0.0, 1e-6);
}

TEST (SimulatorRayCasting, PoleOccludesWall)
{
  sim::Scene scene;
  scene.addObject (wallObject (10.0));
  sim::SceneObject pole;
  pole.id = 1;
  pole.kind = "pole";
  pole.geometry.addCircle ({5.0, 0.0}, 0.2);
  scene.addObject (pole);
  const sim::SceneSnapshot snapshot = scene.at (0.0);
  const sim::RayHit front = snapshot.castRay ({{0.0, 0.0}, {1.0, 0.0}}, 30.0);
  EXPECT_EQ (front.object_id, 1);
  EXPECT_NEAR (front.range, 4.8, 1e-12);
  const double beside = std::atan2 (0.5, 5.0);  // passes 0.5 m from the pole's centre
  const sim::RayHit wall = snapshot.castRay ({{0.0, 0.0}, {std::cos (beside), std::sin (beside)}}, 30.0);
  EXPECT_EQ (wall.object_id, 0);
  EXPECT_NEAR (wall.range, 10.0 / std::cos (beside), 1e-12);
  // A box in front of the pole hides it in turn.
  sim::SceneObject car;
  car.id = 2;
  car.kind = "car";
  car.geometry.addBox (4.5, 1.8);
  car.trajectory.start = pcl_crf::makeRigid2d (3.0, 0.0, kPi / 2);
  scene.addObject (car);
  const sim::RayHit box = scene.at (0.0).castRay ({{0.0, 0.0}, {1.0, 0.0}}, 30.0);
  EXPECT_EQ (box.object_id, 2);
  EXPECT_NEAR (box.range, 3.0 - 0.9, 1e-12);
}

TEST (SimulatorRayCasting, MovingObjectFollowsItsTrajectory)
{
  sim::Trajectory straight;
  straight.start = pcl_crf::makeRigid2d (1.0, 2.0, kPi / 2);
  straight.speed = 2.0;
  EXPECT_NEAR ((straight.poseAt (1.5).translation () - Eigen::Vector2d (1.0, 5.0)).norm (), 0.0, 1e-12);
  sim::Trajectory turn;
  turn.speed = 1.0;
  turn.yaw_rate = 0.5;  // a circle of radius 2 around (0, 2)
  const pcl_crf::Rigid2d half = turn.poseAt (kPi / 0.5);
  EXPECT_NEAR ((half.translation () - Eigen::Vector2d (0.0, 4.0)).norm (), 0.0, 1e-12);
  EXPECT_NEAR (std::abs (pcl_crf::rotationAngle (half)), kPi, 1e-12);
}

// ---------------------------------------------------------------- beams
TEST (SimulatorLaser, BeamOrderAndCount)
{
  // A closed square room: every beam of a full turn returns.
  sim::Scene scene;
  sim::SceneObject room;
  room.id = 0;
  room.is_static = true;
  room.kind = "world";
  room.geometry.addPolyline ({{8, -6}, {8, 7}, {-9, 7}, {-9, -6}, {8, -6}});
  scene.addObject (room);
  for (int beams : {181, 361, 1081}) {
    sim::LaserConfig config;
    config.beam_count = beams;
    const pcl_crf::SensorInfo info = config.sensorInfo ();
    EXPECT_NEAR (info.angle_min, -kPi / 2, 1e-15);
    EXPECT_NEAR (info.angleMax (), kPi / 2, 1e-12);
    config.dropout_probability = 0.0;
    sim::RandomStream rng (beams);
    const auto full = sim::LaserScanner (config).scan (scene.at (0.0), pcl_crf::Rigid2d::Identity (), rng);
    ASSERT_EQ (full.points.cols (), beams);
    for (int k = 0; k < beams; ++k) {
      EXPECT_EQ (full.beams[k], k);
      const double angle = std::atan2 (full.points (1, k), full.points (0, k));
      EXPECT_NEAR (angle, info.angle_min + k * info.angle_increment, 1e-5);
    }
    // Dropouts remove points but keep the counter-clockwise order of the rest.
    config.dropout_probability = 0.3;
    const auto sparse = sim::LaserScanner (config).scan (scene.at (0.0), pcl_crf::Rigid2d::Identity (), rng);
    EXPECT_LT (sparse.points.cols (), beams * 0.8);
    EXPECT_GT (sparse.points.cols (), beams * 0.6);
    for (Eigen::Index k = 1; k < sparse.points.cols (); ++k) {
      EXPECT_LT (sparse.beams[k - 1], sparse.beams[k]);
      EXPECT_LT (std::atan2 (sparse.points (1, k - 1), sparse.points (0, k - 1)),
                 std::atan2 (sparse.points (1, k), sparse.points (0, k)));
    }
  }
  sim::LaserConfig turn;
  turn.beam_count = 360;
  turn.field_of_view = 2 * kPi;
  EXPECT_NEAR (turn.sensorInfo ().angle_increment, 2 * kPi / 360, 1e-15);  // no duplicated beam
}

TEST (SimulatorLaser, RangeNoiseHasTheConfiguredSpread)
{
  sim::Scene scene;
  scene.addObject (wallObject (10.0));
  sim::LaserConfig config;
  config.beam_count = 2001;
  config.field_of_view = 0.2;
  config.range_noise = 0.05;
  config.dropout_probability = 0.0;
  sim::RandomStream rng (3);
  const auto scan = sim::LaserScanner (config).scan (scene.at (0.0), pcl_crf::Rigid2d::Identity (), rng);
  ASSERT_EQ (scan.points.cols (), 2001);
  double sum = 0.0, sum2 = 0.0;
  for (Eigen::Index k = 0; k < scan.points.cols (); ++k) {
    const double angle = std::atan2 (scan.points (1, k), scan.points (0, k));
    const double error = scan.points.col (k).norm () - 10.0 / std::cos (angle);
    sum += error;
    sum2 += error * error;
  }
  EXPECT_NEAR (sum / 2001, 0.0, 0.005);
  EXPECT_NEAR (std::sqrt (sum2 / 2001), 0.05, 0.005);
}

// ---------------------------------------------------------------- determinism
TEST (SimulatorDeterminism, SameSeedGivesIdenticalPairs)
{
  sim::SimulatorConfig config;
  config.seed = 77;
  const sim::ScanPairSimulator a (config), b (config);
  const auto first = a.simulateDataset (0, 4);
  const auto second = b.simulateDataset (0, 4);
  for (std::size_t k = 0; k < first.size (); ++k)
    EXPECT_TRUE (samePair (first[k], second[k])) << first[k].name;
  // Pair k does not depend on how many pairs are made or where the run starts.
  EXPECT_TRUE (samePair (a.simulate (3), first[3]));
  EXPECT_TRUE (samePair (a.simulateDataset (2, 2)[1], first[3]));
}

TEST (SimulatorDeterminism, DifferentSeedsOrIndicesGiveDifferentPairs)
{
  sim::SimulatorConfig config;
  config.seed = 77;
  const sim::ScanPairSimulator a (config);
  config.seed = 78;
  const sim::ScanPairSimulator b (config);
  const ScanPair pa = a.simulate (0), pb = b.simulate (0), pa1 = a.simulate (1);
  EXPECT_FALSE (pa.source.cols () == pb.source.cols () && pa.source == pb.source);
  EXPECT_FALSE (pa.source.cols () == pa1.source.cols () && pa.source == pa1.source);
}

TEST (SimulatorDeterminism, BeamCountChangesTheScansNotTheScene)
{
  sim::SimulatorConfig config;
  config.seed = 5;
  sim::PairSummary coarse_summary, fine_summary;
  sim::PairScene coarse_scene, fine_scene;
  sim::ScanPairSimulator (config).simulate (0, &coarse_summary, &coarse_scene);
  config.laser.beam_count = 1081;
  const ScanPair fine = sim::ScanPairSimulator (config).simulate (0, &fine_summary, &fine_scene);
  EXPECT_EQ (fine.sensor.beam_count, 1081);
  EXPECT_EQ (coarse_summary.scene, fine_summary.scene);
  EXPECT_EQ (coarse_summary.duration, fine_summary.duration);
  EXPECT_EQ (coarse_summary.moving_placed, fine_summary.moving_placed);
  EXPECT_EQ (coarse_scene.scene.getObjects ()[0].geometry.segments.size (),
             fine_scene.scene.getObjects ()[0].geometry.segments.size ());
}

// ---------------------------------------------------------------- ground truth
TEST (SimulatorTruth, ObjectMotionsMapSourcePointsOntoTargetSurfaces)
{
  for (sim::SceneType type : sim::concreteSceneTypes ())
    for (std::uint64_t seed : {11u, 12u}) {
      const sim::ScanPairSimulator simulator (noiseFreeConfig (type, seed));
      sim::PairScene truth;
      const ScanPair pair = simulator.simulate (0, nullptr, &truth);
      const auto target_world = truth.scene.at (truth.duration);
      for (const auto& object : pair.objects) {
        const sim::SceneObject* scene_object = truth.scene.findObject (object.id);
        ASSERT_NE (scene_object, nullptr);
        const sim::Geometry surface =
            scene_object->geometryAt (truth.duration).transformed (scene_object->poseAt (truth.duration));
        double nn_sum = 0.0;
        int nn_count = 0;
        for (Eigen::Index i = 0; i < pair.source.cols (); ++i) {
          if (pair.source_object[i] != object.id)
            continue;
          // On the object's surface at the target time (visible from the target or not) ...
          const Eigen::Vector2d q = object.T_target_source * pair.source.col (i);
          EXPECT_LT (distanceToSurface (truth.sensor_pose_target * q, surface), 1e-4)
              << sim::sceneTypeName (type) << " seed " << seed << " object " << object.id;
          // ... and next to the target scan's points of the same object where it is matched.
          if (pair.source_match[i] != pcl_crf::kNoMatch) {
            nn_sum += (pair.target.col (pair.source_match[i]) - q).norm ();
            ++nn_count;
          }
        }
        if (nn_count > 0) {
          EXPECT_LT (nn_sum / nn_count, 0.15) << sim::sceneTypeName (type) << " object " << object.id;
        }
      }
    }
}

TEST (SimulatorTruth, MatchesFollowTheAssociationRule)
{
  sim::SimulatorConfig config;
  config.seed = 21;
  const sim::ScanPairSimulator simulator (config);
  for (std::size_t k = 0; k < 6; ++k) {
    const ScanPair pair = simulator.simulate (k);
    int matched = 0;
    for (Eigen::Index i = 0; i < pair.source.cols (); ++i) {
      const int id = pair.source_object[i];
      const Eigen::Vector2d q = pair.objects[pair.objectIndex (id)].T_target_source * pair.source.col (i);
      const double tolerance = sim::matchTolerance (q.norm (), pair.sensor.angle_increment, config.laser.range_noise);
      double nearest = std::numeric_limits<double>::infinity ();
      for (Eigen::Index j = 0; j < pair.target.cols (); ++j)
        if (pair.target_object[j] == id)
          nearest = std::min (nearest, (pair.target.col (j) - q).norm ());
      const int m = pair.source_match[i];
      if (m == pcl_crf::kNoMatch) {
        EXPECT_GT (nearest, tolerance);
        continue;
      }
      ++matched;
      EXPECT_EQ (pair.target_object[m], id);
      EXPECT_LE ((pair.target.col (m) - q).norm (), tolerance);
      EXPECT_NEAR ((pair.target.col (m) - q).norm (), nearest, 1e-12);
    }
    EXPECT_GT (matched, pair.source.cols () / 3) << pair.name;
  }
  EXPECT_NEAR (sim::matchTolerance (10.0, 0.01, 0.01), 0.2 + 0.03 + 0.02, 1e-15);
}

TEST (SimulatorTruth, OdometryIsTheTrueMotionPlusNoise)
{
  sim::SimulatorConfig config = noiseFreeConfig (sim::SceneType::Static, 3);
  config.odometry_noise.setZero ();
  config.ego_yaw_rate = 0.2;
  sim::PairScene truth;
  const ScanPair exact = sim::ScanPairSimulator (config).simulate (0, nullptr, &truth);
  const pcl_crf::Rigid2d motion = truth.sensor_pose_source.inverse () * truth.sensor_pose_target;
  EXPECT_LT ((exact.odometry.T_source_target.matrix () - motion.matrix ()).norm (), 1e-12);
  // The static world moves by the inverse of the sensor motion.
  const auto& world = exact.objects[exact.objectIndex (exact.staticObjectId ())];
  EXPECT_LT ((world.T_target_source.matrix () - motion.inverse ().matrix ()).norm (), 1e-12);
  EXPECT_GT (motion.translation ().x (), 1.9);  // forward travel of 2..4 m
  // The scans are as far apart in time as 10 m/s takes to drive it (the yaw bends the path).
  EXPECT_GT (exact.odometry.interval, 0.2);
  EXPECT_LT (exact.odometry.interval, 0.4);
  EXPECT_NEAR (exact.odometry.interval * config.ego_speed, motion.translation ().norm (), 0.01);
  EXPECT_NEAR (exact.odometry.covariance (0, 0), 1e-6, 1e-18);  // variance floor
  EXPECT_EQ (exact.odometry.covariance (0, 1), 0.0);

  config.odometry_noise = Eigen::Vector3d (0.2, 0.1, 0.05);
  const ScanPair noisy = sim::ScanPairSimulator (config).simulate (0);
  EXPECT_NEAR (noisy.odometry.covariance (0, 0), 0.04, 1e-15);
  EXPECT_NEAR (noisy.odometry.covariance (2, 2), 0.0025, 1e-15);
  EXPECT_GT ((noisy.odometry.T_source_target.matrix () - motion.matrix ()).norm (), 1e-6);
}

TEST (SimulatorTruth, ConsecutiveSpacingIsOneScanPeriod)
{
  sim::SimulatorConfig config;
  config.spacing = sim::ScanSpacing::Consecutive;
  config.scan_rate = 75.0;
  config.odometry_noise.setZero ();
  sim::PairSummary summary;
  const ScanPair pair = sim::ScanPairSimulator (config).simulate (4, &summary);
  EXPECT_NEAR (summary.duration, 1.0 / 75.0, 1e-15);
  EXPECT_EQ (pair.odometry.interval, summary.duration);
  EXPECT_NEAR (pair.odometry.T_source_target.translation ().x (), 10.0 / 75.0, 1e-9);
  // Almost everything is seen again after 13 cm of travel.
  EXPECT_GT (summary.matched, 0.8 * summary.source_points);
}

// ---------------------------------------------------------------- datasets
TEST (SimulatorDataset, PairsPassValidationAndRoundTripThroughFiles)
{
  sim::SimulatorConfig config;
  config.seed = 9;
  config.laser.beam_count = 181;
  const sim::ScanPairSimulator simulator (config);
  const auto pairs = simulator.simulateDataset (0, 7);
  for (const auto& pair : pairs) {
    EXPECT_NO_THROW (pcl_crf::validateScanPair (pair, pair.name));
    EXPECT_TRUE (pair.hasTruth ());
    EXPECT_EQ (pair.objects.front ().id, 0);
    EXPECT_EQ (pair.objects.front ().kind, "world");
    for (std::size_t k = 1; k < pair.objects.size (); ++k) {
      EXPECT_EQ (pair.objects[k].id, static_cast<int> (k));
      EXPECT_TRUE (pair.objects[k].kind == "car" || pair.objects[k].kind == "pedestrian" ||
                   pair.objects[k].kind == "cyclist");
      const bool carried = std::count (pair.source_object.begin (), pair.source_object.end (), k) +
                               std::count (pair.target_object.begin (), pair.target_object.end (), k) > 0;
      EXPECT_TRUE (carried) << "object " << k << " of " << pair.name << " has no point";
    }
  }
  const auto dir = freshTempDir ("sim_roundtrip");
  pcl_crf::saveDataset (pairs, dir.string ());
  const auto loaded = pcl_crf::loadDataset (dir.string ());
  ASSERT_EQ (loaded.size (), pairs.size ());
  for (std::size_t k = 0; k < pairs.size (); ++k)
    EXPECT_TRUE (samePair (loaded[k], pairs[k], 1e-15)) << pairs[k].name;  // coordinates are stored exactly
  std::filesystem::remove_all (dir);
}

// ---------------------------------------------------------------- scenes
TEST (SimulatorScenes, OutlineCarOverlapsItselfInTheWorldFrame)
{
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    sim::SimulatorConfig config = noiseFreeConfig (sim::SceneType::Outline, seed);
    config.moving_count = 1;
    sim::PairSummary summary;
    const ScanPair pair = sim::ScanPairSimulator (config).simulate (0, &summary);
    ASSERT_EQ (summary.scene, sim::SceneType::Outline);
    if (pair.objects.size () < 2)
      continue;
    const auto& world = pair.objects[pair.objectIndex (0)];
    const auto& car = pair.objects[pair.objectIndex (1)];
    EXPECT_EQ (car.kind, "car");
    // It really moves: its motion differs from the static world's (by v * dt, 0.6-2.4 m).
    const pcl_crf::Rigid2d relative = world.T_target_source.inverse () * car.T_target_source;
    EXPECT_GT (relative.translation ().norm (), 0.5);
    // Yet, compensated for the ego motion only, its source points fall on its
    // target outline (the polyline through consecutive target points of the car).
    int near = 0, total = 0;
    for (Eigen::Index i = 0; i < pair.source.cols (); ++i) {
      if (pair.source_object[i] != 1)
        continue;
      const Eigen::Vector2d q = world.T_target_source * pair.source.col (i);
      if (std::atan2 (q.y (), q.x ()) < pair.sensor.angle_min ||
          std::atan2 (q.y (), q.x ()) > pair.sensor.angleMax ())
        continue;  // behind the sensor at the target time: cannot overlap
      double nearest = std::numeric_limits<double>::infinity ();
      for (Eigen::Index j = 0; j < pair.target.cols (); ++j) {
        if (pair.target_object[j] != 1)
          continue;
        nearest = std::min (nearest, (pair.target.col (j) - q).norm ());
        if (j + 1 < pair.target.cols () && pair.target_object[j + 1] == 1 &&
            (pair.target.col (j + 1) - pair.target.col (j)).norm () < 1.0)
          nearest = std::min (nearest, distanceToSegment (q, {pair.target.col (j), pair.target.col (j + 1)}));
      }
      near += nearest < 0.05 ? 1 : 0;
      ++total;
    }
    ASSERT_GT (total, 10);
    EXPECT_GT (near, 0.8 * total) << "seed " << seed;
    ++checked;
  }
  EXPECT_GE (checked, 3);
}

TEST (SimulatorScenes, StaticSceneHasOnlyTheWorld)
{
  sim::SimulatorConfig config;
  config.scene = sim::SceneType::Static;
  const auto pairs = sim::ScanPairSimulator (config).simulateDataset (0, 3);
  for (const auto& pair : pairs) {
    ASSERT_EQ (pair.objects.size (), 1u);
    EXPECT_TRUE (pair.objects[0].is_static);
    EXPECT_EQ (pair.objects[0].kind, "world");
    EXPECT_TRUE (std::all_of (pair.source_object.begin (), pair.source_object.end (), [] (int id) { return id == 0; }));
  }
}

TEST (SimulatorScenes, EachSceneTypeMovesItsObjectsAsDescribed)
{
  const double ego_speed = 10.0;
  for (sim::SceneType type : {sim::SceneType::Crossing, sim::SceneType::Overtaking, sim::SceneType::Opposite,
                              sim::SceneType::Pedestrians}) {
    sim::SimulatorConfig config;
    config.scene = type;
    config.moving_count = 3;
    config.seed = 31;
    int visible = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      sim::PairSummary summary;
      sim::PairScene truth;
      const ScanPair pair = sim::ScanPairSimulator (config).simulate (k, &summary, &truth);
      EXPECT_EQ (summary.scene, type);
      EXPECT_LE (summary.moving_placed, 3);
      visible += summary.moving_visible;
      for (const auto& object : truth.scene.getObjects ()) {
        if (object.is_static)
          continue;
        const double heading = pcl_crf::rotationAngle (object.trajectory.start);
        if (type == sim::SceneType::Crossing) {
          EXPECT_NEAR (std::abs (heading), kPi / 2, 0.2);
        }
        if (type == sim::SceneType::Overtaking) {
          EXPECT_EQ (object.kind, "car");
          EXPECT_GT (object.trajectory.speed, ego_speed);
        }
        if (type == sim::SceneType::Opposite) {
          EXPECT_EQ (object.kind, "car");
          EXPECT_GT (std::abs (heading), kPi - 0.05);
        }
        if (type == sim::SceneType::Pedestrians) {
          EXPECT_EQ (object.kind, "pedestrian");
        }
      }
      (void) pair;
    }
    EXPECT_GE (visible, 3) << sim::sceneTypeName (type);
  }
}

TEST (SimulatorScenes, LeggedPedestriansSwingTheirLegs)
{
  sim::SceneObject walker;
  walker.id = 1;
  walker.kind = "pedestrian";
  walker.has_legs = true;
  walker.legs.amplitude = 0.25;
  walker.legs.frequency = 1.0;
  const auto g0 = walker.geometryAt (0.0), g1 = walker.geometryAt (0.25);
  ASSERT_EQ (g0.circles.size (), 2u);
  EXPECT_NEAR (g0.circles[0].centre.x (), 0.0, 1e-12);
  EXPECT_NEAR (g1.circles[0].centre.x (), 0.25, 1e-12);
  EXPECT_NEAR (g1.circles[1].centre.x (), -0.25, 1e-12);
}

// ---------------------------------------------------------------- configuration
TEST (SimulatorConfig, RejectsBadSettings)
{
  EXPECT_NO_THROW (sim::validateSimulatorConfig (sim::SimulatorConfig ()));
  auto rejects = [] (auto change) {
    sim::SimulatorConfig config;
    change (config);
    EXPECT_THROW (sim::validateSimulatorConfig (config), sim::SimulationError);
    EXPECT_THROW (sim::ScanPairSimulator simulator (config), sim::SimulationError);
  };
  rejects ([] (sim::SimulatorConfig& c) { c.laser.beam_count = 1; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.beam_count = 0; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.range_noise = -0.01; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.dropout_probability = 1.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.dropout_probability = -0.1; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.field_of_view = 0.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.field_of_view = 7.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.range_max = 0.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.range_max = std::nan (""); });
  rejects ([] (sim::SimulatorConfig& c) { c.ego_speed = 0.0; });  // travel spacing needs motion
  rejects ([] (sim::SimulatorConfig& c) { c.ego_speed = -1.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.travel_min = 3.0, c.travel_max = 2.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.spacing = sim::ScanSpacing::Consecutive, c.scan_rate = 0.0; });
  // Bounds that keep one pair's time and memory bounded (each used to hang the simulator).
  rejects ([] (sim::SimulatorConfig& c) { c.laser.beam_count = sim::kMaxSimulatedBeams + 1; });
  rejects ([] (sim::SimulatorConfig& c) { c.laser.range_max = 1e9; });
  rejects ([] (sim::SimulatorConfig& c) { c.travel_min = 1e9, c.travel_max = 1e9; });
  rejects ([] (sim::SimulatorConfig& c) { c.spacing = sim::ScanSpacing::Consecutive, c.scan_rate = 1e-300; });
  rejects ([] (sim::SimulatorConfig& c) { c.spacing = sim::ScanSpacing::Consecutive, c.ego_speed = 1e9; });
  rejects ([] (sim::SimulatorConfig& c) { c.moving_count = -2; });
  rejects ([] (sim::SimulatorConfig& c) { c.scene = sim::SceneType::Static, c.moving_count = 2; });
  rejects ([] (sim::SimulatorConfig& c) { c.odometry_noise.y () = -0.1; });
  rejects ([] (sim::SimulatorConfig& c) { c.traffic.legged_pedestrian_fraction = 1.5; });
  // Silent nonsense before: points 685 m away from a 30 m laser, and no mover at all.
  rejects ([] (sim::SimulatorConfig& c) { c.laser.range_noise = c.laser.range_max; });
  rejects ([] (sim::SimulatorConfig& c) { c.traffic.object_speed = 1e300; });
  rejects ([] (sim::SimulatorConfig& c) { c.name_prefix = "a/b"; });
  // Objects labelled moving with the static world's motion: standing, or scans 1e-300 s apart.
  rejects ([] (sim::SimulatorConfig& c) { c.traffic.object_speed = 0.0; });
  rejects ([] (sim::SimulatorConfig& c) { c.traffic.object_speed = 1e-300; });
  rejects ([] (sim::SimulatorConfig& c) { c.ego_speed = 1e300; });
  rejects ([] (sim::SimulatorConfig& c) { c.travel_min = 1e-300, c.travel_max = 1e-300; });
  rejects ([] (sim::SimulatorConfig& c) { c.spacing = sim::ScanSpacing::Consecutive, c.scan_rate = 1e300; });
  sim::SimulatorConfig slow_and_fast;
  slow_and_fast.traffic.object_speed = sim::kMinSimulatedObjectSpeed;
  slow_and_fast.travel_min = slow_and_fast.travel_max = 1.01 * sim::kMinSimulatedScanInterval * slow_and_fast.ego_speed;
  EXPECT_NO_THROW (sim::validateSimulatorConfig (slow_and_fast));
  // A standing sensor is fine with consecutive scans.
  sim::SimulatorConfig standing;
  standing.ego_speed = 0.0;
  standing.spacing = sim::ScanSpacing::Consecutive;
  EXPECT_NO_THROW (sim::validateSimulatorConfig (standing));
  // setConfig keeps the previous configuration on failure.
  sim::ScanPairSimulator simulator;
  sim::SimulatorConfig bad;
  bad.laser.beam_count = 1;
  EXPECT_THROW (simulator.setConfig (bad), sim::SimulationError);
  EXPECT_EQ (simulator.getConfig ().laser.beam_count, 361);

  sim::SceneType type = sim::SceneType::Static;
  EXPECT_FALSE (sim::parseSceneType ("highway", type));
  EXPECT_EQ (type, sim::SceneType::Static);
  for (sim::SceneType t : sim::concreteSceneTypes ()) {
    EXPECT_TRUE (sim::parseSceneType (sim::sceneTypeName (t), type));
    EXPECT_EQ (type, t);
  }
  EXPECT_EQ (sim::ScanPairSimulator ().pairName (7), "pair_0007");
  EXPECT_EQ (sim::ScanPairSimulator ().pairName (12345), "pair_12345");
}

}  // namespace

namespace {

TEST (SimulatorNoReturnPoints, KeepEveryBeamAndAddOnlyUnmatchedWorldPointsAtTheMaximumRange)
{
  sim::SimulatorConfig config;
  config.seed = 7;
  const ScanPair plain = sim::ScanPairSimulator (config).simulate (3);
  config.laser.no_return_points = true;
  const ScanPair kept = sim::ScanPairSimulator (config).simulate (3);
  ASSERT_EQ (kept.source.cols (), config.laser.beam_count);
  ASSERT_EQ (kept.target.cols (), config.laser.beam_count);
  ASSERT_LT (plain.source.cols (), kept.source.cols ());  // some beams saw nothing
  pcl_crf::validateScanPair (kept, "no-return points");
  // The plain scans' points in order, then the added ones: unmatched world points at
  // the maximum range in their beam's direction.
  std::vector<int> position;  // of each plain source point in the kept scan
  for (Eigen::Index i = 0, k = 0; i < kept.source.cols (); ++i) {
    const bool original = k < plain.source.cols () && kept.source.col (i) == plain.source.col (k);
    if (original) {
      EXPECT_EQ (kept.source_object[i], plain.source_object[k]);
      position.push_back (static_cast<int> (i));
      ++k;
      continue;
    }
    EXPECT_NEAR (kept.source.col (i).norm (), config.laser.range_max, 1e-5 * config.laser.range_max) << i;
    const pcl_crf::SensorInfo sensor = kept.sensor;
    EXPECT_NEAR (std::atan2 (kept.source (1, i), kept.source (0, i)), sensor.angle_min + i * sensor.angle_increment,
                 1e-6)
        << i;
    EXPECT_EQ (kept.source_object[i], 0) << i;
    EXPECT_EQ (kept.source_match[i], pcl_crf::kNoMatch) << i;
  }
  ASSERT_EQ (position.size (), static_cast<std::size_t> (plain.source.cols ()));
  for (std::size_t k = 0; k < position.size (); ++k) {
    const int j = plain.source_match[k];
    const int j_kept = kept.source_match[static_cast<std::size_t> (position[k])];
    if (j == pcl_crf::kNoMatch) {
      EXPECT_EQ (j_kept, pcl_crf::kNoMatch) << k;
    }
    else {
      ASSERT_GE (j_kept, 0) << k;
      EXPECT_EQ (kept.target.col (j_kept), plain.target.col (j)) << k;
    }
  }
  EXPECT_EQ (kept.objects.size (), plain.objects.size ());
  EXPECT_TRUE (kept.odometry.T_source_target.isApprox (plain.odometry.T_source_target, 0.0));
}

}  // namespace
