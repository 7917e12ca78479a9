#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/scan_segmentation.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <utility>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

void
validate (const SensorInfo& sensor, const ConsistencyParameters& p)
{
  if (sensor.beam_count < 1 || sensor.beam_count > kMaxBeamCount || !(sensor.angle_increment > 0.0) ||
      !std::isfinite (sensor.angle_increment) || !std::isfinite (sensor.angle_min))
    throw std::invalid_argument ("[pcl_crf::clustering::detectDynamicSegments] the sensor needs a beam_count in [1, " +
                                 std::to_string (kMaxBeamCount) + "], a finite angle_min and a finite angle_increment "
                                 "> 0");
  if (!(p.free_space_margin > 0.0) || p.beam_window < 0 || !(p.segment_break_distance > 0.0) ||
      !(p.min_dynamic_fraction >= 0.0 && p.min_dynamic_fraction < 1.0) || !(p.confidence_sigmas >= 0.0))
    throw std::invalid_argument ("[pcl_crf::clustering::detectDynamicSegments] invalid parameters: margin and "
                                 "break distance must be > 0, beam_window >= 0, min_dynamic_fraction in [0, 1), "
                                 "confidence_sigmas >= 0");
}

/** Beam index of a bearing, or −1 outside the field of view. The bearing is taken
 *  counter-clockwise from beam 0, within one turn: angle_min and angle_min + 2π name
 *  the same sensor. */
int
beamOf (const Eigen::Vector2d& p, const SensorInfo& sensor)
{
  constexpr double kTurn = 2.0 * M_PI;
  const double half_beam = 0.5 * sensor.angle_increment;
  double from_first = std::atan2 (p.y (), p.x ()) - sensor.angle_min;
  from_first -= kTurn * std::floor ((from_first + half_beam) / kTurn);  // into [−half a beam, a turn − half a beam)
  const double b = std::round (from_first / sensor.angle_increment);
  return b >= 0.0 && b < sensor.beam_count ? static_cast<int> (b) : -1;
}

/** The range of every beam of a scan, NaN where it has no return. */
std::vector<double>
rangeImage (const Eigen::Matrix2Xd& scan, const SensorInfo& sensor)
{
  std::vector<double> ranges (static_cast<std::size_t> (sensor.beam_count), std::numeric_limits<double>::quiet_NaN ());
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
  {
    const int b = beamOf (scan.col (i), sensor);
    if (b >= 0)
      ranges[b] = std::isnan (ranges[b]) ? scan.col (i).norm () : std::min (ranges[b], scan.col (i).norm ());
  }
  return ranges;
}

/** Nearest return among the beams b − w … b + w; NaN when none has one. */
double
nearestReturn (const std::vector<double>& ranges, int b, int window)
{
  double nearest = std::numeric_limits<double>::quiet_NaN ();
  for (int k = std::max (0, b - window); k <= std::min (static_cast<int> (ranges.size ()) - 1, b + window); ++k)
    if (!std::isnan (ranges[k]) && !(ranges[k] >= nearest))
      nearest = ranges[k];
  return nearest;
}

/** Standard deviations of the ego translation (largest axis) [m] and rotation [rad]. */
std::pair<double, double>
egoDeviations (const Eigen::Matrix3d* covariance)
{
  if (!covariance)
    return {0.0, 0.0};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xy (covariance->topLeftCorner<2, 2> ());
  return {std::sqrt (std::max (xy.eigenvalues ().maxCoeff (), 0.0)), std::sqrt (std::max ((*covariance) (2, 2), 0.0))};
}

}  // namespace

std::vector<bool>
freeSpaceViolations (const Eigen::Matrix2Xd& points, const Rigid2d& T_other_points, const Eigen::Matrix2Xd& other,
                     const SensorInfo& sensor, const ConsistencyParameters& parameters,
                     const Eigen::Matrix3d* covariance)
{
  validate (sensor, parameters);
  for (const std::string& problem : {scanPointsProblem (points, "the scan's"), scanPointsProblem (other, "the other scan's")})
    if (!problem.empty ())
      throw std::invalid_argument ("[pcl_crf::clustering::freeSpaceViolations] " + problem);
  if (!T_other_points.matrix ().allFinite () || !isRotation (T_other_points))
    throw std::invalid_argument ("[pcl_crf::clustering::freeSpaceViolations] the motion is not a finite rigid motion");
  if (covariance != nullptr && !covariance->allFinite ())
    throw std::invalid_argument ("[pcl_crf::clustering::freeSpaceViolations] the covariance has a NaN or infinite value");
  const std::vector<double> ranges = rangeImage (other, sensor);
  const auto [sigma_xy, sigma_theta] = egoDeviations (covariance);
  const double k = parameters.confidence_sigmas;
  const double margin = parameters.free_space_margin + k * sigma_xy;
  std::vector<bool> violates (static_cast<std::size_t> (points.cols ()), false);
  for (Eigen::Index i = 0; i < points.cols (); ++i)
  {
    const Eigen::Vector2d q = T_other_points * Eigen::Vector2d (points.col (i));
    const int b = beamOf (q, sensor);
    if (b < 0)
      continue;  // outside the other field of view: unknown, static
    const double range = q.norm ();
    const double bearing_sigma = sigma_theta + sigma_xy / std::max (range, 1e-3);
    const int window =
        parameters.beam_window + static_cast<int> (std::ceil (k * bearing_sigma / sensor.angle_increment));
    const double wall = nearestReturn (ranges, b, window);
    violates[i] = !std::isnan (wall) && range < wall - margin;
  }
  return violates;
}

std::vector<int>
detectDynamicSegments (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const SensorInfo& sensor,
                       const Rigid2d& T_target_source, const ConsistencyParameters& parameters,
                       const Eigen::Matrix3d* covariance)
{
  const std::vector<bool> dynamic =
      freeSpaceViolations (source, T_target_source, target, sensor, parameters, covariance);
  const std::vector<int> segment = segmentByDistance (source, parameters.segment_break_distance, 0);
  const int segment_count = segment.empty () ? 0 : segment.back () + 1;
  std::vector<int> votes (static_cast<std::size_t> (segment_count), 0), sizes (votes.size (), 0);
  for (std::size_t i = 0; i < segment.size (); ++i)
  {
    votes[segment[i]] += dynamic[i] ? 1 : 0;
    ++sizes[segment[i]];
  }
  std::vector<int> cluster_of_segment (votes.size (), 0);
  int next = 1;
  for (std::size_t s = 0; s < votes.size (); ++s)
    if (votes[s] > parameters.min_dynamic_fraction * sizes[s])
      cluster_of_segment[s] = next++;
  std::vector<int> clusters (segment.size ());
  for (std::size_t i = 0; i < segment.size (); ++i)
    clusters[i] = cluster_of_segment[segment[i]];
  return clusters;
}

}  // namespace clustering
}  // namespace pcl_crf
