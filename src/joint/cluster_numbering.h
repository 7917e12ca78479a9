#pragma once
// Internal: the numbering of a joint result's clusters (joint_estimation.cpp), shared
// with the removal of redundant clusters (redundant_clusters.cpp).

#include <pcl_crf/joint/joint_estimation.h>

namespace pcl_crf {
namespace joint {
namespace detail {

/** Renumbers the clusters of \a result largest first; their sizes, the outlier list
 *  and the static cluster follow. */
void
numberLargestFirst (JointResult& result);

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
