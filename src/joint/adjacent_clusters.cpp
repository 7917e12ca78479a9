#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Whether source point \a i of \a result is in a moving cluster. */
bool
moving (const JointResult& result, int i)
{
  return !detail::inStaticWorldOrOutliers (result, static_cast<std::size_t> (i));
}

/** Whether motion \a T places every point of cluster \a l within its overlap radius
 *  (overlapRadius () of its spacing on its segment) of where the cluster's own motion
 *  places it: on the cluster's points the two motions cannot be told apart. */
bool
placesAlike (const Eigen::Matrix2Xd& source, const std::vector<matching::ScanSegment>& segments,
             const matching::SegmentMotionParameters& parameters, const JointResult& result, int l, const Rigid2d& T)
{
  for (const matching::ScanSegment& segment : segments)
    for (int i = segment.begin; i < segment.end; ++i) {
      if (result.source_cluster[i] != l)
        continue;
      const double radius =
          matching::overlapRadius (parameters, matching::pointSpacing (source, i, segment.begin, segment.end));
      if ((T * source.col (i) - result.cluster_motions[l] * source.col (i)).squaredNorm () > radius * radius)
        return false;
    }
  return true;
}

/** Merges one pair of adjacent clusters that move alike (the smaller into the larger).
 *  \return false when no pair is left. */
bool
mergeOnePair (const Eigen::Matrix2Xd& source, const std::vector<matching::ScanSegment>& segments,
              const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  const std::vector<int> sizes =
      clustering::clusterSizes (result.source_cluster, static_cast<int> (result.cluster_motions.size ()));
  for (const matching::ScanSegment& segment : segments)
    for (int i = segment.begin; i + 1 < segment.end; ++i) {
      const int a = result.source_cluster[i], b = result.source_cluster[i + 1];
      if (a == b || !moving (result, i) || !moving (result, i + 1))
        continue;
      const int larger = sizes[a] >= sizes[b] ? a : b, smaller = larger == a ? b : a;
      if (!placesAlike (source, segments, parameters, result, smaller, result.cluster_motions[larger]))
        continue;
      for (int& l : result.source_cluster)
        l = l == smaller ? larger : l;
      std::vector<bool> emptied (result.cluster_motions.size (), false);
      emptied[smaller] = true;
      detail::removeClusters (emptied, result);  // renumbers largest first
      return true;
    }
  return false;
}

/** mergeAdjacentClustersThatMoveAlike () over the source's segments. */
int
mergeAlongSegments (const Eigen::Matrix2Xd& source, const std::vector<matching::ScanSegment>& segments,
                    const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  if (result.static_cluster < 0)
    return 0;
  int merged = 0;
  while (mergeOnePair (source, segments, parameters, result))
    ++merged;
  return merged;
}

}  // namespace

int
detail::mergeAdjacentClustersThatMoveAlike (const ScanViews& views, JointResult& result)
{
  checkResultAgainstSource ("mergeAdjacentClustersThatMoveAlike", views.source (), result);
  return mergeAlongSegments (views.source (), views.sourceSegments (), views.parameters (), result);
}

int
mergeAdjacentClustersThatMoveAlike (const Eigen::Matrix2Xd& source,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  detail::checkResultAgainstSource ("mergeAdjacentClustersThatMoveAlike", source, result);
  const std::vector<matching::ScanSegment> segments =
      matching::segmentScan (source, parameters.breakpoint_angle, parameters.range_noise,
                             matching::BeamGaps::MissingReturns, parameters.max_missing_returns);
  return mergeAlongSegments (source, segments, parameters, result);
}

}  // namespace joint
}  // namespace pcl_crf
