#include <pcl_crf/joint/joint_estimation.h>

#include <gtest/gtest.h>

#include "synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::kOutlierCluster;
using pcl_crf::Rigid2d;
using pcl_crf::test::translation;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::markPointsThatMovedAway;
using pcl_crf::joint::removeClustersTheTargetSeesThrough;
using pcl_crf::joint::separatePointsTheTargetSeesThrough;
using pcl_crf::joint::separateSegmentsTheTargetSeesThrough;

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

/** The point of \a scan nearest to \a point. */
int
nearestPoint (const Eigen::Matrix2Xd& scan, const Eigen::Vector2d& point)
{
  Eigen::Index j;
  (scan.colwise () - point).colwise ().squaredNorm ().minCoeff (&j);
  return static_cast<int> (j);
}

/** Every source point in the static world (identity), matched to its nearest target point. */
JointResult
allStaticResult (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target)
{
  JointResult result;
  result.cluster_motions = {Rigid2d::Identity ()};
  result.static_cluster = 0;
  for (Eigen::Index i = 0; i < source.cols (); ++i) {
    result.source_cluster.push_back (0);
    result.source_match.push_back (nearestPoint (target, source.col (i)));
  }
  result.cluster_sizes = {static_cast<int> (source.cols ())};
  return result;
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
                                       : nearestPoint (scene.target, result.cluster_motions[cluster] * scene.source.col (i)));
  }
  return result;
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

constexpr int kWalkerA = 1, kWalkerB = 2, kWalkerC = 3;

/** A wall along y = 8 m and three pedestrians 0.2 m wide: A at y = 4 m steps 0.5 m to the
 *  right, B at y = 5 m 0.4 m to the left, and C at y = 3 m hides (the target has none). */
struct Walkers
{
  Eigen::Matrix2Xd source, target;
  std::vector<int> source_object, target_object;

  Walkers ()
  {
    source = rayCast ({{8.0, -20.0, 20.0, kWall},
                       {4.0, -0.1, 0.1, kWalkerA},
                       {5.0, -3.1, -2.9, kWalkerB},
                       {3.0, 2.9, 3.1, kWalkerC}},
                      source_object);
    target = rayCast ({{8.0, -20.0, 20.0, kWall}, {4.0, 0.4, 0.6, kWalkerA}, {5.0, -3.5, -3.3, kWalkerB}},
                      target_object);
  }

  JointResult
  allStatic () const
  {
    return allStaticResult (source, target);
  }
};

/** The cluster every point of \a object is in, or -2 when its points are in several. */
int
clusterOf (const std::vector<int>& objects, int object, const JointResult& result)
{
  int cluster = -3;
  for (std::size_t i = 0; i < objects.size (); ++i)
    if (objects[i] == object)
      cluster = cluster == -3 || cluster == result.source_cluster[i] ? result.source_cluster[i] : -2;
  return cluster;
}

TEST (JointMovedPoints, PointsThatMovedOutPairedWithPointsThatMovedInGetAClusterEach)
{
  const Walkers scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = scene.allStatic ();
  ASSERT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, result), 2);
  ASSERT_EQ (result.cluster_motions.size (), 3u);
  EXPECT_EQ (result.static_cluster, 0);
  EXPECT_EQ (clusterOf (scene.source_object, kWall, result), 0);
  EXPECT_EQ (clusterOf (scene.source_object, kWalkerC, result), 0);  // hidden: no motion to give it
  const int a = clusterOf (scene.source_object, kWalkerA, result);
  const int b = clusterOf (scene.source_object, kWalkerB, result);
  ASSERT_GT (a, 0);
  ASSERT_GT (b, 0);
  EXPECT_NE (a, b);
  // The centroids' displacement, within a beam spacing along the walker (the beams
  // sample it at other places before and after): 0.035 m for A, 0.06 m for B.
  EXPECT_NEAR (result.cluster_motions[a].translation ().x (), 0.5, 0.035);
  EXPECT_NEAR (result.cluster_motions[a].translation ().y (), 0.0, 1e-9);
  EXPECT_NEAR (result.cluster_motions[b].translation ().x (), -0.4, 0.06);
  EXPECT_NEAR (result.cluster_motions[b].translation ().y (), 0.0, 1e-9);
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i)
    if (scene.source_object[i] == kWalkerA) {  // matched to the walker where it went
      ASSERT_NE (result.source_match[i], kNoMatch) << i;
      EXPECT_EQ (scene.target_object[result.source_match[i]], kWalkerA) << i;
    }
}

