#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcl_crf {
namespace {

void
checkOptions (const LogPairOptions& options)
{
  const OdometryNoiseModel& n = options.noise;
  if (options.step == 0)
    throw LogError ("[pcl_crf::makeLogPair] the scan step must be at least 1");
  if (!(n.translation_per_metre >= 0.0) || !(n.rotation_per_radian >= 0.0) || !(n.rotation_per_metre >= 0.0) ||
      !(n.min_translation_std > 0.0) || !(n.min_rotation_std > 0.0) ||
      !(options.no_odometry_translation_std > 0.0) || !(options.no_odometry_rotation_std > 0.0))
    throw LogError ("[pcl_crf::makeLogPair] noise-model factors must not be negative and the minimum "
                    "standard deviations must be positive");
  if (!(options.range_noise >= 0.0) || !(options.footprint_margin >= 0.0) || !(options.still_tolerance >= 0.0))
    throw LogError ("[pcl_crf::makeLogPair] the range noise, footprint margin and still tolerance must not be "
                    "negative");
}

Odometry
composeOdometry (const LaserLog& log, std::size_t k, const LogPairOptions& options)
{
  Odometry odometry;
  odometry.covariance.setZero ();
  for (std::size_t j = k + 1; j <= k + options.step; ++j) {
    const LaserScanRecord& scan = log.scans[j];
    if (!scan.has_odometry_step) {
      const double st = options.no_odometry_translation_std, sr = options.no_odometry_rotation_std;
      odometry.T_source_target = Rigid2d::Identity ();
      odometry.covariance = Eigen::Vector3d (st * st, st * st, sr * sr).asDiagonal ();
      return odometry;
    }
    odometry.T_source_target = odometry.T_source_target * scan.odometry_step;
    odometry.covariance += options.noise.covariance (scan.odometry_step);
  }
  return odometry;
}

/** true when the sensor-frame point p lies in the object's grown footprint. */
bool
insideFootprint (const Eigen::Vector2d& p, const Rigid2d& T_object_sensor, const Eigen::Vector2d& half_extent)
{
  const Eigen::Vector2d q = T_object_sensor * p;
  return std::abs (q.x ()) <= half_extent.x () && std::abs (q.y ()) <= half_extent.y ();
}

/** true when no corner of the footprint (object frame, \a half_extent) moves \a tolerance
 *  or farther between \a T_object and \a T_world: the displacement (R_o − R_w) p + t_o − t_w
 *  is affine in p, so its norm peaks at a corner of the rectangle. */
bool
standsStill (const Rigid2d& T_object, const Rigid2d& T_world, const Rigid2d& T_source_object,
             const Eigen::Vector2d& half_extent, double tolerance)
{
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) {
      const Eigen::Vector2d corner = T_source_object * Eigen::Vector2d (sx * half_extent.x (), sy * half_extent.y ());
      if ((T_object * corner - T_world * corner).norm () >= tolerance)
        return false;
    }
  return true;
}

struct ObjectAtPair
{
  int id;
  Rigid2d T_object_source;  // object frame <- source sensor frame
  Rigid2d T_object_target;
  Eigen::Vector2d half_extent;
};

std::vector<int>
labelScan (const Eigen::Matrix2Xd& points, const std::vector<ObjectAtPair>& objects, bool source)
{
  std::vector<int> labels (points.cols (), 0);
  for (Eigen::Index i = 0; i < points.cols (); ++i)
    for (const auto& object : objects)
      if (insideFootprint (points.col (i), source ? object.T_object_source : object.T_object_target,
                           object.half_extent)) {
        labels[i] = object.id;
        break;
      }
  return labels;
}

