#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/rigid_fit.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Rounds of ICP at most, and the change of every entry of the motion's matrix below
 *  which it has converged. */
constexpr int kMaxIcpRounds = 20;
constexpr double kIcpConvergence = 1e-6;

[[noreturn]] void
fail (const char* function, const std::string& what)
{
  throw std::invalid_argument (std::string ("[pcl_crf::joint::") + function + "] " + what);
}

}  // namespace

Rigid2d
detail::icpOnNearestPoints (const Eigen::Matrix2Xd& source, const std::vector<int>& members,
                            const KnnIndex& target_points, Rigid2d T, double gate)
{
  const Eigen::MatrixXd& target = target_points.points ();
  for (int round = 0; round < kMaxIcpRounds; ++round) {
    const KnnIndex::Result nearest = target_points.search (detail::movedPoints (source, members, T), 1);
    RigidFitAccumulator fit;
    for (std::size_t k = 0; k < members.size (); ++k) {
      const auto column = static_cast<Eigen::Index> (k);
      if (nearest.squared_distances (0, column) <= gate * gate)
        fit.add (source.col (members[k]), target.col (nearest.indices (0, column)));
    }
    if (!fit.isWellPosed ())
      break;
    const Rigid2d next = fit.solve ();
    const double change = (next.matrix () - T.matrix ()).cwiseAbs ().maxCoeff ();
    T = next;
    if (change < kIcpConvergence)
      break;
  }
  return T;
}

namespace {

/** How many of \a members (points of \a segment) T puts within their overlap radius
 *  (matching::overlapRadius () of their spacing on the segment) of a target point. */
int
explainedByNearest (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
                    const std::vector<int>& members, const KnnIndex& target_points, const Rigid2d& T,
                    const matching::SegmentMotionParameters& parameters)
{
  const KnnIndex::Result nearest = target_points.search (detail::movedPoints (source, members, T), 1);
  int explained = 0;
  for (std::size_t k = 0; k < members.size (); ++k) {
    const double radius = matching::overlapRadius (
        parameters, matching::pointSpacing (source, members[k], segment.begin, segment.end));
    explained += nearest.squared_distances (0, static_cast<Eigen::Index> (k)) <= radius * radius ? 1 : 0;
  }
  return explained;
}

/** The cluster of \a start whose motion is T_static, or -1. */
int
clusterOfMotion (const LadderStart& start, const Rigid2d& T_static)
{
  for (std::size_t l = 0; l < start.motions.size (); ++l)
    if (start.motions[l].matrix () == T_static.matrix ())
      return static_cast<int> (l);
  return -1;
}

/** Whether the ladder's cluster, put into the static world by the final clustering on
 *  \a segment (its points \a members there), moved: of its points both motions place in
 *  the target's view and the static motion does not hide behind a target return
 *  (matching::hiddenBehindAReturn (): there the target says nothing of them), at least
 *  \a min_points, the static motion explains fewer than half and the ladder's motion
 *  T_ladder more than half. */
bool
movedAsTheLadderSays (const detail::ScanViews& views, const matching::ScanSegment& segment,
                      const std::vector<int>& members, const Rigid2d& T_static, const Rigid2d& T_ladder, int min_points)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const std::vector<double> radii_squared = detail::squaredOverlapRadii (source, segment, members, views.parameters ());
  const detail::TargetPlacement by_static = detail::placeInTarget (detail::movedPoints (source, members, T_static),
                                                                   radii_squared, views);
  const detail::TargetPlacement by_ladder = detail::placeInTarget (detail::movedPoints (source, members, T_ladder),
                                                                   radii_squared, views);
  const detail::SensorView& target_view = views.targetView ();
  int in_view = 0, static_explains = 0, ladder_explains = 0;
  for (std::size_t k = 0; k < members.size (); ++k)
    if (by_static.in_view[k] && by_ladder.in_view[k] &&
        !matching::hiddenBehindAReturn (target_view.profile, by_static.points.col (static_cast<Eigen::Index> (k)),
                                        target_view.breakpoint)) {
      ++in_view;
      static_explains += by_static.explained[k] ? 1 : 0;
      ladder_explains += by_ladder.explained[k] ? 1 : 0;
    }
  return in_view >= min_points && 2 * static_explains < in_view && 2 * ladder_explains > in_view;
}

}  // namespace