TEST (JointMovedPoints, NothingMovedFartherThanMaxDisplacementOrWithoutAReturnBehindIt)
{
  const Walkers scene;
  pcl_crf::matching::SegmentMotionParameters parameters;
  parameters.max_displacement = 0.45;  // A's 0.5 m step is too far, B's 0.4 m is not
  JointResult result = scene.allStatic ();
  EXPECT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, result), 1);
  EXPECT_EQ (clusterOf (scene.source_object, kWalkerA, result), 0);
  EXPECT_EQ (clusterOf (scene.source_object, kWalkerB, result), 1);

  // Without the wall behind them, the beams that passed where the walkers were return
  // nothing: no evidence that they moved.
  std::vector<int> source_object, target_object;
  const Eigen::Matrix2Xd source = rayCast ({{4.0, -0.1, 0.1, kWalkerA}, {5.0, -3.1, -2.9, kWalkerB}}, source_object);
  const Eigen::Matrix2Xd target = rayCast ({{4.0, 0.4, 0.6, kWalkerA}, {5.0, -3.5, -3.3, kWalkerB}}, target_object);
  JointResult open;
  open.cluster_motions = {Rigid2d::Identity ()};
  open.static_cluster = 0;
  open.source_cluster.assign (static_cast<std::size_t> (source.cols ()), 0);
  open.source_match.assign (static_cast<std::size_t> (source.cols ()), kNoMatch);
  EXPECT_EQ (separatePointsTheTargetSeesThrough (source, target, pcl_crf::matching::SegmentMotionParameters (), open),
             0);
}

TEST (JointMovedPoints, MovingClustersKeepTheirPointsAndBadResultsAreRejected)
{
  const Walkers scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // A already has a cluster of its own, with its motion and matches: its points stay
  // there, and its target points are explained (C, which hid, does not take them).
  JointResult result = scene.allStatic ();
  result.cluster_motions.push_back (translation (0.5, 0.0));
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i)
    if (scene.source_object[i] == kWalkerA) {
      result.source_cluster[i] = 1;
      result.source_match[i] = nearestPoint (scene.target, result.cluster_motions[1] * scene.source.col (i));
    }
  const std::vector<int> a_matches = result.source_match;
  EXPECT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, result), 1);  // B only
  EXPECT_EQ (clusterOf (scene.source_object, kWalkerC, result), 0);
  EXPECT_EQ (clusterOf (scene.source_object, kWalkerA, result), 1);
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i) {
    if (scene.source_object[i] == kWalkerA) {
      EXPECT_EQ (result.source_match[i], a_matches[i]) << i;
    }
  }
  EXPECT_EQ (result.cluster_motions.size (), 3u);

  JointResult no_static = scene.allStatic ();
  no_static.static_cluster = -1;
  EXPECT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, no_static), 0);
  JointResult short_result = scene.allStatic ();
  short_result.source_cluster.pop_back ();
  short_result.source_match.pop_back ();
  EXPECT_THROW (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, short_result),
                std::invalid_argument);
}

/** A wall along y = 8 m and a board 1 m wide (x in [-0.5, 0.5] m) along y = \a source_y m
 *  in the source and \a target_y m in the target: it drove straight towards the sensor
 *  (or away from it), so its view in one scan hides behind its view in the other. */
struct RadialBoard
{
  Eigen::Matrix2Xd source, target;
  std::vector<int> source_object, target_object;

  RadialBoard (double source_y, double target_y)
  {
    source = rayCast ({{8.0, -20.0, 20.0, kWall}, {source_y, -0.5, 0.5, kBoard}}, source_object);
    target = rayCast ({{8.0, -20.0, 20.0, kWall}, {target_y, -0.5, 0.5, kBoard}}, target_object);
  }
};

/** Checks that \a result gives the board, and only it, a cluster of its own moving by
 *  \a dy along y, its points matched to the board's target points. */
void
expectBoardCluster (const RadialBoard& scene, const JointResult& result, double dy)
{
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_EQ (result.static_cluster, 0);
  EXPECT_EQ (clusterOf (scene.source_object, kWall, result), 0);
  ASSERT_EQ (clusterOf (scene.source_object, kBoard, result), 1);
  // The centroids' displacement: exact across the board, within a beam spacing along it
  // (0.5° at 3 m, 0.03 m; the beams sample the board at other places in each scan).
  EXPECT_NEAR (result.cluster_motions[1].translation ().y (), dy, 1e-9);
  EXPECT_NEAR (result.cluster_motions[1].translation ().x (), 0.0, 0.03);
  EXPECT_NEAR (result.cluster_motions[1].rotation () (1, 0), 0.0, 1e-12);
  int matched = 0;
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i)
    if (scene.source_object[i] == kBoard && result.source_match[i] != kNoMatch) {
      EXPECT_EQ (scene.target_object[result.source_match[i]], kBoard) << i;
      ++matched;
    }
  EXPECT_GT (matched, 0);
}

