#include "scan_views.h"

namespace pcl_crf {
namespace joint {
namespace detail {

ScanViews::ScanViews (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                      const matching::SegmentMotionParameters& parameters, const SensorInfo& sensor)
  : source_ (source), target_ (target), parameters_ (parameters), sensor_ (sensor)
{
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
                                   matching::BeamGaps::MissingReturns);
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

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
