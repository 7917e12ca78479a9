#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <numeric>
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

/** Some points of one source segment (in its order), each placed by two motions.
 *  \a explained_by_first / \a explained_by_second count the points within their overlap
 *  radius of a target point, of those both motions place in the target's view
 *  (detail::TargetPlacement: a point leaving it says nothing for or against). */
struct TwoPlacements
{
  detail::TargetPlacement first, second;
  int explained_by_first = 0;
  int explained_by_second = 0;
};

TwoPlacements
placeByBoth (const detail::ScanViews& views, const matching::ScanSegment& segment, const std::vector<int>& members,
             const Rigid2d& first, const Rigid2d& second)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const std::vector<double> radii_squared = detail::squaredOverlapRadii (source, segment, members, views.parameters ());
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (members.size ()));
  for (std::size_t k = 0; k < members.size (); ++k)
    points.col (static_cast<Eigen::Index> (k)) = source.col (members[k]);
  TwoPlacements both{detail::placeInTarget (first * points, radii_squared, views),
                     detail::placeInTarget (second * points, radii_squared, views)};
  for (std::size_t k = 0; k < members.size (); ++k)
    if (both.first.in_view[k] && both.second.in_view[k]) {
      both.explained_by_first += both.first.explained[k] ? 1 : 0;
      both.explained_by_second += both.second.explained[k] ? 1 : 0;
    }
  return both;
}

/** Whether motion \a T explains the points of cluster \a l as well as the cluster's own
 *  motion (placeByBoth () on each segment): a surface that slides along itself looks
 *  alike to the target wherever it slid, except at its ends, so that there two motions
 *  farther apart than the overlap radius are still the same to the data. */
bool
explainsAsWell (const detail::ScanViews& views, const JointResult& result, int l, const Rigid2d& T)
{
  int own = 0, other = 0;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    const std::vector<int> members = detail::segmentPointsLabelled (segment, result.source_cluster, l);
    if (members.empty ())
      continue;
    const TwoPlacements both = placeByBoth (views, segment, members, result.cluster_motions[l], T);
    own += both.explained_by_first;
    other += both.explained_by_second;
  }
  return other >= own;
}

/** The static world's points [begin, end) of \a segment join the neighbouring moving
 *  cluster (at begin − 1 or at end) whose motion explains most of them, when it
 *  explains at least one and as many as the static motion does (placeByBoth ()); each
 *  takes its nearest target point there when explained, or no match.
 *  \return true when they joined one. */
bool
extendOverStaticRun (const detail::ScanViews& views, const matching::ScanSegment& segment, int begin, int end,
                     JointResult& result)
{
  std::vector<int> run (static_cast<std::size_t> (end - begin));
  std::iota (run.begin (), run.end (), begin);
  const Rigid2d& T_static = result.cluster_motions[result.static_cluster];
  int best = -1;
  TwoPlacements best_placements;
  for (const int neighbour : {begin - 1, end}) {
    if (neighbour < segment.begin || neighbour >= segment.end || !moving (result, neighbour))
      continue;
    const int l = result.source_cluster[neighbour];
    TwoPlacements both = placeByBoth (views, segment, run, result.cluster_motions[l], T_static);
    if (both.explained_by_first == 0 || both.explained_by_first < both.explained_by_second)
      continue;
    if (best < 0 || both.explained_by_first > best_placements.explained_by_first) {
      best = l;
      best_placements = std::move (both);
    }
  }
  if (best < 0)
    return false;
  for (std::size_t k = 0; k < run.size (); ++k) {
    result.source_cluster[run[k]] = best;
    result.source_match[run[k]] =
        best_placements.first.explained[k] ? best_placements.first.nearest.indices (0, static_cast<Eigen::Index> (k))
                                           : kNoMatch;
  }
  return true;
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

int
detail::extendMovingClustersOverTheirSurfaces (const ScanViews& views, JointResult& result)
{
  checkResultAgainstScans ("extendMovingClustersOverTheirSurfaces", views.source (), views.target (), result);
  if (result.static_cluster < 0)
    return 0;
  int extended = 0;
  for (const matching::ScanSegment& segment : views.sourceSegments ())
    for (int begin = segment.begin; begin < segment.end;) {
      int end = begin;  // [begin, end): a run of the static world's points
      while (end < segment.end && result.source_cluster[end] == result.static_cluster)
        ++end;
      if (end > begin && extendOverStaticRun (views, segment, begin, end, result))
        ++extended;
      begin = std::max (end, begin + 1);
    }
  if (extended > 0)
    numberLargestFirst (result);
  return extended;
}

int
extendMovingClustersOverTheirSurfaces (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                       const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::extendMovingClustersOverTheirSurfaces (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