TEST (JointMovedPoints, AnObjectThatCameNearerPairsWithItsViewHiddenBehindIt)
{
  // The board at 3 m in the target stands where the source saw through to it at 5 m
  // (it moved in); its source view lies behind it in the target, seen through by no
  // beam (nothing moved out). Hidden, that view still pairs with the board: it lies
  // in the board's shadow.
  const RadialBoard scene (5.0, 3.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = allStaticResult (scene.source, scene.target);
  ASSERT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, result), 1);
  expectBoardCluster (scene, result, -2.0);
}

TEST (JointMovedPoints, AnObjectThatWentFartherPairsWithItsViewHiddenBehindIt)
{
  // The mirror: the board at 3 m in the source moved out; its target view at 5 m hides
  // behind it from the source sensor.
  const RadialBoard scene (3.0, 5.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = allStaticResult (scene.source, scene.target);
  ASSERT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, parameters, result), 1);
  expectBoardCluster (scene, result, 2.0);
}

TEST (JointMovedPoints, AHiddenViewPairsOnlyInItsObjectsShadowAndWithEnoughPoints)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  {
    // The board came 2 m nearer: farther than max_displacement, its views do not pair
    // (nor does the band of wall it now hides, farther still).
    pcl_crf::matching::SegmentMotionParameters near_only = parameters;
    near_only.max_displacement = 1.5;
    const RadialBoard scene (5.0, 3.0);
    JointResult result = allStaticResult (scene.source, scene.target);
    EXPECT_EQ (separatePointsTheTargetSeesThrough (scene.source, scene.target, near_only, result), 0);
    EXPECT_EQ (clusterOf (scene.source_object, kBoard, result), 0);
  }
  {
    // A board too narrow to be told from noise: 2 points hide behind its target view,
    // fewer than min_segment_points (3); with 2 allowed, they pair.
    std::vector<int> source_object, target_object;
    const Eigen::Matrix2Xd source =
        rayCast ({{8.0, -20.0, 20.0, kWall}, {5.0, -0.01, 0.05, kBoard}}, source_object);
    const Eigen::Matrix2Xd target =
        rayCast ({{8.0, -20.0, 20.0, kWall}, {3.0, -0.01, 0.05, kBoard}}, target_object);
    ASSERT_EQ (std::count (source_object.begin (), source_object.end (), kBoard), 2);
    JointResult result = allStaticResult (source, target);
    EXPECT_EQ (separatePointsTheTargetSeesThrough (source, target, parameters, result), 0);
    pcl_crf::matching::SegmentMotionParameters two_points = parameters;
    two_points.min_segment_points = 2;
    EXPECT_EQ (separatePointsTheTargetSeesThrough (source, target, two_points, result), 1);
    EXPECT_EQ (clusterOf (source_object, kBoard, result), 1);
  }
  {
    // A board appears in front of a static box and hides all of it; a post appears
    // nearer to the box than the board is. The hidden box and the post are each other's
    // nearest, but the box is in the board's shadow, not the post's.
    std::vector<int> source_object, target_object;
    const Eigen::Matrix2Xd source =
        rayCast ({{8.0, -20.0, 20.0, kWall}, {6.0, 2.3, 2.7, kCar}}, source_object);
    const Eigen::Matrix2Xd target = rayCast (
        {{8.0, -20.0, 20.0, kWall}, {6.0, 2.3, 2.7, kCar}, {3.0, 1.0, 1.4, kBoard}, {6.5, 3.5, 3.7, kWalkerC}},
        target_object);
    ASSERT_EQ (std::count (target_object.begin (), target_object.end (), kCar), 0);
    JointResult result = allStaticResult (source, target);
    EXPECT_EQ (separatePointsTheTargetSeesThrough (source, target, parameters, result), 0);
  }
}

TEST (JointMovedPoints, AStretchOfWallHiddenBehindANewcomerIsNoObjectsView)
{
  // A board appears 4 m away (it moved in) and hides 1.2 m of the wall behind it. That
  // stretch is hidden, in the board's shadow and its nearest group, but the wall goes on,
  // explained by the static motion, on both sides of it: a surface hidden in the middle,
  // not the board's old view, which would end at the board's own edges.
  std::vector<int> source_object, target_object;
  const Eigen::Matrix2Xd source = rayCast ({{8.0, -20.0, 20.0, kWall}}, source_object);
  const Eigen::Matrix2Xd target =
      rayCast ({{8.0, -20.0, 20.0, kWall}, {4.0, -0.3, 0.3, kBoard}}, target_object);
  JointResult result = allStaticResult (source, target);
  EXPECT_EQ (separatePointsTheTargetSeesThrough (source, target, pcl_crf::matching::SegmentMotionParameters (), result),
             0);
  EXPECT_EQ (result.cluster_motions.size (), 1u);
}

constexpr int kTruck = 1;

/** A wall along y = 8 m and a truck along y = 2 m, x in [1, 6] m, that drives
 *  \a truck_drive m along itself between the scans (the sensor stands): the static
 *  motion maps the truck onto its own side in the target, all but its trailing end. */
