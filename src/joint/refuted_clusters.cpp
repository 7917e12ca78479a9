#include <pcl_crf/clustering/scan_segmentation.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Per cluster: how many points of its extent (\a attached) the target sensor saw
 *  through under its motion, and how many of its own points are matched. */
struct FreeSpaceEvidence
{
  std::vector<int> seen_through;
  std::vector<int> matched;
};

FreeSpaceEvidence
weighEvidence (const detail::ScanViews& views, const std::vector<int>& attached, const JointResult& result)
{
  const auto clusters = result.cluster_motions.size ();
  FreeSpaceEvidence evidence{std::vector<int> (clusters, 0), std::vector<int> (clusters, 0)};
  const detail::SensorView& seen = views.targetView ();
  for (std::size_t i = 0; i < attached.size (); ++i) {
    const int l = attached[i];
    if (l == kOutlierCluster || l == result.static_cluster)
      continue;
    const Eigen::Vector2d moved = result.cluster_motions[l] * views.source ().col (static_cast<Eigen::Index> (i));
    evidence.seen_through[l] += matching::seesThrough (seen.profile, moved, seen.breakpoint) ? 1 : 0;
    evidence.matched[l] += result.source_cluster[i] == l && result.source_match[i] != kNoMatch ? 1 : 0;
  }
  return evidence;
}

}  // namespace

int
detail::removeClustersTheTargetSeesThrough (const ScanViews& views, JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  checkResultAgainstScans ("removeClustersTheTargetSeesThrough", source, views.target (), result);
  if (result.static_cluster < 0 || result.cluster_motions.size () < 2)
    return 0;
  // Per source point: its cluster, or for an outlier the cluster whose motion it would
  // share, that of the nearer closest clustered point on its source segment.
  const std::vector<int> attached = clustering::completeLabelsWithinSegments (
      source, matching::segmentOfEachPoint (views.sourceSegments (), source.cols ()), result.source_cluster,
      kOutlierCluster);
  const FreeSpaceEvidence evidence = weighEvidence (views, attached, result);
  std::vector<bool> removed (result.cluster_motions.size (), false);
  for (std::size_t l = 0; l < removed.size (); ++l)
    removed[l] = evidence.seen_through[l] > evidence.matched[l];  // refuted by more points than support it
  return removeClusters (removed, result);
}

int
removeClustersTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::removeClustersTheTargetSeesThrough (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
