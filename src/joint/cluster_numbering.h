#pragma once
// Internal: the numbering and checking of a joint result's clusters (joint_estimation.cpp),
// shared with the steps that edit a result's clusters (redundant_clusters.cpp,
// refuted_clusters.cpp, free_space_objects.cpp, moved_out_points.cpp, slid_segments.cpp).

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
 *  clusters are not as many, or a cluster (or the static one) is not one of the result's. */
void
checkResultClusters (const char* function, const JointResult& result);

/** checkResultClusters (), and \throws std::invalid_argument, naming \a function, when
 *  the result has not one cluster per point of \a source or \a source holds a NaN or
 *  infinite point. */
void
checkResultAgainstSource (const char* function, const Eigen::Matrix2Xd& source, const JointResult& result);

/** checkResultClusters (), and \throws std::invalid_argument, naming \a function, when a
 *  match is not a point of \a target or \a target holds a NaN or infinite point. */
void
checkResultAgainstTarget (const char* function, const Eigen::Matrix2Xd& target, const JointResult& result);

/** \throws std::invalid_argument, naming \a function, when a segment parameter is out of
 *  its range (matching::segmentParametersProblem ()). */
void
checkSegmentParameters (const char* function, const matching::SegmentMotionParameters& parameters);

/** checkResultAgainstSource () and checkResultAgainstTarget (). */
void
checkResultAgainstScans (const char* function, const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                         const JointResult& result);

/** Removes the clusters marked in \a removed (one flag per cluster): their points become
 *  outliers (kNoMatch, kOutlierCluster), the others are renumbered largest first.
 *  \return the number of clusters removed (\a result is untouched when none is marked) */
int
removeClusters (const std::vector<bool>& removed, JointResult& result);

/** Adds \a points to result.moved_away, which stays increasing and without repeats. */
void
markMovedAway (const std::vector<int>& points, JointResult& result);

/** The points \a indices of \a scan moved by T, as columns in that order. */
inline Eigen::Matrix2Xd
movedPoints (const Eigen::Matrix2Xd& scan, const std::vector<int>& indices, const Rigid2d& T)
{
  Eigen::Matrix2Xd moved (2, static_cast<Eigen::Index> (indices.size ()));
  for (std::size_t k = 0; k < indices.size (); ++k)
    moved.col (static_cast<Eigen::Index> (k)) = T * scan.col (indices[k]);
  return moved;
}

/** Whether source point \a i of \a result is in the static world or among the outliers
 *  (the points the free-space steps may give a cluster of their own). */
inline bool
inStaticWorldOrOutliers (const JointResult& result, std::size_t i)
{
  return result.source_cluster[i] == result.static_cluster || result.source_cluster[i] == kOutlierCluster;
}

/** Whether a free-space step has anything to separate from the static world: \a result
 *  has one, and both scans have the two points a range profile and a segment need. */
inline bool
canSeparateFromStaticWorld (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const JointResult& result)
{
  return result.static_cluster >= 0 && source.cols () >= 2 && target.cols () >= 2;
}

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
