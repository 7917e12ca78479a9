#pragma once
// Small hand-made scan pairs for tests that must not depend on the simulator.

#include <pcl_crf/core/scan_pair.h>

#include <cmath>
#include <vector>

namespace pcl_crf {
namespace test {

/** The motion that moves every point by (\a x, \a y). */
inline Rigid2d
translation (double x, double y)
{
  return Rigid2d (Eigen::Translation2d (x, y));
}

/** \a points as the columns of a 2 x N matrix, in order. */
inline Eigen::Matrix2Xd
asColumns (const std::vector<Eigen::Vector2d>& points)
{
  Eigen::Matrix2Xd xy (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t i = 0; i < points.size (); ++i)
    xy.col (static_cast<Eigen::Index> (i)) = points[i];
  return xy;
}

/** Points every \a step metres along the walls of an axis-aligned room
 *  [x0, x1] x [y0, y1], counter-clockwise. */
inline Eigen::Matrix2Xd
roomOutline (double x0, double x1, double y0, double y1, double step)
{
  std::vector<Eigen::Vector2d> points;
  const Eigen::Vector2d corners[5] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d a = corners[side], b = corners[side + 1];
    const int count = static_cast<int> ((b - a).norm () / step);
    for (int k = 0; k < count; ++k)
      points.push_back (a + (b - a) * (static_cast<double> (k) / count));
  }
  return asColumns (points);
}

/** A static room seen from two poses: the target is the source moved by
 *  \a T_target_source, every source point matches the target point of the same
 *  index. Odometry = the true motion perturbed by \a odometry_error. */
inline ScanPair
staticRoomPair (const Rigid2d& T_target_source, const Rigid2d& odometry_error = Rigid2d::Identity (),
                double step = 0.1)
{
  ScanPair pair;
  pair.name = "room";
  pair.source = roomOutline (-4.0, 6.0, -3.0, 5.0, step);
  pair.target = T_target_source * pair.source;
  const auto n = static_cast<std::size_t> (pair.source.cols ());
  pair.sensor = {static_cast<int> (n), -M_PI, 2 * M_PI / n, 30.0};
  pair.source_object.assign (n, 0);
  pair.target_object.assign (n, 0);
  pair.source_match.resize (n);
  for (std::size_t i = 0; i < n; ++i)
    pair.source_match[i] = static_cast<int> (i);
  pair.objects.push_back ({0, true, T_target_source, "world"});
  pair.odometry.T_source_target = T_target_source.inverse () * odometry_error;
  pair.odometry.covariance = Eigen::Vector3d (0.01, 0.01, 0.001).asDiagonal ();
  return pair;
}

}  // namespace test
}  // namespace pcl_crf