struct Alongside
{
  Eigen::Matrix2Xd source, target;
  std::vector<int> source_object, target_object;

  explicit Alongside (double truck_drive)
  {
    source = rayCast ({{8.0, -20.0, 20.0, kWall}, {2.0, 1.0, 6.0, kTruck}}, source_object);
    target = rayCast ({{8.0, -20.0, 20.0, kWall}, {2.0, 1.0 + truck_drive, 6.0 + truck_drive, kTruck}}, target_object);
  }

  JointResult
  allStatic () const
  {
    return allStaticResult (source, target);
  }
};

TEST (JointSlidSegments, ATruckSlidingAlongItselfGetsItsOwnClusterAndMotion)
{
  const Alongside scene (1.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = scene.allStatic ();
  ASSERT_EQ (separateSegmentsTheTargetSeesThrough (scene.source, scene.target, parameters, 2, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_EQ (clusterOf (scene.source_object, kWall, result), result.static_cluster);
  const int truck = clusterOf (scene.source_object, kTruck, result);
  ASSERT_GE (truck, 0);
  ASSERT_NE (truck, result.static_cluster);
  // Its object end aligned with the target's: within one beam spacing at that end
  // (0.5° at 6.3 m along a side seen at 18°: 0.17 m), exactly along the side.
  EXPECT_NEAR (result.cluster_motions[truck].translation ().x (), 1.0, 0.17);
  EXPECT_NEAR (result.cluster_motions[truck].translation ().y (), 0.0, 1e-9);
  EXPECT_TRUE (result.cluster_motions[truck].linear ().isIdentity (1e-12));
  int matched = 0, truck_points = 0;
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i) {
    if (scene.source_object[i] != kTruck)
      continue;
    ++truck_points;
    const int j = result.source_match[i];
    if (j == kNoMatch)
      continue;
    ++matched;
    EXPECT_EQ (scene.target_object[j], kTruck) << i;
    EXPECT_LT ((scene.target.col (j) - (scene.source.col (i) + Eigen::Vector2d (1.0, 0.0))).norm (), 0.2) << i;
  }
  EXPECT_EQ (matched, truck_points);  // every shifted point lands on the target's side
  EXPECT_EQ (result.cluster_sizes[truck], truck_points);
}

TEST (JointSlidSegments, AStandingScenePartlyClusteredOrTooLittleSeenThroughIsLeftAlone)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  const Alongside standing (0.0);
  JointResult result = standing.allStatic ();
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (standing.source, standing.target, parameters, 1, result), 0);
  EXPECT_EQ (result.cluster_motions.size (), 1u);

  const Alongside driving (1.0);
  JointResult unchanged = driving.allStatic ();
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (driving.source, driving.target, parameters, 1000, unchanged), 0);
  // A truck one of whose points is already in a moving cluster is that cluster's to explain.
  JointResult claimed = driving.allStatic ();
  claimed.cluster_motions.push_back (translation (1.0, 0.0));
  const auto first_truck_point =
      std::find (driving.source_object.begin (), driving.source_object.end (), kTruck) - driving.source_object.begin ();
  claimed.source_cluster[first_truck_point] = 1;
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (driving.source, driving.target, parameters, 2, claimed), 0);
  // Too short to be a segment worth sliding.
  pcl_crf::matching::SegmentMotionParameters long_segments;
  long_segments.min_segment_points = static_cast<int> (driving.source.cols ()) + 1;
  JointResult short_segments = driving.allStatic ();
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (driving.source, driving.target, long_segments, 2, short_segments), 0);
  // A shift beyond max_displacement is never proposed.
  pcl_crf::matching::SegmentMotionParameters near_only;
  near_only.max_displacement = 0.5;
  JointResult far = driving.allStatic ();
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (driving.source, driving.target, near_only, 2, far), 0);
}

constexpr int kPost = 2;

TEST (JointSlidSegments, AShortSegmentThatFitsTwoPlacesEquallyWellIsLeftAlone)
{
  // A 0.1 m post 2 m away (about five points) that stood in front of the wall and is
  // gone from there in the target: where it went, its shape alone must tell.
  std::vector<int> source_object, one_object, two_object;
  const Eigen::Matrix2Xd source = rayCast ({{8.0, -20.0, 20.0, kWall}, {2.0, 1.0, 1.1, kPost}}, source_object);
  const Eigen::Matrix2Xd one_post =
      rayCast ({{8.0, -20.0, 20.0, kWall}, {2.0, 1.5, 1.6, kPost}}, one_object);
  const Eigen::Matrix2Xd two_posts =
      rayCast ({{8.0, -20.0, 20.0, kWall}, {2.0, 1.5, 1.6, kPost}, {2.0, 0.3, 0.4, kPost}}, two_object);
  const pcl_crf::matching::SegmentMotionParameters parameters;

  JointResult single = allStaticResult (source, one_post);
  ASSERT_EQ (separateSegmentsTheTargetSeesThrough (source, one_post, parameters, 2, single), 1);
  const int post = clusterOf (source_object, kPost, single);
  ASSERT_NE (post, single.static_cluster);
  EXPECT_NEAR (single.cluster_motions[post].translation ().x (), 0.5, 0.05);  // one beam spacing there
  EXPECT_NEAR (single.cluster_motions[post].translation ().y (), 0.0, 1e-9);

  // Two posts, each explaining the whole segment: 0.5 m right or 0.7 m left.
  JointResult ambiguous = allStaticResult (source, two_posts);
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (source, two_posts, parameters, 2, ambiguous), 0);
  EXPECT_EQ (ambiguous.cluster_motions.size (), 1u);
  EXPECT_EQ (clusterOf (source_object, kPost, ambiguous), ambiguous.static_cluster);
}