int
addSegmentMotionHypotheses (const Eigen::Matrix2Xd& source, const KnnIndex& target_points, const Rigid2d& T_static,
                            const matching::SegmentMotionParameters& parameters, LadderStart& start)
{
  if (static_cast<Eigen::Index> (start.cluster.size ()) != source.cols ())
    fail ("addSegmentMotionHypotheses", "the start has " + std::to_string (start.cluster.size ()) +
                                            " clusters for " + std::to_string (source.cols ()) + " source points");
  const int static_cluster = clusterOfMotion (start, T_static);
  if (static_cluster < 0 || target_points.size () == 0 || source.cols () < 2)
    return 0;
  std::vector<std::pair<std::vector<int>, Rigid2d>> hypotheses;
  for (const matching::ScanSegment& segment :
       matching::segmentScan (source, parameters.breakpoint_angle, parameters.range_noise)) {
    std::vector<int> members = detail::segmentPointsLabelled (segment, start.cluster, static_cluster);
    const int n = static_cast<int> (members.size ());
    if (n < parameters.min_segment_points ||
        2 * explainedByNearest (source, segment, members, target_points, T_static, parameters) >= n)
      continue;
    const Rigid2d T = detail::icpOnNearestPoints (source, members, target_points, T_static, parameters.overlap_radius);
    if (2 * explainedByNearest (source, segment, members, target_points, T, parameters) > n)
      hypotheses.emplace_back (std::move (members), T);
  }
  if (hypotheses.empty ())
    return 0;
  // The outlier cluster is numbered after the real ones: it moves up past the new ones.
  const int outlier = static_cast<int> (start.motions.size ());
  const int new_outlier = outlier + static_cast<int> (hypotheses.size ());
  for (int& l : start.cluster)
    l = l == outlier ? new_outlier : l;
  for (const auto& [members, T] : hypotheses) {
    for (int i : members)
      start.cluster[i] = static_cast<int> (start.motions.size ());
    start.motions.push_back (T);
  }
  return static_cast<int> (hypotheses.size ());
}

int
detail::keepLadderClustersTheFinalClusteringMerged (const ScanViews& views, const JointResult& ladder, int min_points,
                                                    JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  checkResultAgainstScans ("keepLadderClustersTheFinalClusteringMerged", source, views.target (), result);
  checkResultAgainstSource ("keepLadderClustersTheFinalClusteringMerged", source, ladder);
  if (result.static_cluster < 0 || ladder.static_cluster < 0)
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  std::vector<Rigid2d> kept_motions;
  std::vector<std::vector<int>> kept_members;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    std::vector<int> members = detail::segmentPointsLabelled (segment, result.source_cluster, result.static_cluster);
    if (static_cast<int> (members.size ()) < min_points || 2 * static_cast<int> (members.size ()) <= segment.size ())
      continue;
    // They must all be in one moving cluster of the ladder.
    const int l = ladder.source_cluster[members.front ()];
    if (l < 0 || l == ladder.static_cluster ||
        std::any_of (members.begin (), members.end (), [&ladder, l] (int i) { return ladder.source_cluster[i] != l; }) ||
        !movedAsTheLadderSays (views, segment, members, T_static, ladder.cluster_motions[l], min_points))
      continue;
    kept_motions.push_back (ladder.cluster_motions[l]);
    kept_members.push_back (std::move (members));
  }
  for (std::size_t k = 0; k < kept_members.size (); ++k) {
    for (int i : kept_members[k])
      result.source_cluster[i] = static_cast<int> (result.cluster_motions.size ());
    result.cluster_motions.push_back (kept_motions[k]);
  }
  if (!kept_members.empty ())
    numberLargestFirst (result);
  return static_cast<int> (kept_members.size ());
}

int
keepLadderClustersTheFinalClusteringMerged (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                            const matching::SegmentMotionParameters& parameters,
                                            const JointResult& ladder, JointResult& result)
{
  return detail::keepLadderClustersTheFinalClusteringMerged (detail::ScanViews (source, target, parameters), ladder,
                                                             parameters.min_segment_points, result);
}

}  // namespace joint
}  // namespace pcl_crf
