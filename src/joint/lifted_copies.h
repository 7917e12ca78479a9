#pragma once
// Internal: estimateJoint () on scans whose points repeat (core/repeated_points.h)
// estimates on the first copies and lifts the result to every point.

#include <pcl_crf/joint/joint_estimation.h>

#include <vector>

namespace pcl_crf {
namespace joint {
namespace detail {

/** \a distinct, a result over the first copies of the source points against the first
 *  copies of the target points (firstCopies () of \a source_first and \a target_first,
 *  firstOfEqualPoints () of each scan), lifted to every point: a copy takes its first
 *  copy's match (a target point's first copy), cluster and moved-away mark; the
 *  clusters are renumbered largest first. */
JointResult
liftToCopies (const JointResult& distinct, const std::vector<int>& source_first, const std::vector<int>& target_first);

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