TEST (JointSlidSegments, APlaceThatExplainsOnePointLessStillMakesTheSlideAmbiguousTwoLessDoNot)
{
  // An eight-point post 2 m away goes to one of two posts. The wall has a gap at bearings
  // 69°-97° (x in [-1, 3] m at y = 8 m) where the second post, shorter, stands with no
  // return behind it: aligned with its end, the post's last points land beside it, on
  // bearings 75.5°-77.5° that a board 1 m away hides, neither explained nor seen through.
  // (Without the board the target's empty beams there would have seen through them: the
  // post is a surface the sensor returns from on every beam.)
  std::vector<int> source_object, target_object;
  const Surface left{8.0, -20.0, -1.0, kWall}, right{8.0, 3.0, 20.0, kWall}, board{1.0, 0.222, 0.259, kWall};
  const Eigen::Matrix2Xd source = rayCast ({left, right, board, {2.0, 1.0, 1.2, kPost}}, source_object);
  const auto targetWithSecondPostTo = [&] (double x_max) {
    return rayCast ({left, right, board, {2.0, 1.5, 1.7, kPost}, {2.0, 0.3, x_max, kPost}}, target_object);
  };
  // 0.12 m long, the second post explains 7 of the 8 points where the first explains 8.
  const Eigen::Matrix2Xd one_less = targetWithSecondPostTo (0.42);
  JointResult ambiguous = allStaticResult (source, one_less);
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (source, one_less, {}, 2, ambiguous), 0);
  EXPECT_EQ (clusterOf (source_object, kPost, ambiguous), ambiguous.static_cluster);
  // 0.09 m long, 6 of 8: the first post is where it went.
  const Eigen::Matrix2Xd two_less = targetWithSecondPostTo (0.39);
  JointResult slid = allStaticResult (source, two_less);
  ASSERT_EQ (separateSegmentsTheTargetSeesThrough (source, two_less, {}, 2, slid), 1);
  const int post = clusterOf (source_object, kPost, slid);
  ASSERT_NE (post, slid.static_cluster);
  EXPECT_NEAR (slid.cluster_motions[post].translation ().x (), 0.5, 0.05);
}

/** Every \a keep-th point of \a object's in \a scan (and \a objects), the others dropped:
 *  a surface the sensor returns from on one beam in \a keep. */
Eigen::Matrix2Xd
thinObject (const Eigen::Matrix2Xd& scan, std::vector<int>& objects, int object, int keep)
{
  std::vector<Eigen::Index> kept;
  int seen = 0;
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
    if (objects[i] != object || seen++ % keep == 0)
      kept.push_back (i);
  Eigen::Matrix2Xd thinned (2, static_cast<Eigen::Index> (kept.size ()));
  std::vector<int> kept_objects;
  for (std::size_t k = 0; k < kept.size (); ++k) {
    thinned.col (static_cast<Eigen::Index> (k)) = scan.col (kept[k]);
    kept_objects.push_back (objects[kept[k]]);
  }
  objects = std::move (kept_objects);
  return thinned;
}

