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

/** Whether every bearing step of \a points goes one way round (then bearingBacktrack ()
 *  is 0), told without an atan2: the sign of the cross product of consecutive points (a
 *  step of 0 has none, one of π is told by the atan2s). */
bool
turnsOneWay (const Eigen::Matrix2Xd& points)
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
        return false;
      counter_clockwise = counter_clockwise || cross > 0.0;
      clockwise = clockwise || cross < 0.0;
    }
    previous = point;
    started = true;
  }
  return !(counter_clockwise && clockwise);
}

}  // namespace

double
bearingBacktrack (const Eigen::Matrix2Xd& points)
{
  if (turnsOneWay (points))
    return 0.0;
  double counter_clockwise = 0.0, clockwise = 0.0, previous = 0.0;
  int bearings = 0;
  for (Eigen::Index k = 0; k < points.cols (); ++k) {
    if (!hasBearing (points.col (k)))
      continue;
    const double bearing = std::atan2 (points (1, k), points (0, k));
    if (bearings++ > 0) {
      const double step = wrapped (bearing - previous);
      (step > 0.0 ? counter_clockwise : clockwise) += std::abs (step);
    }
    previous = bearing;
  }
  const double way = std::max (counter_clockwise, clockwise);
  return bearings < 3 || way == 0.0 ? 0.0 : std::min (counter_clockwise, clockwise) / way;
}

bool
inBeamOrder (const Eigen::Matrix2Xd& points)
{
  return bearingBacktrack (points) <= kBeamOrderBacktrack;
}

std::vector<int>
beamOrder (const Eigen::Matrix2Xd& points)
{
  const auto n = static_cast<int> (points.cols ());
  std::vector<int> order (static_cast<std::size_t> (n));
  std::iota (order.begin (), order.end (), 0);
  if (inBeamOrder (points))
    return order;
  std::vector<double> bearing (order.size (), -2.0 * kPi);  // the origin's points first
  for (int k = 0; k < n; ++k)
    if (hasBearing (points.col (k)))
      bearing[k] = std::atan2 (points (1, k), points (0, k));
  std::stable_sort (order.begin (), order.end (), [&bearing] (int a, int b) { return bearing[a] < bearing[b]; });
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

}  // namespace pcl_crf
