#include <pcl_crf/joint/joint_estimation.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::kOutlierCluster;
using pcl_crf::Rigid2d;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::removeClustersTheTargetSeesThrough;

constexpr double kDegree = M_PI / 180.0;

/** A horizontal surface y = \a y, x in [\a x_min, \a x_max] [m], of object \a object. */
struct Surface
{
  double y;
  double x_min;
  double x_max;
  int object;
};

/** A scan of \a surfaces from the origin: beams every 0.5° over [0°, 180°], each
 *  returning its nearest surface (none: no return). \a objects gets every point's
 *  surface object, in beam order. */
Eigen::Matrix2Xd
rayCast (const std::vector<Surface>& surfaces, std::vector<int>& objects)
{
  std::vector<Eigen::Vector2d> points;
  objects.clear ();
  for (int k = 1; k < 360; ++k) {
    const double c = std::cos (0.5 * k * kDegree), s = std::sin (0.5 * k * kDegree);
    double nearest = std::numeric_limits<double>::infinity ();
    int object = -1;
    for (const Surface& surface : surfaces) {
      const double range = surface.y / s, x = range * c;
      if (x >= surface.x_min && x <= surface.x_max && range < nearest) {
        nearest = range;
        object = surface.object;
      }
    }
    if (object >= 0) {
      points.emplace_back (nearest * c, nearest * s);
      objects.push_back (object);
    }
  }
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t i = 0; i < points.size (); ++i)
    scan.col (static_cast<Eigen::Index> (i)) = points[i];
  return scan;
}

constexpr int kWall = 0, kCar = 1, kBoard = 2;

/** A wall along y = 8 m; a car along y = 4 m that drives 0.5 m along x; a board along
 *  y = 3 m that the target no longer sees (it left the view). */
struct Scene
{
  Eigen::Matrix2Xd source, target;
  std::vector<int> source_object, target_object;

  Scene ()
  {
    source = rayCast ({{8.0, -20.0, 20.0, kWall}, {4.0, 0.5, 1.5, kCar}, {3.0, -2.0, -1.0, kBoard}}, source_object);
    target = rayCast ({{8.0, -20.0, 20.0, kWall}, {4.0, 1.0, 2.0, kCar}}, target_object);
  }

  /** The target point nearest to \a point. */
  int
  nearestTarget (const Eigen::Vector2d& point) const
  {
    Eigen::Index j;
    (target.colwise () - point).colwise ().squaredNorm ().minCoeff (&j);
    return static_cast<int> (j);
  }
};

/** The wall in the static world (cluster 0, identity), the car in cluster 1 (its true
 *  motion), the board's last \a board_matched points in cluster 2 of motion \a T_board,
 *  every matched point taking the target point nearest to where its motion puts it,
 *  and the board's other points outliers. */
JointResult
sceneResult (const Scene& scene, const Rigid2d& T_board, int board_matched)
{
  JointResult result;
  Rigid2d T_car = Rigid2d::Identity ();
  T_car.translation () = Eigen::Vector2d (0.5, 0.0);
  result.cluster_motions = {Rigid2d::Identity (), T_car, T_board};
  result.static_cluster = 0;
  int board_points = 0;
  for (int object : scene.source_object)
    board_points += object == kBoard ? 1 : 0;
  int board_seen = 0;
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i) {
    int cluster = scene.source_object[i];
    if (cluster == kBoard && board_seen++ < board_points - board_matched)
      cluster = kOutlierCluster;
    result.source_cluster.push_back (cluster);
    result.source_match.push_back (cluster == kOutlierCluster
                                       ? kNoMatch
                                       : scene.nearestTarget (result.cluster_motions[cluster] * scene.source.col (i)));
  }
  return result;
}

Rigid2d
translation (double x, double y)
{
  Rigid2d T = Rigid2d::Identity ();
  T.translation () = Eigen::Vector2d (x, y);
  return T;
}

TEST (JointRefutedClusters, AClusterWhoseMotionSweepsItsSegmentThroughTheTargetsViewBecomesOutliers)
{
  // The board's last 3 points matched to the wall under a 2 m shift towards it: that
  // shift puts all of the board in front of the wall, where every target beam passed.
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = sceneResult (scene, translation (0.0, 2.0), 3);
  const std::vector<int> matches (result.source_match);
  ASSERT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_EQ (result.static_cluster, 0);
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i) {
    const int object = scene.source_object[i];
    if (object == kBoard) {
      EXPECT_EQ (result.source_cluster[i], kOutlierCluster) << i;
      EXPECT_EQ (result.source_match[i], kNoMatch) << i;
    }
    else {  // the wall and the car keep their clusters and matches
      EXPECT_EQ (result.source_cluster[i], object) << i;
      EXPECT_EQ (result.source_match[i], matches[i]) << i;
    }
  }
  EXPECT_EQ (result.cluster_motions[1].translation ().x (), 0.5);
  EXPECT_EQ (result.outliers.size (), static_cast<std::size_t> (std::count (scene.source_object.begin (),
                                                                            scene.source_object.end (), kBoard)));
}

TEST (JointRefutedClusters, AClusterMostlyMatchedOrWhereTheTargetCouldNotSeeStays)
{
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // Shifted 6 m the board lies behind the wall: the target could not have seen it.
  JointResult hidden = sceneResult (scene, translation (0.0, 6.0), 3);
  EXPECT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, hidden), 0);
  EXPECT_EQ (hidden.cluster_motions.size (), 3u);
  // The car's true motion puts none of it where the target saw through; the board with
  // all its points matched is refuted by no more points than support it.
  JointResult matched = sceneResult (scene, translation (0.0, 2.0), 1000);
  EXPECT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, matched), 0);
  // Unmatched, the same board is refuted.
  for (std::size_t i = 0; i < matched.source_cluster.size (); ++i)
    if (matched.source_cluster[i] == kBoard)
      matched.source_match[i] = kNoMatch;
  EXPECT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, matched), 1);
}

TEST (JointRefutedClusters, LeavesTheStaticWorldAndResultsWithoutOneAlone)
{
  // The static world moved 2 m into the target's free space is still the static world.
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = sceneResult (scene, translation (0.0, 6.0), 3);
  result.cluster_motions[0] = translation (0.0, -2.0);
  EXPECT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, result), 0);
  JointResult no_static = sceneResult (scene, translation (0.0, 2.0), 3);
  no_static.static_cluster = -1;
  EXPECT_EQ (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, no_static), 0);
}

TEST (JointRefutedClusters, RejectsInconsistentResults)
{
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult short_result = sceneResult (scene, translation (0.0, 2.0), 3);
  short_result.source_cluster.pop_back ();
  short_result.source_match.pop_back ();
  EXPECT_THROW (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, short_result),
                std::invalid_argument);
  JointResult match = sceneResult (scene, translation (0.0, 2.0), 3);
  match.source_match[0] = static_cast<int> (scene.target.cols ());
  EXPECT_THROW (removeClustersTheTargetSeesThrough (scene.source, scene.target, parameters, match),
                std::invalid_argument);
}

}  // namespace
