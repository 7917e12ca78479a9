#include <pcl_crf/core/beam_order.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pcl_crf {

namespace {

constexpr double kPi = 3.14159265358979323846;

/** Whether \a point has a bearing (is off the sensor's origin). */
bool
hasBearing (const Eigen::Vector2d& point)
{
  return point.x () != 0.0 || point.y () != 0.0;
}

/** \a angle wrapped into (−π, π]. */
double
wrapped (double angle)
{
  angle = std::remainder (angle, 2.0 * kPi);
  return angle <= -kPi ? angle + 2.0 * kPi : angle;
}

/** Which way round a scan's bearings go. */
enum class Turn
{
  kCounterClockwise,
  kClockwise,
  kBothWays
};

/** Which way every bearing step of \a points goes, told without an atan2: the sign of
 *  the cross product of consecutive points (a step of 0 has none, one of π is told by
 *  the atan2s). kCounterClockwise also when no step has a sign. */
Turn
turnOfEveryStep (const Eigen::Matrix2Xd& points)
{
  bool counter_clockwise = false, clockwise = false;
  Eigen::Vector2d previous;
  bool started = false;
  for (Eigen::Index k = 0; k < points.cols (); ++k) {
    const Eigen::Vector2d point = points.col (k);
    if (!hasBearing (point))
      continue;
    if (started) {
      const double cross = previous.x () * point.y () - previous.y () * point.x ();
      if (cross == 0.0 && previous.dot (point) <= 0.0)
        return Turn::kBothWays;
      counter_clockwise = counter_clockwise || cross > 0.0;
      clockwise = clockwise || cross < 0.0;
    }
    previous = point;
    started = true;
  }
  if (counter_clockwise && clockwise)
    return Turn::kBothWays;
  return clockwise ? Turn::kClockwise : Turn::kCounterClockwise;
}

/** The bearing steps of a scan's points (each wrapped into (−π, π]), summed by the way they turn. */
struct BearingWay
{
  double counter_clockwise = 0.0;
  double clockwise = 0.0;
  int bearings = 0;  // points that have a bearing

