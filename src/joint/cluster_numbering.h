#pragma once
// Internal: the numbering and checking of a joint result's clusters (joint_estimation.cpp),
// shared with the steps that edit a result's clusters (redundant_clusters.cpp,
// free_space_objects.cpp).

#include <pcl_crf/joint/joint_estimation.h>

#include <vector>

namespace pcl_crf {
namespace joint {
namespace detail {

/** Renumbers the clusters of \a result largest first; their sizes, the outlier list
 *  and the static cluster follow. */
void
numberLargestFirst (JointResult& result);

/** \throws std::invalid_argument, naming \a function, when the result's matches and
 *  clusters are not one per source point, a match is not a point of \a target or a
 *  cluster (or the static one) is not one of the result's. */
void
checkResultAgainstTarget (const char* function, const Eigen::Matrix2Xd& target, const JointResult& result);

/** checkResultAgainstTarget (), and \throws std::invalid_argument, naming \a function, when
 *  the result has not one cluster per point of \a source. */
void
checkResultAgainstScans (const char* function, const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                         const JointResult& result);

/** Removes the clusters marked in \a removed (one flag per cluster): their points become
 *  outliers (kNoMatch, kOutlierCluster), the others are renumbered largest first. */
void
removeClusters (const std::vector<bool>& removed, JointResult& result);

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
