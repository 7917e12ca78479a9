#pragma once
// A small box near the sensor between two far walls, for the joint model's steps that
// tell small motions from the static world (test_joint_segment_hypotheses.cpp,
// test_joint_slight_motions.cpp).

#include <pcl_crf/core/scan_pair.h>

#include <cmath>
#include <vector>

namespace pcl_crf {
namespace test {

constexpr int kWallPoints = 41;  // on each side
constexpr int kBoxPoints = 21;
constexpr int kBoxBegin = kWallPoints;
constexpr int kBoxEnd = kWallPoints + kBoxPoints;
constexpr int kPoints = 2 * kWallPoints + kBoxPoints;

/** A small box 0.6 m ahead of the sensor (its face x = 0.6, y from −0.1 to 0.1, 1 cm
 *  apart: a 1/10-scale car's back) between two walls 6 m away (bearings −60° … −20° and
 *  20° … 60°, every degree), in beam order; the box moved by \a box_motion. */
inline Eigen::Matrix2Xd
boxBetweenWalls (const Rigid2d& box_motion = Rigid2d::Identity ())
{
  Eigen::Matrix2Xd points (2, kPoints);
  const auto wall = [] (double degrees) {
    const double bearing = degrees * M_PI / 180.0;
    return Eigen::Vector2d (6.0 * std::cos (bearing), 6.0 * std::sin (bearing));
  };
  for (int k = 0; k < kWallPoints; ++k)
    points.col (k) = wall (-60.0 + k);
  for (int k = 0; k < kBoxPoints; ++k)
    points.col (kBoxBegin + k) = box_motion * Eigen::Vector2d (0.6, -0.1 + 0.01 * k);
  for (int k = 0; k < kWallPoints; ++k)
    points.col (kBoxEnd + k) = wall (20.0 + k);
  return points;
}

/** The walls of boxBetweenWalls () with \a middle (in beam order) in place of the box. */
inline Eigen::Matrix2Xd
wallsAround (const std::vector<Eigen::Vector2d>& middle)
{
  const Eigen::Matrix2Xd walls = boxBetweenWalls ();
  Eigen::Matrix2Xd points (2, 2 * kWallPoints + static_cast<Eigen::Index> (middle.size ()));
  points.leftCols (kWallPoints) = walls.leftCols (kWallPoints);
  for (std::size_t k = 0; k < middle.size (); ++k)
    points.col (kWallPoints + static_cast<Eigen::Index> (k)) = middle[k];
  points.rightCols (kWallPoints) = walls.rightCols (kWallPoints);
  return points;
}

/** Whether point \a i of boxBetweenWalls () is on the box. */
inline bool
onBox (int i)
{
  return i >= kBoxBegin && i < kBoxEnd;
}

}  // namespace test
}  // namespace pcl_crf