TEST (JointSlidSegments, BeamsWithoutAReturnCountOnlyAgainstASurfaceTheSensorReturnsFromOnEveryBeam)
{
  // The truck of Alongside drives 1 m along itself with nothing behind it: walls far to
  // the left and right (bearings 110°-158° and 8°-15°) bound the field of view, and the
  // beams past the truck's trailing end in the target return nothing.
  const std::vector<Surface> walls{{8.0, -20.0, -3.0, kWall}, {8.0, 30.0, 60.0, kWall}};
  const auto scan = [&] (double truck_from, std::vector<int>& objects) {
    std::vector<Surface> surfaces = walls;
    surfaces.push_back ({2.0, truck_from, truck_from + 5.0, kTruck});
    return rayCast (surfaces, objects);
  };
  std::vector<int> source_object, target_object;
  const Eigen::Matrix2Xd source = scan (1.0, source_object), target = scan (2.0, target_object);
  const pcl_crf::matching::SegmentMotionParameters parameters;

  // Returned from on every beam: the beams without a return where the static motion
  // puts the trailing end saw through it.
  JointResult dense = allStaticResult (source, target);
  ASSERT_EQ (separateSegmentsTheTargetSeesThrough (source, target, parameters, 2, dense), 1);
  const int truck = clusterOf (source_object, kTruck, dense);
  ASSERT_GE (truck, 0);
  ASSERT_NE (truck, dense.static_cluster);
  EXPECT_NEAR (dense.cluster_motions[truck].translation ().x (), 1.0, 0.17);  // a beam spacing at its end
  EXPECT_NEAR (dense.cluster_motions[truck].translation ().y (), 0.0, 1e-9);

  // Returned from on one beam in three (runs of two missing returns) in the source: a
  // surface the sensor drops returns on, so the target's empty beams say nothing.
  std::vector<int> sparse_object = source_object;
  const Eigen::Matrix2Xd sparse_source = thinObject (source, sparse_object, kTruck, 3);
  JointResult sparse = allStaticResult (sparse_source, target);
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (sparse_source, target, parameters, 2, sparse), 0);
  EXPECT_EQ (clusterOf (sparse_object, kTruck, sparse), sparse.static_cluster);
  // One beam in two (single missing returns, as real scanners leave): still counted.
  std::vector<int> halved_object = source_object;
  const Eigen::Matrix2Xd halved_source = thinObject (source, halved_object, kTruck, 2);
  JointResult halved = allStaticResult (halved_source, target);
  ASSERT_EQ (separateSegmentsTheTargetSeesThrough (halved_source, target, parameters, 2, halved), 1);
  EXPECT_NE (clusterOf (halved_object, kTruck, halved), halved.static_cluster);
}

/** A standing board 2 m ahead (y = 2 m, x in [−0.6, 0.6] m, or ±\a half_length) whose
 *  right half stands 4 cm farther back (\a step; 0: flat), seen twice from the origin, where the target
 *  sees both of its ends 0.3 m farther right but the step where it was: free space says
 *  it slid 0.3 m, its shape (the step, which a slide would misplace by 4 cm over 0.3 m)
 *  says it stood. Range noise on a rough real surface does the same: on the real
 *  overtakes bag a wall slid 0.26 m (scan 150). With no step (flat), nothing tells the
 *  slide from a real one. */
struct SteppedBoard
{
  Eigen::Matrix2Xd source, target;
  std::vector<int> source_object, target_object;

  explicit SteppedBoard (double step, double half_length = 0.6)
  {
    source = rayCast (
        {{8.0, -20.0, 20.0, kWall}, {2.0, -half_length, 0.0, kTruck}, {2.0 + step, 0.0, half_length, kTruck}},
        source_object);
    target = rayCast ({{8.0, -20.0, 20.0, kWall},
                       {2.0, 0.3 - half_length, 0.0, kTruck},
                       {2.0 + step, 0.0, 0.3 + half_length, kTruck}},
                      target_object);
  }

  /** The board's cluster after separateObjectsInFreeSpace () on allStaticResult (),
   *  given \a static_fit or not. */
  int
  slid (const pcl_crf::joint::SlightMotionTest* static_fit, JointResult& result) const
  {
    result = allStaticResult (source, target);
    EXPECT_LE (pcl_crf::joint::separateObjectsInFreeSpace (source, target, {}, result, static_fit), 1);
    return clusterOf (source_object, kTruck, result);
  }
};

/** separateObjectsInFreeSpace () on \a board (SteppedBoard::slid ()): the slide it
 *  finds without the static fit's check, and with it (dropped unless
 *  \a kept_when_checked). */
void
expectSlides (const SteppedBoard& board, bool kept_when_checked)
{
  const pcl_crf::joint::SlightMotionTest test;
  for (const bool checked : {false, true}) {
    SCOPED_TRACE (checked ? "checked" : "unchecked");
    JointResult result;
    const int board_cluster = board.slid (checked ? &test : nullptr, result);
    if (checked && !kept_when_checked) {
      EXPECT_EQ (result.cluster_motions.size (), 1u);
      EXPECT_EQ (board_cluster, result.static_cluster);
      continue;
    }
    ASSERT_GE (board_cluster, 0);
    ASSERT_NE (board_cluster, result.static_cluster);
    // Measured: 0.288–0.307 m along the board, within 0.02 m across it.
    EXPECT_NEAR (result.cluster_motions[board_cluster].translation ().x (), 0.3, 0.02);
    EXPECT_NEAR (result.cluster_motions[board_cluster].translation ().y (), 0.0, 0.02);
  }
}