  /** The way back against the main direction, as a fraction of the main direction's way. */
  double
  backtrack () const
  {
    const double way = std::max (counter_clockwise, clockwise);
    return bearings < 3 || way == 0.0 ? 0.0 : std::min (counter_clockwise, clockwise) / way;
  }
};

BearingWay
bearingWay (const Eigen::Matrix2Xd& points)
{
  BearingWay way;
  double previous = 0.0;
  for (Eigen::Index k = 0; k < points.cols (); ++k) {
    if (!hasBearing (points.col (k)))
      continue;
    const double bearing = std::atan2 (points (1, k), points (0, k));
    if (way.bearings++ > 0) {
      const double step = wrapped (bearing - previous);
      (step > 0.0 ? way.counter_clockwise : way.clockwise) += std::abs (step);
    }
    previous = bearing;
  }
  return way;
}

/** How a scan is to be read for the chains. */
enum class Reading
{
  kAsItIs,                   // in beam order, counter-clockwise
  kBackwards,                // in beam order, clockwise
  kByBearing,                // in no beam order, mostly counter-clockwise
  kByBearingListedClockwise  // in no beam order, mostly clockwise
};

Reading
readingOf (const Eigen::Matrix2Xd& points)
{
  const Turn turn = turnOfEveryStep (points);
  if (turn != Turn::kBothWays)
    return turn == Turn::kClockwise ? Reading::kBackwards : Reading::kAsItIs;
  const BearingWay way = bearingWay (points);
  if (way.backtrack () > kBeamOrderBacktrack)
    return way.clockwise > way.counter_clockwise ? Reading::kByBearingListedClockwise : Reading::kByBearing;
  return way.clockwise > way.counter_clockwise ? Reading::kBackwards : Reading::kAsItIs;
}

/** The indices of \a points sorted by bearing, counter-clockwise from the one after the
 *  widest gap, the origin's points first, equal bearings in index order (decreasing when
 *  \a listed_clockwise: a scan and the same scan listed the other way round give one
 *  order of their points). */
std::vector<int>
sortedByBearing (const Eigen::Matrix2Xd& points, bool listed_clockwise)
{
  const auto n = static_cast<int> (points.cols ());
  std::vector<int> order (static_cast<std::size_t> (n));
  std::iota (order.begin (), order.end (), 0);
  std::vector<double> bearing (order.size (), -2.0 * kPi);  // the origin's points first
  for (int k = 0; k < n; ++k)
    if (hasBearing (points.col (k)))
      bearing[k] = std::atan2 (points (1, k), points (0, k));
  std::sort (order.begin (), order.end (), [&bearing, listed_clockwise] (int a, int b) {
    return bearing[a] < bearing[b] || (bearing[a] == bearing[b] && (listed_clockwise ? a > b : a < b));
  });
  // Start after the widest gap between consecutive bearings (the last to the first across ±π included).
  const auto first = static_cast<std::size_t> (std::count (bearing.begin (), bearing.end (), -2.0 * kPi));
  std::size_t start = first;
  double widest = -1.0;
  for (std::size_t k = first; k < order.size (); ++k) {
    const std::size_t before = k == first ? order.size () - 1 : k - 1;
    const double gap = k == first ? bearing[order[k]] + 2.0 * kPi - bearing[order[before]]
                                  : bearing[order[k]] - bearing[order[before]];
    if (gap > widest) {
      widest = gap;
      start = k;
    }
  }
  std::rotate (order.begin () + static_cast<long> (first), order.begin () + static_cast<long> (start), order.end ());
  return order;
}

/** \a order (a scan's points in beam order, counter-clockwise) read from the point
 *  after its widest break when its listing starts between two neighbouring beams that
 *  both returned (a 360° laser listing its circle from a beam in front of a surface):
 *  the widest gap between the bearings of neighbours, a sector without a return, or,
 *  where none is wider than neighbouring beams are apart (kNeighbourSteps median
 *  steps), the widest jump between neighbouring points, where its surfaces break. The
 *  chains are then cut at the same place from whichever such beam the listing starts,
 *  and not through the object in front of it. A scan whose listing starts at a gap (a
 *  laser's back, or the sector without a return it starts in) keeps its order. */
void
startAfterTheWidestBreak (const Eigen::Matrix2Xd& points, std::vector<int>& order)
{
  constexpr double kNeighbourSteps = 1.5;  // a step of more leaves a beam out
  const std::size_t n = order.size ();
  if (n < 3)
    return;
  std::vector<double> bearings (n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d point = points.col (order[k]);
    if (!hasBearing (point))
      return;  // no bearing to order by: read as listed
    bearings[k] = std::atan2 (point.y (), point.x ());
  }
  std::vector<double> gaps (n);  // counter-clockwise from point k − 1 (the last, for k = 0) to point k
  for (std::size_t k = 0; k < n; ++k)
    gaps[k] = wrapped (bearings[k] - bearings[(k + n - 1) % n]);
  std::vector<double> steps (gaps.begin () + 1, gaps.end ());
  const auto middle = steps.begin () + static_cast<long> (steps.size () / 2);
  std::nth_element (steps.begin (), middle, steps.end ());
  const double neighbours_apart = kNeighbourSteps * *middle;
  if (!(gaps[0] > 0.0 && gaps[0] <= neighbours_apart))
    return;  // the listing starts at a gap
  std::size_t start = static_cast<std::size_t> (std::max_element (gaps.begin (), gaps.end ()) - gaps.begin ());
  if (gaps[start] <= neighbours_apart) {  // a return on every beam: cut at the widest jump
    start = 0;
    double widest = (points.col (order.front ()) - points.col (order.back ())).squaredNorm ();
    for (std::size_t k = 1; k < n; ++k) {
      const double jump = (points.col (order[k]) - points.col (order[k - 1])).squaredNorm ();
      if (jump > widest) {
        widest = jump;
        start = k;
      }
    }
  }
  std::rotate (order.begin (), order.begin () + static_cast<long> (start), order.end ());
}

}  // namespace

double
bearingBacktrack (const Eigen::Matrix2Xd& points)
{
  if (turnOfEveryStep (points) != Turn::kBothWays)
    return 0.0;
  return bearingWay (points).backtrack ();
}

bool
inBeamOrder (const Eigen::Matrix2Xd& points)
{
  return readingOf (points) == Reading::kAsItIs;
}

std::vector<int>
beamOrder (const Eigen::Matrix2Xd& points)
{
  const Reading reading = readingOf (points);
  std::vector<int> order;
  if (reading == Reading::kByBearing || reading == Reading::kByBearingListedClockwise) {
    order = sortedByBearing (points, reading == Reading::kByBearingListedClockwise);
  }
  else {
    order.resize (static_cast<std::size_t> (points.cols ()));
    std::iota (order.begin (), order.end (), 0);
    if (reading == Reading::kBackwards)
      std::reverse (order.begin (), order.end ());
  }
  startAfterTheWidestBreak (points, order);
  return order;
}

}  // namespace pcl_crf
