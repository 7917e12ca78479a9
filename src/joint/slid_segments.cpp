#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** What the target scan says of one segment: its points (target frame) are explained
 *  (a target point within their overlap radius) or seen through (to a return farther
 *  away), or neither. */
struct TargetView
{
  matching::RangeProfile profile;
  matching::BreakpointDistance breakpoint;
  KnnIndex points;
};

/** How a shifted and the unshifted static motion fare on the segment points both keep
 *  in the target's field of view (a point leaving it says nothing for or against). */
struct Comparison
{
  int explained = 0;
  int seen_through = 0;
  int static_explained = 0;
  int static_seen_through = 0;

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

/** Whether every point of \a segment is in the static or the outlier cluster. */
bool
outsideMovingClusters (const matching::ScanSegment& segment, const JointResult& result)
{
  for (int i = segment.begin; i < segment.end; ++i)
    if (result.source_cluster[i] != result.static_cluster && result.source_cluster[i] != kOutlierCluster)
      return false;
  return true;
}

int
countSeenThrough (const Eigen::Matrix2Xd& moved, const TargetView& view)
{
  int seen = 0;
  for (Eigen::Index k = 0; k < moved.cols (); ++k)
    seen += matching::seesThroughToAReturn (view.profile, moved.col (k), view.breakpoint) ? 1 : 0;
  return seen;
}

/** The squared overlap radius of every point of \a segment. */
std::vector<double>
squaredRadii (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
              const matching::SegmentMotionParameters& parameters)
{
  std::vector<double> radii;
  for (int i = segment.begin; i < segment.end; ++i) {
    const double r = matching::overlapRadius (parameters, matching::pointSpacing (source, i, segment.begin, segment.end));
    radii.push_back (r * r);
  }
  return radii;
}

/** The segment's points under the static motion (\a at_static) against the same points
 *  shifted by \a shift, with their nearest target points. */
Comparison
compare (const Eigen::Matrix2Xd& at_static, const Eigen::Matrix2Xd& shifted, const KnnIndex::Result& static_nearest,
         const KnnIndex::Result& shifted_nearest, const std::vector<double>& radii_squared, const TargetView& view)
{
  Comparison c;
  for (Eigen::Index k = 0; k < at_static.cols (); ++k) {
    if (!matching::inFieldOfView (view.profile, at_static.col (k)) ||
        !matching::inFieldOfView (view.profile, shifted.col (k)))
      continue;
    c.static_explained += static_nearest.squared_distances (0, k) <= radii_squared[k] ? 1 : 0;
    c.explained += shifted_nearest.squared_distances (0, k) <= radii_squared[k] ? 1 : 0;
    c.static_seen_through += matching::seesThroughToAReturn (view.profile, at_static.col (k), view.breakpoint) ? 1 : 0;
    c.seen_through += matching::seesThroughToAReturn (view.profile, shifted.col (k), view.breakpoint) ? 1 : 0;
  }
  return c;
}

/** The segment joins a new cluster of the static motion shifted by \a shift; each point
 *  takes its nearest target point there when within its overlap radius, or no match. */
void
addCluster (const matching::ScanSegment& segment, const Rigid2d& T, const KnnIndex::Result& nearest,
            const std::vector<double>& radii_squared, JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  for (int k = 0; k < segment.size (); ++k) {
    const bool near = nearest.squared_distances (0, k) <= radii_squared[k];
    result.source_cluster[segment.begin + k] = cluster;
    result.source_match[segment.begin + k] = near ? nearest.indices (0, k) : kNoMatch;
  }
}

}  // namespace

int
separateSegmentsTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, int min_seen_through,
                                      JointResult& result)
{
  detail::checkResultAgainstScans ("separateSegmentsTheTargetSeesThrough", source, target, result);
  if (min_seen_through < 1)
    throw std::invalid_argument ("[pcl_crf::joint::separateSegmentsTheTargetSeesThrough] min_seen_through must be "
                                 ">= 1, got " + std::to_string (min_seen_through));
  if (result.static_cluster < 0 || source.cols () < 2 || target.cols () < 2)
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  TargetView view{matching::makeRangeProfile (target), {}, {}};
  view.breakpoint = matching::breakpointDistance (view.profile, parameters.breakpoint_angle, parameters.range_noise);
  view.points.build (target);
  const std::vector<matching::ScanSegment> target_segments =
      matching::segmentScan (target, parameters.breakpoint_angle, parameters.range_noise);
  int added = 0;
  for (const matching::ScanSegment& segment :
       matching::segmentScan (source, parameters.breakpoint_angle, parameters.range_noise)) {
    if (segment.size () < parameters.min_segment_points || !outsideMovingClusters (segment, result))
      continue;
    const Eigen::Matrix2Xd at_static = T_static * source.middleCols (segment.begin, segment.size ());
    if (countSeenThrough (at_static, view) < min_seen_through)
      continue;
    const std::vector<Eigen::Vector2d> shifts =
        matching::endAlignments (at_static.col (0), at_static.col (segment.size () - 1),
                                 matching::objectEnds (source, segment), target, target_segments, parameters);
    const std::vector<double> radii_squared = squaredRadii (source, segment, parameters);
    const KnnIndex::Result static_nearest = view.points.search (at_static, 1);
    int best_gain = 0;
    KnnIndex::Result best_nearest;
    Eigen::Vector2d best_shift = Eigen::Vector2d::Zero ();
    for (std::size_t h = 1; h < shifts.size (); ++h) {  // shifts[0] is the static motion itself
      const Eigen::Matrix2Xd shifted = at_static.colwise () + shifts[h];
      KnnIndex::Result nearest = view.points.search (shifted, 1);
      const Comparison c = compare (at_static, shifted, static_nearest, nearest, radii_squared, view);
      if (c.dominates () && c.gain () > best_gain) {
        best_gain = c.gain ();
        best_shift = shifts[h];
        best_nearest = std::move (nearest);
      }
    }
    if (best_gain == 0)
      continue;
    Rigid2d T = T_static;
    T.translation () += best_shift;
    addCluster (segment, T, best_nearest, radii_squared, result);
    ++added;
  }
  if (added > 0)
    detail::numberLargestFirst (result);
  return added;
}

}  // namespace joint
}  // namespace pcl_crf
