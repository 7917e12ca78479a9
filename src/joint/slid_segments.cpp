#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

using detail::TargetPlacement;

/** How a shifted placement fares against the static one on the points both keep in
 *  the target's field of view (a point leaving it says nothing for or against). */
struct Comparison
{
  int explained = 0;
  int seen_through = 0;
  int static_explained = 0;
  int static_seen_through = 0;

  Comparison (const TargetPlacement& at_static, const TargetPlacement& shifted)
  {
    for (std::size_t k = 0; k < at_static.in_view.size (); ++k) {
      if (!at_static.in_view[k] || !shifted.in_view[k])
        continue;
      static_explained += at_static.explained[k] ? 1 : 0;
      explained += shifted.explained[k] ? 1 : 0;
      static_seen_through += at_static.seen_through[k] ? 1 : 0;
      seen_through += shifted.seen_through[k] ? 1 : 0;
    }
  }

  /** explained minus seen-through points, gained over the static motion. */
  int
  gain () const
  {
    return (explained - seen_through) - (static_explained - static_seen_through);
  }

  /** The shift explains at least as many points and leaves fewer in free space. */
  bool
  dominates () const
  {
    return explained >= static_explained && seen_through < static_seen_through;
  }
};

/** Whether every point of \a segment is in the static world or among the outliers. */
bool
outsideMovingClusters (const matching::ScanSegment& segment, const JointResult& result)
{
  for (int i = segment.begin; i < segment.end; ++i)
    if (!detail::inStaticWorldOrOutliers (result, static_cast<std::size_t> (i)))
      return false;
  return true;
}

/** The best qualifying end-alignment shift of a segment: its gain (0 when none
 *  qualifies, or when the segment's shape does not tell where it went), the shift and
 *  the placement it gives. */
struct Slide
{
  int gain = 0;
  Eigen::Vector2d shift = Eigen::Vector2d::Zero ();
  TargetPlacement placement;
};

/** Whether another qualifying shift, farther than \a radius from the best one, explains
 *  the segment as well, or within one point (a point at the edge of its overlap radius
 *  tells nothing): then its shape does not single out where it went (a leg or a post
 *  of a few points fits the end of many surfaces; a truck's side fits one). */
bool
placedAmbiguously (const Slide& best, const std::vector<std::pair<int, Eigen::Vector2d>>& qualifying, double radius)
{
  for (const auto& [gain, shift] : qualifying)
    if (gain >= best.gain - 1 && (shift - best.shift).norm () > radius)
      return true;
  return false;
}

Slide
bestSlide (const matching::ScanSegment& segment, const Eigen::Matrix2Xd& at_static, const detail::ScanViews& views,
           detail::SeenThrough test)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const matching::SegmentMotionParameters& parameters = views.parameters ();
  const std::vector<Eigen::Vector2d> shifts =
      matching::endAlignments (at_static.col (0), at_static.col (segment.size () - 1),
                               matching::objectEnds (source, segment), views.target (), views.targetSegments (),
                               parameters);
  const std::vector<double> radii_squared = detail::squaredOverlapRadii (source, segment, parameters);
  const TargetPlacement static_placement = detail::placeInTarget (at_static, radii_squared, views, test);
  Slide best;
  std::vector<std::pair<int, Eigen::Vector2d>> qualifying;  // gain, shift
  for (std::size_t h = 1; h < shifts.size (); ++h) {  // shifts[0] is the static motion itself
    TargetPlacement shifted = detail::placeInTarget (at_static.colwise () + shifts[h], radii_squared, views, test);
    const Comparison c (static_placement, shifted);
    if (!c.dominates ())
      continue;
    qualifying.emplace_back (c.gain (), shifts[h]);
    if (c.gain () > best.gain)
      best = {c.gain (), shifts[h], std::move (shifted)};
  }
  if (placedAmbiguously (best, qualifying, parameters.overlap_radius))
    return {};
  return best;
}

/** Which of the target's beams tell that it saw through the points of \a segment: beams
 *  without a return as well (detail::SeenThrough::Firmly) when the source sensor
 *  returned from the segment's surface on every beam but single ones, otherwise only
 *  returns beyond them. A surface the sensor skipped runs of beams on is one it drops
 *  returns from (dark, glossy, far or seen at a grazing angle), and then the target's
 *  beams without a return where the static motion puts it say nothing: on the real
 *  intersection bag a "segment" of 6 returns over 25° was slid 1.1 m on three such
 *  beams. One missing beam is allowed anywhere, as matching::seesThroughFirmly ()
 *  allows a dropped edge return: the real scanners' samples leave single 1° bins empty. */
detail::SeenThrough
seenThroughTest (const matching::ScanSegment& segment, const detail::ScanViews& views)
{
  const double step = views.sourceView ().profile.step;
  return step > 0.0 && matching::longestMissingRun (views.source (), segment, step) <= 1 ? detail::SeenThrough::Firmly
                                                                                         : detail::SeenThrough::ToAReturn;
}

/** The segment joins a new cluster of motion \a T; each point takes its nearest target
 *  point there when explained, or no match. */
void
addCluster (const matching::ScanSegment& segment, const Rigid2d& T, const TargetPlacement& placement, JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  for (int k = 0; k < segment.size (); ++k) {
    result.source_cluster[segment.begin + k] = cluster;
    result.source_match[segment.begin + k] = placement.explained[k] ? placement.nearest.indices (0, k) : kNoMatch;
  }
}

}  // namespace

int
detail::separateSegmentsTheTargetSeesThrough (const ScanViews& views, int min_seen_through, JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const matching::SegmentMotionParameters& parameters = views.parameters ();
  checkResultAgainstScans ("separateSegmentsTheTargetSeesThrough", source, views.target (), result);
  if (min_seen_through < 1)
    throw std::invalid_argument ("[pcl_crf::joint::separateSegmentsTheTargetSeesThrough] min_seen_through must be "
                                 ">= 1, got " + std::to_string (min_seen_through));
  if (!canSeparateFromStaticWorld (source, views.target (), result))
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  const detail::SensorView& seen = views.targetView ();
  int added = 0;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    if (segment.size () < parameters.min_segment_points || !outsideMovingClusters (segment, result))
      continue;
    const Eigen::Matrix2Xd at_static = T_static * source.middleCols (segment.begin, segment.size ());
    const std::vector<bool> grazed = detail::grazedPoints (at_static, parameters.breakpoint_angle);
    const detail::SeenThrough test = seenThroughTest (segment, views);
    int seen_through = 0;
    for (Eigen::Index k = 0; k < at_static.cols (); ++k)
      seen_through += !grazed[k] && detail::sawThrough (seen, at_static.col (k), test) ? 1 : 0;
    if (seen_through < min_seen_through)
      continue;
    const Slide slide = bestSlide (segment, at_static, views, test);
    if (slide.gain == 0)
      continue;
    Rigid2d T = T_static;
    T.translation () += slide.shift;
    addCluster (segment, T, slide.placement, result);
    ++added;
  }
  if (added > 0)
    numberLargestFirst (result);
  return added;
}

int
separateSegmentsTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, int min_seen_through,
                                      JointResult& result)
{
  return detail::separateSegmentsTheTargetSeesThrough (detail::ScanViews (source, target, parameters),
                                                       min_seen_through, result);
}

}  // namespace joint
}  // namespace pcl_crf
