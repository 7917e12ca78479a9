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

/** Whether motion \a T explains the points of cluster \a l as well as the cluster's own
 *  motion: of the points both place in the target's view (detail::TargetPlacement), at
 *  least as many within their overlap radius of a target point. A surface that slides
 *  along itself looks alike to the target wherever it slid, except at its ends: there
 *  two motions farther apart than the overlap radius are still the same to the data. */
bool
explainsAsWell (const detail::ScanViews& views, const JointResult& result, int l, const Rigid2d& T)
{
  const Eigen::Matrix2Xd& source = views.source ();
  int own = 0, other = 0;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    std::vector<int> members;  // of cluster l, in the segment's order
    for (int i = segment.begin; i < segment.end; ++i)
      if (result.source_cluster[i] == l)
        members.push_back (i);
    if (members.empty ())
      continue;
    const std::vector<double> all_radii = detail::squaredOverlapRadii (source, segment, views.parameters ());
    std::vector<double> radii_squared;
    Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (members.size ()));
    for (std::size_t k = 0; k < members.size (); ++k) {
      radii_squared.push_back (all_radii[members[k] - segment.begin]);
      points.col (k) = source.col (members[k]);
    }
    const detail::TargetPlacement by_own = detail::placeInTarget (result.cluster_motions[l] * points, radii_squared, views);
    const detail::TargetPlacement by_other = detail::placeInTarget (T * points, radii_squared, views);
    for (std::size_t k = 0; k < members.size (); ++k)
      if (by_own.in_view[k] && by_other.in_view[k]) {
        own += by_own.explained[k] ? 1 : 0;
        other += by_other.explained[k] ? 1 : 0;
      }
  }
  return other >= own;
}

/** Merges one pair of adjacent clusters that move alike (the smaller into the larger).
 *  \return false when no pair is left. */
bool
mergeOnePair (const detail::ScanViews& views, JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const std::vector<matching::ScanSegment>& segments = views.sourceSegments ();
  const std::vector<int> sizes =
      clustering::clusterSizes (result.source_cluster, static_cast<int> (result.cluster_motions.size ()));
  for (const matching::ScanSegment& segment : segments)
    for (int i = segment.begin; i + 1 < segment.end; ++i) {
      const int a = result.source_cluster[i], b = result.source_cluster[i + 1];
      if (a == b || !moving (result, i) || !moving (result, i + 1))
        continue;
      const int larger = sizes[a] >= sizes[b] ? a : b, smaller = larger == a ? b : a;
      const Rigid2d& T = result.cluster_motions[larger];
      if (!placesAlike (source, segments, views.parameters (), result, smaller, T) &&
          !explainsAsWell (views, result, smaller, T))
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

}  // namespace

int
detail::mergeAdjacentClustersThatMoveAlike (const ScanViews& views, JointResult& result)
{
  checkResultAgainstScans ("mergeAdjacentClustersThatMoveAlike", views.source (), views.target (), result);
  if (result.static_cluster < 0)
    return 0;
  int merged = 0;
  while (mergeOnePair (views, result))
    ++merged;
  return merged;
}

int
mergeAdjacentClustersThatMoveAlike (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::mergeAdjacentClustersThatMoveAlike (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