TEST (JointFreeSpaceSlides, ASlideTheStaticMotionFitsBetterIsDropped)
{
  // The static motion misplaces no point of the stepped board; the slide misplaces
  // the 0.3 m before the step by 4 cm, about 20 points, each by more than 2 of its σ
  // (range noise 1 cm, half a beam spacing 0.9 cm): D far above 32 and above one
  // variance per point of the board's 66.
  expectSlides (SteppedBoard (0.04), false);
}

TEST (JointFreeSpaceSlides, ASlideAlongAFlatSideIsKept)
{
  expectSlides (SteppedBoard (0.0), true);
}

TEST (JointFreeSpaceSlides, ASmallStepOnALongBoardIsNotEnoughEvidence)
{
  // A 3 cm step on a 2 m board (106 points): the slide's deviance passes 32 but not
  // one variance per point, since along one surface the residuals are correlated.
  expectSlides (SteppedBoard (0.03, 1.0), true);
}

TEST (JointFreeSpaceSlides, AStaticFitTestOutOfRangeIsAnError)
{
  const SteppedBoard board (0.04);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  pcl_crf::joint::SlightMotionTest bad;
  bad.min_deviance = 0.0;
  JointResult result = allStaticResult (board.source, board.target);
  EXPECT_THROW (pcl_crf::joint::separateObjectsInFreeSpace (board.source, board.target, parameters, result, &bad),
                std::invalid_argument);
  bad = {};
  bad.along_beam_steps = -1.0;
  EXPECT_THROW (pcl_crf::joint::separateObjectsInFreeSpace (board.source, board.target, parameters, result, &bad),
                std::invalid_argument);
  // Also where no slide is found to weigh: a scene that did not move.
  bad = {};
  bad.min_mean_deviance = std::numeric_limits<double>::quiet_NaN ();
  JointResult standing = allStaticResult (board.source, board.source);
  EXPECT_THROW (pcl_crf::joint::separateObjectsInFreeSpace (board.source, board.source, parameters, standing, &bad),
                std::invalid_argument);
  const pcl_crf::joint::SlightMotionTest good;
  EXPECT_EQ (pcl_crf::joint::separateObjectsInFreeSpace (board.source, board.source, parameters, standing, &good), 0);
}

TEST (JointSlidSegments, RejectsResultsThatDoNotFitTheScansAndANonPositiveEvidenceCount)
{
  const Alongside scene (1.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = scene.allStatic ();
  EXPECT_THROW (separateSegmentsTheTargetSeesThrough (scene.source, scene.target, parameters, 0, result),
                std::invalid_argument);
  JointResult short_result = scene.allStatic ();
  short_result.source_cluster.pop_back ();
  short_result.source_match.pop_back ();
  EXPECT_THROW (separateSegmentsTheTargetSeesThrough (scene.source, scene.target, parameters, 2, short_result),
                std::invalid_argument);
  JointResult no_static = scene.allStatic ();
  no_static.static_cluster = -1;
  EXPECT_EQ (separateSegmentsTheTargetSeesThrough (scene.source, scene.target, parameters, 2, no_static), 0);
}

/** allStaticResult () with the points of \a object (per point: \a objects) outliers. */
JointResult
withObjectUnmatched (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const std::vector<int>& objects,
                     int object)
{
  JointResult result = allStaticResult (source, target);
  for (std::size_t i = 0; i < objects.size (); ++i)
    if (objects[i] == object) {
      result.source_cluster[i] = kOutlierCluster;
      result.source_match[i] = kNoMatch;
    }
  return result;
}

/** The indices of the points of \a object (per point: \a objects), increasing. */
std::vector<int>
pointsOf (const std::vector<int>& objects, int object)
{
  std::vector<int> points;
  for (std::size_t i = 0; i < objects.size (); ++i)
    if (objects[i] == object)
      points.push_back (static_cast<int> (i));
  return points;
}

TEST (JointMovedAway, OutliersTheTargetSawThroughToAReturnMovedAway)
{
  // The scene's board (y = 3 m, 31 points) is gone from the target, whose beams there
  // reach the wall 5 m behind it: every board point moved away, and the prediction
  // keeps them out of the static world.
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = withObjectUnmatched (scene.source, scene.target, scene.source_object, kBoard);
  const std::vector<int> board = pointsOf (scene.source_object, kBoard);
  ASSERT_EQ (board.size (), 31u);
  EXPECT_EQ (markPointsThatMovedAway (scene.source, scene.target, parameters, result), 31);
  EXPECT_EQ (result.moved_away, board);
  EXPECT_EQ (result.cluster_motions.size (), 1u);  // clusters and matches untouched
  const pcl_crf::Prediction prediction = pcl_crf::joint::toPrediction (scene.source, result);
  for (Eigen::Index i = 0; i < scene.source.cols (); ++i)
    EXPECT_EQ (prediction.source_cluster[i], scene.source_object[i] == kBoard ? kOutlierCluster : 0) << i;
  // Unmarked, the board's outliers took the static world's label, as before.
  result.moved_away.clear ();
  const pcl_crf::Prediction completed = pcl_crf::joint::toPrediction (scene.source, result);
  EXPECT_EQ (std::count (completed.source_cluster.begin (), completed.source_cluster.end (), 0), scene.source.cols ());
}

TEST (JointMovedAway, NothingBehindAShortRunOrAClusteredPointMovedAway)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // No wall behind the board in either scan: its beams in the target saw nothing, which
  // a dropped return would show as well.
  std::vector<int> source_object, target_object;
  const Eigen::Matrix2Xd open_source =
      rayCast ({{8.0, 2.0, 20.0, kWall}, {3.0, -2.0, -1.0, kBoard}}, source_object);
  const Eigen::Matrix2Xd open_target = rayCast ({{8.0, 2.0, 20.0, kWall}}, target_object);
  JointResult open = withObjectUnmatched (open_source, open_target, source_object, kBoard);
  EXPECT_EQ (markPointsThatMovedAway (open_source, open_target, parameters, open), 0);
  EXPECT_TRUE (open.moved_away.empty ());
  // Two consecutive board outliers are fewer than min_segment_points (3).
  const Scene scene;
  JointResult two = allStaticResult (scene.source, scene.target);
  const std::vector<int> board = pointsOf (scene.source_object, kBoard);
  for (const int i : {board[5], board[6]})
    two.source_cluster[i] = kOutlierCluster;
  EXPECT_EQ (markPointsThatMovedAway (scene.source, scene.target, parameters, two), 0);
  // Points the static world or a moving cluster holds are not outliers.
  JointResult clustered = allStaticResult (scene.source, scene.target);
  EXPECT_EQ (markPointsThatMovedAway (scene.source, scene.target, parameters, clustered), 0);
  // Points an earlier step marked (removeClustersANearerClusterExplains ()) stay marked
  // while they are outliers; one a later step clustered again does not.
  JointResult earlier = two;
  earlier.moved_away = {board[5], board[6], board[7]};
  EXPECT_EQ (markPointsThatMovedAway (scene.source, scene.target, parameters, earlier), 2);
  EXPECT_EQ (earlier.moved_away, (std::vector<int>{board[5], board[6]}));
  // Without a static world nothing tells where the points should be.
  JointResult no_static = withObjectUnmatched (scene.source, scene.target, scene.source_object, kBoard);
  no_static.static_cluster = -1;
  EXPECT_EQ (markPointsThatMovedAway (scene.source, scene.target, parameters, no_static), 0);
}

