#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/scan_segments.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The distance from \a p to the piece of outline between \a a and \a b [m]. */
double
distanceToPiece (const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double length_squared = ab.squaredNorm ();
  const double t = length_squared > 0.0 ? std::clamp ((p - a).dot (ab) / length_squared, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm ();
}

/** Per cluster but the static world: how many of its points, each moved by \a motion_of
 *  its cluster, lie within \a radius of the target's outline: the pieces from its nearest
 *  target point to that point's neighbours on the same target segment (\a segment_of,
 *  per target point). */
template <typename MotionOf> std::vector<int>
pointsOnTheOutline (const detail::ScanViews& views, const std::vector<int>& segment_of, const JointResult& result,
                    double radius, MotionOf motion_of)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const Eigen::Matrix2Xd& target = views.target ();
  std::vector<int> on (result.cluster_motions.size (), 0);
  std::vector<Eigen::Index> points;
  for (Eigen::Index i = 0; i < source.cols (); ++i)
    if (result.source_cluster[i] != kOutlierCluster && result.source_cluster[i] != result.static_cluster)
      points.push_back (i);
  if (points.empty ())
    return on;
  Eigen::Matrix2Xd moved (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    moved.col (static_cast<Eigen::Index> (k)) = motion_of (result.source_cluster[points[k]]) * source.col (points[k]);
  const KnnIndex::Result nearest = views.targetPoints ().search (moved, 1);  // one batched query
  for (std::size_t k = 0; k < points.size (); ++k) {
    const auto column = static_cast<Eigen::Index> (k);
    const int j = nearest.indices (0, column);
    double distance = std::sqrt (nearest.squared_distances (0, column));
    for (const int neighbour : {j - 1, j + 1})
      if (neighbour >= 0 && neighbour < target.cols () && segment_of[neighbour] == segment_of[j])
        distance = std::min (distance, distanceToPiece (moved.col (column), target.col (j), target.col (neighbour)));
    on[result.source_cluster[points[k]]] += distance <= radius ? 1 : 0;
  }
  return on;
}

}  // namespace

int
detail::removeClustersOnTheStaticOutline (const ScanViews& views, JointResult& result)
{
  checkResultAgainstScans ("removeClustersOnTheStaticOutline", views.source (), views.target (), result);
  if (result.static_cluster < 0 || result.cluster_motions.size () < 2)
    return 0;
  const double radius = 3.0 * views.parameters ().range_noise;
  const Rigid2d& T_static = result.cluster_motions[result.static_cluster];
  const std::vector<int> segment_of =
      matching::segmentOfEachPoint (views.targetSegments (), views.target ().cols ());
  const std::vector<int> under_static =
      pointsOnTheOutline (views, segment_of, result, radius, [&T_static] (int) { return T_static; });
  const std::vector<int> under_own = pointsOnTheOutline (views, segment_of, result, radius,
                                                         [&result] (int l) { return result.cluster_motions[l]; });
  const std::vector<int> sizes = clustering::clusterSizes (result.source_cluster,
                                                           static_cast<int> (result.cluster_motions.size ()));
  std::vector<bool> removed (result.cluster_motions.size (), false);
  for (std::size_t l = 0; l < removed.size (); ++l)
    removed[l] = static_cast<int> (l) != result.static_cluster && 2 * under_static[l] > sizes[l] &&
                 under_static[l] >= under_own[l];
  return removeClusters (removed, result);
}

int
removeClustersOnTheStaticOutline (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                  const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::removeClustersOnTheStaticOutline (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
