#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The points of one scan segment that moved, and their centroid [m, target frame]. */
struct MovedGroup
{
  std::vector<int> points;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero ();
};

/** The points of \a scan that the other sensor (\a other_view) saw through (to a return)
 *  when moved by T, among those \a candidate allows. */
std::vector<bool>
seenThroughByTheOther (const Eigen::Matrix2Xd& scan, const detail::SensorView& other_view, const Rigid2d& T,
                       const std::vector<bool>& candidate)
{
  std::vector<bool> seen (candidate.size (), false);
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
    seen[i] = candidate[i] && matching::seesThroughToAReturn (other_view.profile, T * scan.col (i), other_view.breakpoint);
  return seen;
}

/** The points of \a marked grouped by their segment of \a scan, with the centroids of
 *  the points moved by \a T. */
std::vector<MovedGroup>
groupBySegment (const Eigen::Matrix2Xd& scan, const std::vector<matching::ScanSegment>& segments,
                const std::vector<bool>& marked, const Rigid2d& T)
{
  std::vector<MovedGroup> groups;
  for (const matching::ScanSegment& segment : segments) {
    MovedGroup group;
    for (int i = segment.begin; i < segment.end; ++i)
      if (marked[i]) {
        group.points.push_back (i);
        group.centroid += T * scan.col (i);
      }
    if (group.points.empty ())
      continue;
    group.centroid /= static_cast<double> (group.points.size ());
    groups.push_back (std::move (group));
  }
  return groups;
}

/** Per target point: false on the target segments a moving cluster's point is matched
 *  to (that cluster's object, seen after it moved), true elsewhere. */
std::vector<bool>
unclaimedTargets (const std::vector<matching::ScanSegment>& segments, Eigen::Index points,
                  const std::vector<bool>& free, const JointResult& result)
{
  std::vector<bool> claimed (static_cast<std::size_t> (points), false);
  for (std::size_t i = 0; i < free.size (); ++i)
    if (!free[i] && result.source_match[i] != kNoMatch)
      claimed[result.source_match[i]] = true;
  std::vector<bool> unclaimed (claimed.size (), true);
  for (const matching::ScanSegment& segment : segments)
    if (std::any_of (claimed.begin () + segment.begin, claimed.begin () + segment.end, [] (bool c) { return c; }))
      std::fill (unclaimed.begin () + segment.begin, unclaimed.begin () + segment.end, false);
  return unclaimed;
}

/** The index of the centroid of \a groups nearest to \a point within \a reach [m], or -1. */
int
nearestGroup (const Eigen::Vector2d& point, const std::vector<MovedGroup>& groups, double reach)
{
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity ();
  for (std::size_t g = 0; g < groups.size (); ++g) {
    const double distance = (groups[g].centroid - point).norm ();
    if (distance <= reach && distance < best_distance) {
      best_distance = distance;
      best = static_cast<int> (g);
    }
  }
  return best;
}

/** Per moved-out group: the moved-in group it pairs with, or -1. Groups pair when each
 *  is the other's nearest (centroids within \a reach [m]): one object's two views, where
 *  the nearest alone lets a walker's moved-out leg take a neighbour's moved-in one. */
std::vector<int>
mutualCounterparts (const std::vector<MovedGroup>& moved_out, const std::vector<MovedGroup>& moved_in, double reach)
{
  std::vector<int> counterpart (moved_out.size (), -1);
  for (std::size_t a = 0; a < moved_out.size (); ++a) {
    const int b = nearestGroup (moved_out[a].centroid, moved_in, reach);
    if (b >= 0 && nearestGroup (moved_in[b].centroid, moved_out, reach) == static_cast<int> (a))
      counterpart[a] = b;
  }
  return counterpart;
}

/** The moved-out group joins a new cluster of motion T: each point takes the nearest
 *  point of the moved-in group within its overlap radius, or no match. */
void
addCluster (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const MovedGroup& moved_out,
            const MovedGroup& moved_in, const Rigid2d& T, const matching::SegmentMotionParameters& parameters,
            JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  for (int i : moved_out.points) {
    const Eigen::Vector2d moved = T * source.col (i);
    int match = kNoMatch;
    double nearest = std::numeric_limits<double>::infinity ();
    for (int j : moved_in.points) {
      const double radius = matching::overlapRadius (parameters, matching::pointSpacing (target, j, 0, target.cols ()));
      const double distance = (target.col (j) - moved).norm ();
      if (distance <= radius && distance < nearest) {
        nearest = distance;
        match = j;
      }
    }
    result.source_cluster[i] = cluster;
    result.source_match[i] = match;
  }
}

}  // namespace

int
detail::separatePointsTheTargetSeesThrough (const ScanViews& views, JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const Eigen::Matrix2Xd& target = views.target ();
  const matching::SegmentMotionParameters& parameters = views.parameters ();
  checkResultAgainstScans ("separatePointsTheTargetSeesThrough", source, target, result);
  if (!canSeparateFromStaticWorld (source, target, result))
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  std::vector<bool> free (result.source_cluster.size ());
  for (std::size_t i = 0; i < free.size (); ++i)
    free[i] = inStaticWorldOrOutliers (result, i);
  const std::vector<MovedGroup> moved_out = groupBySegment (
      source, views.sourceSegments (), seenThroughByTheOther (source, views.targetView (), T_static, free), T_static);
  if (moved_out.empty ())
    return 0;
  const std::vector<matching::ScanSegment>& target_segments = views.targetSegments ();
  const std::vector<MovedGroup> moved_in = groupBySegment (
      target, target_segments,
      seenThroughByTheOther (target, views.sourceView (), T_static.inverse (),
                             unclaimedTargets (target_segments, target.cols (), free, result)),
      Rigid2d::Identity ());
  const std::vector<int> counterpart = mutualCounterparts (moved_out, moved_in, parameters.max_displacement);
  int added = 0;
  for (std::size_t a = 0; a < moved_out.size (); ++a) {
    const int b = counterpart[a];
    if (b < 0)  // it left the view or hid, or its view is ambiguous: no motion to give it
      continue;
    Rigid2d T = T_static;  // the static motion shifted by the moved-out group's displacement
    T.translation () += moved_in[b].centroid - moved_out[a].centroid;
    addCluster (source, target, moved_out[a], moved_in[b], T, parameters, result);
    ++added;
  }
  if (added > 0)
    numberLargestFirst (result);
  return added;
}

int
separatePointsTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::separatePointsTheTargetSeesThrough (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
