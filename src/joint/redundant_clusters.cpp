#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"

#include <algorithm>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The target points that the points of the clusters \a by marks (one flag per
 *  cluster) are matched to, as a kd-tree. */
KnnIndex
claimedTargets (const Eigen::Matrix2Xd& target, const JointResult& result, const std::vector<bool>& by)
{
  std::vector<int> claimed;
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i) {
    const int l = result.source_cluster[i];
    if (l != kOutlierCluster && by[l] && result.source_match[i] != kNoMatch)
      claimed.push_back (result.source_match[i]);
  }
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (claimed.size ()));
  for (std::size_t c = 0; c < claimed.size (); ++c)
    points.col (static_cast<Eigen::Index> (c)) = target.col (claimed[c]);
  KnnIndex index;
  index.build (points);
  return index;
}

/** The target points the static world's points are matched to, as a kd-tree. */
KnnIndex
staticWorldTargets (const Eigen::Matrix2Xd& target, const JointResult& result)
{
  std::vector<bool> by (result.cluster_motions.size (), false);
  by[result.static_cluster] = true;
  return claimedTargets (target, result, by);
}

/** Per cluster: true when it has matched points and most of them (more than half)
 *  landed within their target point's overlap radius of a target point in \a claimed. */
std::vector<bool>
explainedClusters (const Eigen::Matrix2Xd& target, const matching::SegmentMotionParameters& parameters,
                   const KnnIndex& claimed, const JointResult& result)
{
  const int clusters = static_cast<int> (result.cluster_motions.size ());
  std::vector<int> matched (static_cast<std::size_t> (clusters), 0), unexplained (matched);
  std::vector<int> points;
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i)
    if (result.source_cluster[i] != kOutlierCluster && result.source_cluster[i] != result.static_cluster &&
        result.source_match[i] != kNoMatch)
      points.push_back (static_cast<int> (i));
  std::vector<bool> explained (static_cast<std::size_t> (clusters), false);
  if (points.empty ())
    return explained;
  Eigen::Matrix2Xd landed (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    landed.col (static_cast<Eigen::Index> (k)) = target.col (result.source_match[points[k]]);
  const KnnIndex::Result nearest = claimed.search (landed, 1);  // one batched query
  for (std::size_t k = 0; k < points.size (); ++k) {
    const int l = result.source_cluster[points[k]];
    const int j = result.source_match[points[k]];
    const double radius = matching::overlapRadius (parameters, matching::pointSpacing (target, j, 0, target.cols ()));
    ++matched[l];
    if (nearest.squared_distances (0, static_cast<Eigen::Index> (k)) > radius * radius)
      ++unexplained[l];
  }
  for (int l = 0; l < clusters; ++l)
    explained[l] = matched[l] > 0 && 2 * unexplained[l] < matched[l];  // a majority
  return explained;
}

/** The moving clusters, nearest to the static motion first: by the mean distance
 *  between where their motion and the static one put their points. */
std::vector<int>
movingClustersByDisplacement (const Eigen::Matrix2Xd& source, const JointResult& result)
{
  const int clusters = static_cast<int> (result.cluster_motions.size ());
  const Rigid2d& T_static = result.cluster_motions[result.static_cluster];
  std::vector<double> displacement (static_cast<std::size_t> (clusters), 0.0);
  std::vector<int> points (static_cast<std::size_t> (clusters), 0);
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i) {
    const int l = result.source_cluster[i];
    if (l == kOutlierCluster || l == result.static_cluster)
      continue;
    const Eigen::Vector2d p = source.col (static_cast<Eigen::Index> (i));
    displacement[l] += (result.cluster_motions[l] * p - T_static * p).norm ();
    ++points[l];
  }
  std::vector<int> order;
  for (int l = 0; l < clusters; ++l)
    if (l != result.static_cluster) {
      order.push_back (l);
      displacement[l] /= std::max (points[l], 1);
    }
  std::stable_sort (order.begin (), order.end (), [&] (int a, int b) { return displacement[a] < displacement[b]; });
  return order;
}