TEST (JointMovedAway, ABoardSeenNearlyEdgeOnDidNotMoveAway)
{
  // A board along y = 0.5 m, x in [2.6, 3.4] m, seen at 8.5°–10.5° (5 points 0.14–0.2 m
  // apart, one segment), gone from the target, whose beams there reach a wall along
  // y = 1.5 m behind it. Four of them meet the board at 10° or less, the breakpoint
  // angle: a few centimetres of range move such a surface by whole beams, so the wall
  // beyond says nothing of it, and one point is no run.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  std::vector<int> source_object, target_object;
  const Eigen::Matrix2Xd source = rayCast ({{1.5, 5.0, 20.0, kWall}, {0.5, 2.6, 3.4, kBoard}}, source_object);
  const Eigen::Matrix2Xd target = rayCast ({{1.5, 5.0, 20.0, kWall}}, target_object);
  ASSERT_EQ (pointsOf (source_object, kBoard).size (), 5u);
  JointResult result = withObjectUnmatched (source, target, source_object, kBoard);
  EXPECT_EQ (markPointsThatMovedAway (source, target, parameters, result), 0);
}

TEST (JointMovedAway, RejectsResultsThatDoNotFitTheScansOrMarkNoSourcePoint)
{
  const Scene scene;
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult short_result = withObjectUnmatched (scene.source, scene.target, scene.source_object, kBoard);
  short_result.source_cluster.pop_back ();
  short_result.source_match.pop_back ();
  EXPECT_THROW (markPointsThatMovedAway (scene.source, scene.target, parameters, short_result),
                std::invalid_argument);
  JointResult bad_cluster = withObjectUnmatched (scene.source, scene.target, scene.source_object, kBoard);
  bad_cluster.source_cluster[0] = 4;
  EXPECT_THROW (markPointsThatMovedAway (scene.source, scene.target, parameters, bad_cluster), std::invalid_argument);
  JointResult bad_mark = withObjectUnmatched (scene.source, scene.target, scene.source_object, kBoard);
  bad_mark.moved_away = {static_cast<int> (scene.source.cols ())};
  EXPECT_THROW (pcl_crf::joint::toPrediction (scene.source, bad_mark), std::invalid_argument);
}

}  // namespace
