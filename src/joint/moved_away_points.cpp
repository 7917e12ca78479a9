#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Per point of \a segment: whether it is in the outlier cluster and the target saw
 *  through to a return beyond where \a T_static puts it (matching::seesThroughToAReturn
 *  (): a direction without a return may be a dropped one), its beam not grazing the
 *  segment (detail::grazedPoints ()). */
std::vector<bool>
seenLeaving (const detail::ScanViews& views, const matching::ScanSegment& segment, const Rigid2d& T_static,
             const JointResult& result)
{
  const Eigen::Matrix2Xd at_static = T_static * views.source ().middleCols (segment.begin, segment.size ());
  const std::vector<bool> grazed = detail::grazedPoints (at_static, views.parameters ().breakpoint_angle);
  const detail::SensorView& seen = views.targetView ();
  std::vector<bool> leaving (static_cast<std::size_t> (segment.size ()), false);
  for (Eigen::Index k = 0; k < at_static.cols (); ++k)
    leaving[k] = result.source_cluster[segment.begin + k] == kOutlierCluster && !grazed[k] &&
                 matching::seesThroughToAReturn (seen.profile, at_static.col (k), seen.breakpoint);
  return leaving;
}

/** Appends to \a moved_away every run of at least \a min_points consecutive points of
 *  \a segment that \a leaving marks. */
void
appendRuns (const matching::ScanSegment& segment, const std::vector<bool>& leaving, int min_points,
            std::vector<int>& moved_away)
{
  int k = 0;
  const int n = segment.size ();
  while (k < n) {
    if (!leaving[k]) {
      ++k;
      continue;
    }
    int end = k;
    while (end < n && leaving[end])
      ++end;
    if (end - k >= min_points)
      for (int j = k; j < end; ++j)
        moved_away.push_back (segment.begin + j);
    k = end;
  }
}

}  // namespace

int
detail::markPointsThatMovedAway (const ScanViews& views, JointResult& result)
{
  const Eigen::Matrix2Xd& source = views.source ();
  checkResultAgainstScans ("markPointsThatMovedAway", source, views.target (), result);
  std::vector<int> earlier;  // marked by an earlier step, and still outliers
  for (int i : result.moved_away)
    if (i >= 0 && static_cast<std::size_t> (i) < result.source_cluster.size () &&
        result.source_cluster[i] == kOutlierCluster)
      earlier.push_back (i);
  result.moved_away.clear ();
  if (!canSeparateFromStaticWorld (source, views.target (), result))
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  const int min_points = views.parameters ().min_segment_points;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    const auto first = result.source_cluster.begin () + segment.begin;
    if (std::count (first, first + segment.size (), kOutlierCluster) < min_points)
      continue;  // no run of outliers long enough
    appendRuns (segment, seenLeaving (views, segment, T_static, result), min_points, result.moved_away);
  }
  markMovedAway (earlier, result);
  return static_cast<int> (result.moved_away.size ());
}

int
markPointsThatMovedAway (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                         const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  return detail::markPointsThatMovedAway (detail::ScanViews (source, target, parameters), result);
}

}  // namespace joint
}  // namespace pcl_crf
