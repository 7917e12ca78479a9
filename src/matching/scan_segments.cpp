#include <pcl_crf/matching/scan_segments.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace matching {

namespace {

/** |bearing(q) − bearing(p)| wrapped to [0, π]. */
double
bearingStep (const Eigen::Vector2d& p, const Eigen::Vector2d& q)
{
  const double d = std::abs (std::atan2 (q.y (), q.x ()) - std::atan2 (p.y (), p.x ()));
  return d > M_PI ? 2.0 * M_PI - d : d;
}

/** Adaptive breakpoint test between consecutive points p, q (Borges & Aldon, 2004). */
bool
isBreakpoint (const Eigen::Vector2d& p, const Eigen::Vector2d& q, double breakpoint_angle, double range_noise)
{
  const double dphi = bearingStep (p, q);
  if (dphi >= breakpoint_angle)
    return true;
  const double range = std::min (p.norm (), q.norm ());
  const double threshold = range * std::sin (dphi) / std::sin (breakpoint_angle - dphi) + 3.0 * range_noise;
  return (q - p).norm () > threshold;
}

/** The end point \a end has the point \a across beyond its breakpoint farther away. */
bool
isObjectEnd (const Eigen::Matrix2Xd& scan, int end, int across)
{
  return across >= 0 && across < scan.cols () && scan.col (across).squaredNorm () > scan.col (end).squaredNorm ();
}

}  // namespace

std::vector<ScanSegment>
segmentScan (const Eigen::Matrix2Xd& points, double breakpoint_angle, double range_noise)
{
  std::vector<ScanSegment> segments;
  const int n = static_cast<int> (points.cols ());
  int begin = 0;
  for (int i = 1; i <= n; ++i)
    if (i == n || isBreakpoint (points.col (i - 1), points.col (i), breakpoint_angle, range_noise)) {
      segments.push_back ({begin, i});
      begin = i;
    }
  return segments;
}

std::vector<int>
segmentOfEachPoint (const std::vector<ScanSegment>& segments, Eigen::Index points)
{
  std::vector<int> of (static_cast<std::size_t> (points), -1);
  for (std::size_t s = 0; s < segments.size (); ++s)
    for (int i = segments[s].begin; i < segments[s].end; ++i)
      of[i] = static_cast<int> (s);
  return of;
}

SegmentEnds
objectEnds (const Eigen::Matrix2Xd& points, const ScanSegment& segment)
{
  return {isObjectEnd (points, segment.begin, segment.begin - 1), isObjectEnd (points, segment.end - 1, segment.end)};
}

Eigen::Matrix2Xd
segmentNormals (const Eigen::Matrix2Xd& points, const std::vector<ScanSegment>& segments)
{
  constexpr int kReach = 2;  // chord between the points two places before and after
  Eigen::Matrix2Xd normals = Eigen::Matrix2Xd::Zero (2, points.cols ());
  for (const ScanSegment& segment : segments) {
    if (segment.size () < 2)
      continue;
    for (int j = segment.begin; j < segment.end; ++j) {
      const Eigen::Vector2d chord =
          points.col (std::min (j + kReach, segment.end - 1)) - points.col (std::max (j - kReach, segment.begin));
      if (chord.squaredNorm () > 0.0)
        normals.col (j) = Eigen::Vector2d (-chord.y (), chord.x ()).normalized ();
    }
  }
  return normals;
}

}  // namespace matching
}  // namespace pcl_crf