/** The points of the clusters \a removed marks, of each such cluster the static motion
 *  mostly (more than half) puts farther than their overlap radius from every target
 *  point. */
std::vector<int>
pointsTheStaticMotionLeavesUnexplained (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                        const matching::SegmentMotionParameters& parameters,
                                        const JointResult& result, const std::vector<bool>& removed)
{
  const KnnIndex target_points (target);
  const Rigid2d& T_static = result.cluster_motions[result.static_cluster];
  std::vector<int> marked;
  for (std::size_t l = 0; l < removed.size (); ++l) {
    if (!removed[l])
      continue;
    std::vector<int> points;
    for (std::size_t i = 0; i < result.source_cluster.size (); ++i)
      if (result.source_cluster[i] == static_cast<int> (l))
        points.push_back (static_cast<int> (i));
    const KnnIndex::Result nearest =
        target_points.search (detail::movedPoints (source, points, T_static), 1);  // one batched query
    int explained = 0;
    for (std::size_t k = 0; k < points.size (); ++k) {
      const double radius =
          matching::overlapRadius (parameters, matching::pointSpacing (source, points[k], 0, source.cols ()));
      explained += nearest.squared_distances (0, static_cast<Eigen::Index> (k)) <= radius * radius ? 1 : 0;
    }
    if (2 * explained < static_cast<int> (points.size ()))
      marked.insert (marked.end (), points.begin (), points.end ());
  }
  return marked;
}

}  // namespace

int
detail::removeClusters (const std::vector<bool>& removed, JointResult& result)
{
  const auto count = static_cast<int> (std::count (removed.begin (), removed.end (), true));
  if (count == 0)
    return 0;
  std::vector<int> rank (removed.size (), kOutlierCluster);
  std::vector<Rigid2d> motions;
  for (std::size_t l = 0; l < removed.size (); ++l)
    if (!removed[l]) {
      rank[l] = static_cast<int> (motions.size ());
      motions.push_back (result.cluster_motions[l]);
    }
  result.cluster_motions = std::move (motions);
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i) {
    int& l = result.source_cluster[i];
    if (l == kOutlierCluster)
      continue;
    if (removed[l])
      result.source_match[i] = kNoMatch;
    l = rank[l];
  }
  result.static_cluster = rank[result.static_cluster];
  detail::numberLargestFirst (result);  // the sizes and the outlier list
  return count;
}

int
removeClustersTheStaticWorldExplains (const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  detail::checkResultAgainstTarget ("removeClustersTheStaticWorldExplains", target, result);
  detail::checkSegmentParameters ("removeClustersTheStaticWorldExplains", parameters);
  if (result.static_cluster < 0)
    return 0;
  const KnnIndex claimed = staticWorldTargets (target, result);
  if (claimed.size () == 0)
    return 0;
  return detail::removeClusters (explainedClusters (target, parameters, claimed, result), result);
}

int
removeClustersANearerClusterExplains (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  detail::checkResultAgainstScans ("removeClustersANearerClusterExplains", source, target, result);
  detail::checkSegmentParameters ("removeClustersANearerClusterExplains", parameters);
  if (result.static_cluster < 0)
    return 0;
  const std::vector<int> order = movingClustersByDisplacement (source, result);
  std::vector<bool> removed (result.cluster_motions.size (), false), nearer (removed);
  for (std::size_t k = 0; k < order.size (); ++k) {
    const int l = order[k];
    if (k > 0) {
      const KnnIndex claimed = claimedTargets (target, result, nearer);
      removed[l] = claimed.size () > 0 && explainedClusters (target, parameters, claimed, result)[l];
    }
    nearer[l] = !removed[l];
  }
  if (std::none_of (removed.begin (), removed.end (), [] (bool r) { return r; }))
    return 0;
  const std::vector<int> moved_away = pointsTheStaticMotionLeavesUnexplained (source, target, parameters, result, removed);
  const int count = detail::removeClusters (removed, result);
  detail::markMovedAway (moved_away, result);
  return count;
}

}  // namespace joint
}  // namespace pcl_crf
