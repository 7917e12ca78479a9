#include <pcl_crf/simulation/laser_scanner.h>
#include <pcl_crf/core/decimal_text.h>

#include <cmath>
#include <limits>
#include <string>

namespace pcl_crf {
namespace simulation {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

}  // namespace

SensorInfo
LaserConfig::sensorInfo () const
{
  SensorInfo info;
  info.beam_count = beam_count;
  info.range_max = range_max;
  info.angle_min = -0.5 * field_of_view;
  const bool full_turn = field_of_view >= kTwoPi - 1e-9;
  const int intervals = full_turn ? beam_count : beam_count - 1;
  info.angle_increment = intervals > 0 ? field_of_view / intervals : 0.0;
  return info;
}

double
storedCoordinate (double value)
{
  // Mirrors pcl::io::savePCDFileASCII (precision 8) and the float parse on loading.
  const std::string text = formatGeneral (static_cast<double> (static_cast<float> (value)), 8);
  return static_cast<double> (parseDecimalFloat (text).value_or (std::numeric_limits<float>::quiet_NaN ()));
}

SimulatedScan
LaserScanner::scan (const SceneSnapshot& snapshot, const Rigid2d& sensor_pose, RandomStream& rng) const
{
  const SensorInfo info = config_.sensorInfo ();
  const double heading = rotationAngle (sensor_pose);
  std::vector<Eigen::Vector2d> points;
  SimulatedScan out;
  for (int i = 0; i < info.beam_count; ++i) {
    const double angle = info.angle_min + i * info.angle_increment;
    const double dropout_draw = rng.uniform ();
    const double noise_draw = rng.normal ();
    Ray ray;
    ray.origin = sensor_pose.translation ();
    ray.direction = Eigen::Vector2d (std::cos (heading + angle), std::sin (heading + angle));
    const RayHit hit = snapshot.castRay (ray, config_.range_max);
    if (!hit.valid () || dropout_draw < config_.dropout_probability)
      continue;
    const double range = hit.range + config_.range_noise * noise_draw;
    if (range <= 0.0)
      continue;
    points.emplace_back (storedCoordinate (range * std::cos (angle)), storedCoordinate (range * std::sin (angle)));
    out.object_ids.push_back (hit.object_id);
    out.beams.push_back (i);
  }
  out.points.resize (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    out.points.col (static_cast<Eigen::Index> (k)) = points[k];
  return out;
}

}  // namespace simulation
}  // namespace pcl_crf