void
addTruth (const LaserLog& log, const LaserScanRecord& s, const LaserScanRecord& t, const LogPairOptions& options,
          ScanPair& pair)
{
  ObjectTruth world;
  world.id = 0;
  world.is_static = true;
  world.kind = "world";
  world.T_target_source = t.pose.inverse () * s.pose;
  pair.objects.push_back (world);
  std::vector<ObjectAtPair> tracked;
  for (std::size_t k = 0; k < log.objects.size (); ++k) {
    const TrackedObject& object = log.objects[k];
    Rigid2d O_s, O_t;
    if (!object.track.interpolate (s.stamp, O_s) || !object.track.interpolate (t.stamp, O_t))
      continue;
    ObjectTruth truth;
    truth.id = static_cast<int> (k) + 1;
    truth.kind = object.kind;
    truth.T_target_source = t.pose.inverse () * O_t * O_s.inverse () * s.pose;
    const Eigen::Vector2d margin = Eigen::Vector2d::Constant (options.footprint_margin);
    const ObjectAtPair at{truth.id, O_s.inverse () * s.pose, O_t.inverse () * t.pose, object.half_extent + margin};
    if (standsStill (truth.T_target_source, world.T_target_source, at.T_object_source.inverse (), at.half_extent,
                     options.still_tolerance))
      continue;  // a parked car: part of the static world
    pair.objects.push_back (truth);
    tracked.push_back (at);
  }
  if (!options.label_points)
    return;
  pair.source_object = labelScan (pair.source, tracked, true);
  pair.target_object = labelScan (pair.target, tracked, false);
  // Drop tracked objects that no point hit, as the simulator does.
  std::vector<ObjectTruth> kept;
  for (const auto& object : pair.objects)
    if (object.is_static || std::count (pair.source_object.begin (), pair.source_object.end (), object.id) > 0 ||
        std::count (pair.target_object.begin (), pair.target_object.end (), object.id) > 0)
      kept.push_back (object);
  pair.objects = kept;
  simulation::assignTrueMatches (pair, options.range_noise);
}

}  // namespace

Eigen::Matrix3d
OdometryNoiseModel::covariance (const Rigid2d& step) const
{
  const double d = step.translation ().norm ();
  const double turn = std::abs (rotationAngle (step));
  const double st = std::max (min_translation_std, translation_per_metre * d);
  const double sr = std::max (min_rotation_std, rotation_per_radian * turn + rotation_per_metre * d);
  return Eigen::Vector3d (st * st, st * st, sr * sr).asDiagonal ();
}

std::size_t
logPairCount (std::size_t scan_count, std::size_t step)
{
  return step == 0 || scan_count <= step ? 0 : scan_count - step;
}

ScanPair
makeLogPair (const LaserLog& log, std::size_t k, const LogPairOptions& options)
{
  checkOptions (options);
  if (k + options.step >= log.scans.size ())
    throw LogError (log.path + ": no scan pair (" + std::to_string (k) + ", " + std::to_string (k + options.step) +
                    "): the log has " + std::to_string (log.scans.size ()) + " scans");
  const LaserScanRecord& s = log.scans[k];
  const LaserScanRecord& t = log.scans[k + options.step];
  const auto where = [&] () { return log.path + ": scans " + std::to_string (k) + " and " +
                                     std::to_string (k + options.step); };
  if (s.sensor.beam_count != t.sensor.beam_count ||
      std::abs (s.sensor.angle_increment - t.sensor.angle_increment) > 1e-9 ||
      std::abs (s.sensor.angle_min - t.sensor.angle_min) > 1e-9)
    throw LogError (where () + " have different beam layouts");
  if (s.points.cols () == 0 || t.points.cols () == 0)
    throw LogError (where () + ": a scan has no valid reading");
  if (options.label_points && !(s.has_pose && t.has_pose))
    throw LogError (where () + ": labels need reference poses for both scans");

  ScanPair pair;
  char name[32];
  std::snprintf (name, sizeof (name), "scan_%06zu", k);
  pair.name = name;
  pair.sensor = s.sensor;
  pair.source = s.points;
  pair.target = t.points;
  pair.odometry = composeOdometry (log, k, options);
  if (t.stamp > s.stamp)  // otherwise unknown
    pair.odometry.interval = t.stamp - s.stamp;
  if (s.has_pose && t.has_pose)
    addTruth (log, s, t, options, pair);
  return pair;
}

bool
referenceEgoMotion (const ScanPair& pair, Rigid2d& T_source_target)
{
  const int id = pair.staticObjectId ();
  if (id < 0)
    return false;
  T_source_target = pair.objects[pair.objectIndex (id)].T_target_source.inverse ();
  return true;
}

}  // namespace pcl_crf
