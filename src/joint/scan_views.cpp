#include "scan_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace pcl_crf {
namespace joint {
namespace detail {

ScanViews::ScanViews (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                      const matching::SegmentMotionParameters& parameters, const SensorInfo& sensor)
  : source_ (source), target_ (target), parameters_ (parameters), sensor_ (sensor)
{
  const std::string problem = matching::segmentParametersProblem (parameters);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::joint] the segment parameters: " + problem);
}

const std::vector<matching::ScanSegment>&
ScanViews::sourceSegments () const
{
  return segments (source_segments_, source_);
}

const std::vector<matching::ScanSegment>&
ScanViews::targetSegments () const
{
  return segments (target_segments_, target_);
}

const SensorView&
ScanViews::sourceView () const
{
  return view (source_view_, source_);
}

const SensorView&
ScanViews::targetView () const
{
  return view (target_view_, target_);
}

const KnnIndex&
ScanViews::targetPoints () const
{
  if (!target_points_)
    target_points_.emplace (target_);
  return *target_points_;
}

const std::vector<matching::ScanSegment>&
ScanViews::segments (std::optional<std::vector<matching::ScanSegment>>& cache, const Eigen::Matrix2Xd& scan) const
{
  if (!cache)
    cache = matching::segmentScan (scan, parameters_.breakpoint_angle, parameters_.range_noise,
                                   matching::BeamGaps::MissingReturns, parameters_.max_missing_returns);
  return *cache;
}

const SensorView&
ScanViews::view (std::optional<SensorView>& cache, const Eigen::Matrix2Xd& scan) const
{
  if (!cache) {
    SensorView seen{matching::makeRangeProfile (scan, sensor_), {}};
    seen.breakpoint = matching::breakpointDistance (seen.profile, parameters_.breakpoint_angle, parameters_.range_noise);
    cache = std::move (seen);
  }
  return *cache;
}

std::vector<bool>
grazedPoints (const Eigen::Matrix2Xd& points, double breakpoint_angle)
{
  const Eigen::Index n = points.cols ();
  const double least_sine = std::sin (breakpoint_angle);
  std::vector<bool> grazed (static_cast<std::size_t> (n), false);
  for (Eigen::Index k = 0; k < n && n > 1; ++k) {
    const Eigen::Vector2d along = points.col (std::min (k + 1, n - 1)) - points.col (std::max<Eigen::Index> (k - 1, 0));
    const Eigen::Vector2d& beam = points.col (k);
    const double scale = along.norm () * beam.norm ();
    grazed[k] = scale > 0.0 && std::abs (along.x () * beam.y () - along.y () * beam.x ()) < least_sine * scale;
  }
  return grazed;
}

bool
sawThrough (const SensorView& seen, const Eigen::Vector2d& point, SeenThrough test)
{
  switch (test) {
  case SeenThrough::Firmly:
    return matching::seesThroughFirmly (seen.profile, point, seen.breakpoint);
  case SeenThrough::ToAReturn:
    return matching::seesThroughToAReturn (seen.profile, point, seen.breakpoint);
  case SeenThrough::NotAsked:
    break;
  }
  return false;
}

TargetPlacement
placeInTarget (Eigen::Matrix2Xd points, const std::vector<double>& radii_squared, const ScanViews& views,
               SeenThrough test)
{
  TargetPlacement p{std::move (points), {}, {}, {}, {}};
  p.nearest = views.targetPoints ().search (p.points, 1);
  const SensorView& seen = views.targetView ();
  const std::vector<bool> grazed = grazedPoints (p.points, views.parameters ().breakpoint_angle);
  for (Eigen::Index k = 0; k < p.points.cols (); ++k) {
    const Eigen::Vector2d point = p.points.col (k);
    p.in_view.push_back (!grazed[k] && matching::inFieldOfView (seen.profile, point));
    p.explained.push_back (p.nearest.squared_distances (0, k) <= radii_squared[k]);
    p.seen_through.push_back (sawThrough (seen, point, test));
  }
  return p;
}

std::vector<double>
squaredOverlapRadii (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
                     const std::vector<int>& members, const matching::SegmentMotionParameters& parameters)
{
  std::vector<double> radii;
  for (const int i : members) {
    const double r = matching::overlapRadius (parameters, matching::pointSpacing (source, i, segment.begin, segment.end));
    radii.push_back (r * r);
  }
  return radii;
}

std::vector<double>
squaredOverlapRadii (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
                     const matching::SegmentMotionParameters& parameters)
{
  std::vector<int> all (static_cast<std::size_t> (segment.size ()));
  std::iota (all.begin (), all.end (), segment.begin);
  return squaredOverlapRadii (source, segment, all, parameters);
}

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
