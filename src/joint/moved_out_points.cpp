#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <cmath>
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

/** What the other sensor's view says of a point in its frame: matching::seesThroughToAReturn ()
 *  (the point moved out, or in) or matching::hiddenBehindAReturn (). */
using ViewTest = bool (*) (const matching::RangeProfile&, const Eigen::Vector2d&, const matching::BreakpointDistance&);

/** The points of \a scan, among those \a candidate allows, of which \a test holds in the
 *  other sensor's view (\a other_view) when moved by T into its frame. */
std::vector<bool>
markedByTheOther (const Eigen::Matrix2Xd& scan, const detail::SensorView& other_view, const Rigid2d& T,
                  const std::vector<bool>& candidate, ViewTest test)
{
  std::vector<bool> marked (candidate.size (), false);
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
    marked[i] = candidate[i] && test (other_view.profile, T * scan.col (i), other_view.breakpoint);
  return marked;
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

/** Whether most points of \a group (points of \a scan), moved by \a T into the frame of
 *  \a occluder_scan, lie in the shadow of \a occluder (points of that scan): within its
 *  bearings as that scan's sensor sees them, widened by \a step on each side [rad]. */
bool
inShadowOf (const Eigen::Matrix2Xd& scan, const MovedGroup& group, const Rigid2d& T,
            const Eigen::Matrix2Xd& occluder_scan, const MovedGroup& occluder, double step)
{
  const Eigen::Vector2d first = occluder_scan.col (occluder.points.front ());
  const double reference = std::atan2 (first.y (), first.x ());
  const auto bearing = [reference] (const Eigen::Vector2d& p) {  // relative to the reference, in [−π, π]
    return std::remainder (std::atan2 (p.y (), p.x ()) - reference, 2.0 * M_PI);
  };
  double low = 0.0, high = 0.0;
  for (int j : occluder.points) {
    low = std::min (low, bearing (occluder_scan.col (j)));
    high = std::max (high, bearing (occluder_scan.col (j)));
  }
  std::size_t shadowed = 0;
  for (int i : group.points) {
    const double b = bearing (T * scan.col (i));
    shadowed += b >= low - step && b <= high + step ? 1 : 0;
  }
  return 2 * shadowed > group.points.size ();
}

/** Whether a point of \a group (points of \a scan, in beam order) has a neighbour in
 *  beam order outside the group that \a on_static_surface marks and that continues its
 *  surface: the next beam's return (their bearings at most 1.5 steps apart) within the
 *  breakpoint distance (at the smaller range). Such a group is a stretch of a surface the
 *  static motion explains on either side of it, hidden in the middle (a wall behind a
 *  walker), not an object's view, which ends at the object's own edges. */
bool
continuesAStaticSurface (const Eigen::Matrix2Xd& scan, const MovedGroup& group,
                         const std::vector<bool>& on_static_surface, const detail::SensorView& view)
{
  std::vector<bool> in_group (on_static_surface.size (), false);
  for (int i : group.points)
    in_group[i] = true;
  const auto bearing = [&scan] (Eigen::Index i) { return std::atan2 (scan (1, i), scan (0, i)); };
  for (int i : group.points)
    for (const int j : {i - 1, i + 1}) {
      if (j < 0 || j >= scan.cols () || in_group[j] || !on_static_surface[j])
        continue;
      const double step = std::abs (std::remainder (bearing (j) - bearing (i), 2.0 * M_PI));
      const double range = std::min (scan.col (i).norm (), scan.col (j).norm ());
      if (step <= 1.5 * view.profile.step &&
          (scan.col (j) - scan.col (i)).norm () <= range * view.breakpoint.slope + view.breakpoint.offset)
        return true;
    }
  return false;
}

/** The groups of \a groups not marked in \a paired. */
std::vector<MovedGroup>
unpaired (const std::vector<MovedGroup>& groups, const std::vector<bool>& paired)
{
  std::vector<MovedGroup> left;
  for (std::size_t g = 0; g < groups.size (); ++g)
    if (!paired[g])
      left.push_back (groups[g]);
  return left;
}

/** \a candidate without the points of \a groups. */
std::vector<bool>
withoutGroups (std::vector<bool> candidate, const std::vector<MovedGroup>& groups)
{
  for (const MovedGroup& group : groups)
    for (int i : group.points)
      candidate[i] = false;
  return candidate;
}

/** One object seen by one sensor in the other's free space (\a seen, without a
 *  counterpart there) and hidden from it (a group of \a hidden): per group of \a seen,
 *  the group of \a hidden it pairs with, or -1. They pair when each is the other's
 *  nearest (mutualCounterparts ()), both have at least min_segment_points (a point or
 *  two in free space or behind a return is noise as often as an object), most of the
 *  hidden group lies in the seen group's shadow (inShadowOf (), moved by \a T_to_seen
 *  into the seen group's scan frame): what hides an object's other view is the object
 *  itself, which came nearer along the line of sight or went farther; and the hidden
 *  group does not continue a surface the static motion explains
 *  (continuesAStaticSurface () with \a hidden_on_static_surface). */
std::vector<int>
shadowedCounterparts (const std::vector<MovedGroup>& seen, const Eigen::Matrix2Xd& seen_scan,
                      const detail::SensorView& seen_view, const std::vector<MovedGroup>& hidden,
                      const Eigen::Matrix2Xd& hidden_scan, const detail::SensorView& hidden_view,
                      const std::vector<bool>& hidden_on_static_surface, const Rigid2d& T_to_seen,
                      const matching::SegmentMotionParameters& parameters)
{
  std::vector<int> counterpart = mutualCounterparts (seen, hidden, parameters.max_displacement);
  for (std::size_t a = 0; a < seen.size (); ++a) {
    const int b = counterpart[a];
    if (b >= 0 && (static_cast<int> (std::min (seen[a].points.size (), hidden[b].points.size ())) <
                       parameters.min_segment_points ||
                   !inShadowOf (hidden_scan, hidden[b], T_to_seen, seen_scan, seen[a], seen_view.profile.step) ||
                   continuesAStaticSurface (hidden_scan, hidden[b], hidden_on_static_surface, hidden_view)))
      counterpart[a] = -1;
  }
  return counterpart;
}

/** The source group (an object's view in the source) joins a new cluster of motion T:
 *  each point takes the nearest point of the target group (its view in the target)
 *  within its overlap radius, or no match. */
void
addCluster (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const MovedGroup& source_group,
            const MovedGroup& target_group, const Rigid2d& T, const matching::SegmentMotionParameters& parameters,
            JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  for (int i : source_group.points) {
    const Eigen::Vector2d moved = T * source.col (i);
    int match = kNoMatch;
    double nearest = std::numeric_limits<double>::infinity ();
    for (int j : target_group.points) {
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

/** The points of each scan on a surface the static motion explains: static source points
 *  it puts within their overlap radius of their match, and those matches. */
struct StaticSurface
{
  std::vector<bool> source;
  std::vector<bool> target;
};

StaticSurface
staticSurface (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Rigid2d& T_static,
               const matching::SegmentMotionParameters& parameters, const JointResult& result)
{
  StaticSurface surface{std::vector<bool> (static_cast<std::size_t> (source.cols ()), false),
                        std::vector<bool> (static_cast<std::size_t> (target.cols ()), false)};
  for (Eigen::Index i = 0; i < source.cols (); ++i) {
    const int j = result.source_match[i];
    if (result.source_cluster[i] != result.static_cluster || j == kNoMatch)
      continue;
    const double radius = matching::overlapRadius (parameters, matching::pointSpacing (source, i, 0, source.cols ()));
    if ((T_static * source.col (i) - target.col (j)).norm () <= radius)
      surface.source[i] = surface.target[j] = true;
  }
  return surface;
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
      source, views.sourceSegments (),
      markedByTheOther (source, views.targetView (), T_static, free, matching::seesThroughToAReturn), T_static);
  const std::vector<matching::ScanSegment>& target_segments = views.targetSegments ();
  const std::vector<bool> unclaimed = unclaimedTargets (target_segments, target.cols (), free, result);
  const std::vector<MovedGroup> moved_in = groupBySegment (
      target, target_segments,
      markedByTheOther (target, views.sourceView (), T_static.inverse (), unclaimed, matching::seesThroughToAReturn),
      Rigid2d::Identity ());
  if (moved_out.empty () && moved_in.empty ())
    return 0;
  int added = 0;
  const auto pair = [&] (const MovedGroup& source_group, const MovedGroup& target_group) {
    Rigid2d T = T_static;  // the static motion shifted by the object's displacement
    T.translation () += target_group.centroid - source_group.centroid;
    addCluster (source, target, source_group, target_group, T, parameters, result);
    ++added;
  };
  // An object seen before and after it moved: it left free space in both views.
  const std::vector<int> counterpart = mutualCounterparts (moved_out, moved_in, parameters.max_displacement);
  std::vector<bool> out_paired (moved_out.size (), false), in_paired (moved_in.size (), false);
  for (std::size_t a = 0; a < moved_out.size (); ++a)
    if (counterpart[a] >= 0) {
      pair (moved_out[a], moved_in[counterpart[a]]);
      out_paired[a] = in_paired[counterpart[a]] = true;
    }
  // The hidden views below are sought only for groups left without a counterpart.
  const std::vector<MovedGroup> came_in = unpaired (moved_in, in_paired);
  const std::vector<MovedGroup> went_out = unpaired (moved_out, out_paired);
  const StaticSurface on_static_surface = came_in.empty () && went_out.empty ()
                                              ? StaticSurface ()
                                              : staticSurface (source, target, T_static, parameters, result);
  // An object that came nearer: its source view, under the static motion, hides behind
  // it in the target (no moved-out group).
  const std::vector<MovedGroup> hidden_source =
      came_in.empty () ? std::vector<MovedGroup> ()
                       : groupBySegment (source, views.sourceSegments (),
                                         markedByTheOther (source, views.targetView (), T_static,
                                                           withoutGroups (free, moved_out),
                                                           matching::hiddenBehindAReturn),
                                         T_static);
  const std::vector<int> nearer =
      shadowedCounterparts (came_in, target, views.targetView (), hidden_source, source, views.sourceView (),
                            on_static_surface.source, T_static, parameters);
  for (std::size_t b = 0; b < came_in.size (); ++b)
    if (nearer[b] >= 0)
      pair (hidden_source[nearer[b]], came_in[b]);
  // An object that went farther: its target view, under the inverse static motion,
  // hides behind it in the source (no moved-in group). Unpaired moved-out groups can
  // also have left the view or hidden behind something else: they stay.
  const std::vector<MovedGroup> hidden_target =
      went_out.empty () ? std::vector<MovedGroup> ()
                        : groupBySegment (target, target_segments,
                                          markedByTheOther (target, views.sourceView (), T_static.inverse (),
                                                            withoutGroups (unclaimed, moved_in),
                                                            matching::hiddenBehindAReturn),
                                          Rigid2d::Identity ());
  const std::vector<int> farther =
      shadowedCounterparts (went_out, source, views.sourceView (), hidden_target, target, views.targetView (),
                            on_static_surface.target, T_static.inverse (), parameters);
  for (std::size_t a = 0; a < went_out.size (); ++a)
    if (farther[a] >= 0)
      pair (went_out[a], hidden_target[farther[a]]);
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
