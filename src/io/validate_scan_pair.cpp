#include <pcl_crf/io/dataset_io.h>

#include <cmath>
#include <set>
#include <sstream>

namespace pcl_crf {
namespace {

[[noreturn]] void
fail (const std::string& where, const std::string& what)
{
  throw DatasetError (where + ": " + what);
}

void
checkFiniteCloud (const Eigen::Matrix2Xd& cloud, const std::string& name, const std::string& where)
{
  if (cloud.cols () == 0)
    fail (where, name + " scan is empty (a pair needs at least one point in each scan)");
  const std::string problem = scanPointsProblem (cloud, name);
  if (!problem.empty ())
    fail (where, problem);
}

void
checkSensor (const SensorInfo& sensor, const std::string& where)
{
  if (sensor.beam_count <= 0)
    fail (where, "sensor beam count must be positive");
  if (sensor.beam_count > kMaxBeamCount)
    fail (where, "sensor beam count " + std::to_string (sensor.beam_count) + " exceeds " +
                     std::to_string (kMaxBeamCount) + " (no 2D laser has that many beams)");
  if (!std::isfinite (sensor.angle_min) || !std::isfinite (sensor.angle_increment) ||
      !std::isfinite (sensor.range_max))
    fail (where, "sensor angles and range must be finite numbers");
  if (sensor.angle_increment <= 0.0)
    fail (where, "sensor angle increment must be positive (beams in counter-clockwise order)");
  if (sensor.range_max <= 0.0)
    fail (where, "sensor maximum range must be positive");
}

void
checkOdometry (const Odometry& odometry, const std::string& where)
{
  const std::string problem = odometryProblem (odometry);
  if (!problem.empty ())
    fail (where, problem);
  if ((odometry.covariance.diagonal ().array () <= 0.0).any ())
    fail (where, "odometry covariance must have positive variances on its diagonal");
}

std::set<int>
checkObjects (const std::vector<ObjectTruth>& objects, const std::string& where)
{
  std::set<int> ids;
  int static_count = 0;
  for (const auto& object : objects) {
    if (object.id < 0)
      fail (where, "object id " + std::to_string (object.id) + " is negative");
    if (!ids.insert (object.id).second)
      fail (where, "object id " + std::to_string (object.id) + " appears twice");
    if (!object.T_target_source.matrix ().allFinite ())
      fail (where, "object " + std::to_string (object.id) + " has a NaN or infinite motion");
    if (object.T_target_source.translation ().cwiseAbs ().maxCoeff () > kMaxCoordinate)
      fail (where, "object " + std::to_string (object.id) + " moves beyond 1e18 m");
    static_count += object.is_static ? 1 : 0;
  }
  if (static_count != 1)
    fail (where, "exactly one object must be the static world, found " + std::to_string (static_count));
  return ids;
}

void
checkLabels (const std::vector<int>& labels, Eigen::Index count, const std::set<int>& ids,
             const std::string& name, const std::string& where)
{
  if (labels.size () != static_cast<std::size_t> (count))
    fail (where, name + " has " + std::to_string (labels.size ()) + " object labels for " +
                     std::to_string (count) + " points");
  for (std::size_t i = 0; i < labels.size (); ++i)
    if (ids.count (labels[i]) == 0)
      fail (where, name + " point " + std::to_string (i) + " has object id " +
                       std::to_string (labels[i]) + " that no object line declares");
}

void
checkMatches (const ScanPair& pair, const std::string& where)
{
  const auto n = static_cast<std::size_t> (pair.source.cols ());
  if (pair.source_match.size () != n)
    fail (where, "source has " + std::to_string (pair.source_match.size ()) + " matches for " +
                     std::to_string (n) + " points");
  for (std::size_t i = 0; i < n; ++i) {
    const int j = pair.source_match[i];
    if (j != kNoMatch && (j < 0 || j >= pair.target.cols ()))
      fail (where, "source point " + std::to_string (i) + " matches target index " +
                       std::to_string (j) + ", out of range [0, " +
                       std::to_string (pair.target.cols ()) + ") and not -1");
  }
}

}  // namespace

void
validateScanPair (const ScanPair& pair, const std::string& where)
{
  checkSensor (pair.sensor, where);
  checkFiniteCloud (pair.source, "source", where);
  checkFiniteCloud (pair.target, "target", where);
  if (pair.source.cols () > pair.sensor.beam_count || pair.target.cols () > pair.sensor.beam_count)
    fail (where, "a scan holds more points than the sensor has beams (" +
                     std::to_string (pair.sensor.beam_count) + ")");
  checkOdometry (pair.odometry, where);
  const std::set<int> ids = checkObjects (pair.objects, where);
  checkLabels (pair.source_object, pair.source.cols (), ids, "source", where);
  checkLabels (pair.target_object, pair.target.cols (), ids, "target", where);
  checkMatches (pair, where);
}

}  // namespace pcl_crf
