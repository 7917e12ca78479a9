#include <pcl_crf/matching/scan_segments.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace matching {

namespace {

/** \throws std::invalid_argument, naming \a method, for a breakpoint angle outside
 *  (0, π/2] or a range noise that is not a distance ≥ 0 (NaN included). */
void
checkBreakpointSettings (const char* method, double breakpoint_angle, double range_noise)
{
  if (!(breakpoint_angle > 0.0 && breakpoint_angle <= M_PI / 2) || !(range_noise >= 0.0 && std::isfinite (range_noise)))
    throw std::invalid_argument (std::string ("[pcl_crf::matching::") + method +
                                 "] the breakpoint angle must be in (0, pi/2] rad and the range noise a distance "
                                 ">= 0 m, not " + std::to_string (breakpoint_angle) + " rad and " +
                                 std::to_string (range_noise) + " m");
}

/** |b − a| for bearings a, b, wrapped to [0, π]. */
double
bearingStep (double a, double b)
{
  const double d = std::abs (b - a);
  return d > M_PI ? 2.0 * M_PI - d : d;
}

/** The bearing atan2 (y, x) of every point. */
std::vector<double>
bearingsOf (const Eigen::Matrix2Xd& points)
{
  std::vector<double> bearings (static_cast<std::size_t> (points.cols ()));
  for (Eigen::Index i = 0; i < points.cols (); ++i)
    bearings[i] = std::atan2 (points (1, i), points (0, i));
  return bearings;
}

/** The sensor's angular step as the scan shows it: the median bearing step between
 *  consecutive points (0 with fewer than two). */
double
typicalStep (const std::vector<double>& bearings)
{
  if (bearings.size () < 2)
    return 0.0;
  std::vector<double> steps (bearings.size () - 1);
  for (std::size_t k = 0; k + 1 < bearings.size (); ++k)
    steps[k] = bearingStep (bearings[k], bearings[k + 1]);
  const auto middle = steps.begin () + static_cast<std::ptrdiff_t> (steps.size () / 2);
  std::nth_element (steps.begin (), middle, steps.end ());
  return *middle;
}

/** The beams without a return between two returns \a dphi apart in bearing, for a
 *  sensor of angular step \a step: round (Δφ / step) − 1. */
long
missingReturns (double dphi, double step)
{
  return std::lround (dphi / step) - 1;
}

/** Adaptive breakpoint test between consecutive points p, q, \a dphi apart in bearing
 *  (Borges & Aldon, 2004): ||q − p|| > k r sin Δφ / sin(λ − Δφ) + 3σ. Δφ = dphi and
 *  k = 1, unless the gap spans missing returns (\a step > 0, the sensor's step, and
 *  dphi > 1.5 steps): then Δφ = step and k = dphi / step, one step's distance per beam,
 *  and a gap of more than \a max_missing_returns beams (≥ 0) is a breakpoint. */
bool
isBreakpoint (const Eigen::Vector2d& p, const Eigen::Vector2d& q, double dphi, double step, double breakpoint_angle,
              double range_noise, int max_missing_returns = -1)
{
  if (dphi >= breakpoint_angle)
    return true;
  const double range = std::min (p.norm (), q.norm ());
  const bool missing_returns = step > 0.0 && step < breakpoint_angle && dphi > 1.5 * step;
  if (missing_returns && max_missing_returns >= 0 && missingReturns (dphi, step) > max_missing_returns)
    return true;
  const double one_step = missing_returns ? step : dphi;
  const double steps = missing_returns ? dphi / step : 1.0;
  const double threshold =
      steps * range * std::sin (one_step) / std::sin (breakpoint_angle - one_step) + 3.0 * range_noise;
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
segmentScan (const Eigen::Matrix2Xd& points, double breakpoint_angle, double range_noise, BeamGaps gaps,
             int max_missing_returns)
{
  checkBreakpointSettings ("segmentScan", breakpoint_angle, range_noise);
  if (max_missing_returns < -1)
    throw std::invalid_argument ("[pcl_crf::matching::segmentScan] max_missing_returns must be >= 0 beams, or -1 for "
                                 "any run; got " + std::to_string (max_missing_returns));
  std::vector<ScanSegment> segments;
  const int n = static_cast<int> (points.cols ());
  const std::vector<double> bearings = bearingsOf (points);
  const double step = gaps == BeamGaps::MissingReturns ? typicalStep (bearings) : 0.0;
  int begin = 0;
  for (int i = 1; i <= n; ++i)
    if (i == n || isBreakpoint (points.col (i - 1), points.col (i), bearingStep (bearings[i - 1], bearings[i]), step,
                                breakpoint_angle, range_noise, max_missing_returns)) {
      segments.push_back ({begin, i});
      begin = i;
    }
  return segments;
}

std::vector<int>
occludedSurfaces (const Eigen::Matrix2Xd& points, const std::vector<ScanSegment>& segments, double breakpoint_angle,
                  double range_noise)
{
  checkBreakpointSettings ("occludedSurfaces", breakpoint_angle, range_noise);
  int previous_end = 0;
  for (std::size_t s = 0; s < segments.size (); ++s) {
    if (segments[s].begin < previous_end || segments[s].end <= segments[s].begin || segments[s].end > points.cols ())
      throw std::invalid_argument ("[pcl_crf::matching::occludedSurfaces] segment " + std::to_string (s) + " [" +
                                   std::to_string (segments[s].begin) + ", " + std::to_string (segments[s].end) +
                                   ") is not a run of the scan's " + std::to_string (points.cols ()) +
                                   " points after the segment before it");
    previous_end = segments[s].end;
  }
  std::vector<int> surface (segments.size ());
  const std::vector<double> bearings = bearingsOf (points);
  const double step = typicalStep (bearings);
  for (std::size_t s = 0; s < segments.size (); ++s) {
    surface[s] = static_cast<int> (s);
    const int b = segments[s].begin;
    const double range_b = points.col (b).norm ();
    double farthest_between = 0.0;  // every point between a and b must be nearer than both
    for (std::size_t r = s; r-- > 0;) {
      if (r + 1 < s)
        for (int i = segments[r + 1].begin; i < segments[r + 1].end; ++i)
          farthest_between = std::max (farthest_between, points.col (i).norm ());
      const int a = segments[r].end - 1;
      const double dphi = bearingStep (bearings[a], bearings[b]);
      if (farthest_between >= range_b || dphi >= breakpoint_angle)
        break;  // a point between is not in front of b, or a and b are too far apart in bearing
      if (r + 1 == s || farthest_between >= points.col (a).norm ())
        continue;  // nothing between (segmentScan's own breakpoint), or a point between not in front of a
      if (!isBreakpoint (points.col (a), points.col (b), dphi, step, breakpoint_angle, range_noise)) {
        surface[s] = surface[r];
        break;
      }
    }
  }
  return surface;
}

namespace {

/** checkSegments () of one segment, without a vector to hold it (longestMissingRun runs per segment). */
void
checkSegment (const char* function, const ScanSegment& segment, Eigen::Index points)
{
  if (segment.begin < 0 || segment.end > points || segment.end <= segment.begin)
    throw std::invalid_argument (std::string ("[pcl_crf::matching::") + function + "] segment [" +
                                 std::to_string (segment.begin) + ", " + std::to_string (segment.end) +
                                 ") is not a run of the scan's " + std::to_string (points) + " points");
}

}  // namespace

void
checkSegments (const char* function, const std::vector<ScanSegment>& segments, Eigen::Index points)
{
  for (const ScanSegment& segment : segments)
    checkSegment (function, segment, points);
}

std::vector<int>
segmentOfEachPoint (const std::vector<ScanSegment>& segments, Eigen::Index points)
{
  checkSegments ("segmentOfEachPoint", segments, points);
  std::vector<int> of (static_cast<std::size_t> (points), -1);
  for (std::size_t s = 0; s < segments.size (); ++s)
    for (int i = segments[s].begin; i < segments[s].end; ++i)
      of[i] = static_cast<int> (s);
  return of;
}

int
longestMissingRun (const Eigen::Matrix2Xd& points, const ScanSegment& segment, double step)
{
  checkSegment ("longestMissingRun", segment, points.cols ());
  if (!(step > 0.0))
    throw std::invalid_argument ("[pcl_crf::matching::longestMissingRun] the sensor's step must be positive, got " +
                                 std::to_string (step));
  long longest = 0;
  double bearing = std::atan2 (points (1, segment.begin), points (0, segment.begin));
  for (int i = segment.begin + 1; i < segment.end; ++i) {
    const double next = std::atan2 (points (1, i), points (0, i));
    longest = std::max (longest, missingReturns (bearingStep (bearing, next), step));
    bearing = next;
  }
  return static_cast<int> (longest);
}

SegmentEnds
objectEnds (const Eigen::Matrix2Xd& points, const ScanSegment& segment)
{
  return {isObjectEnd (points, segment.begin, segment.begin - 1), isObjectEnd (points, segment.end - 1, segment.end)};
}

Eigen::Matrix2Xd
segmentNormals (const Eigen::Matrix2Xd& points, const std::vector<ScanSegment>& segments)
{
  checkSegments ("segmentNormals", segments, points.cols ());
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
