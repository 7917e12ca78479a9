#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/segment_motions.h>

#include <gtest/gtest.h>

#include "synthetic_scene.h"

#include <algorithm>
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
using pcl_crf::joint::extendMovingClustersOverTheirSurfaces;
using pcl_crf::joint::mergeAdjacentClustersThatMoveAlike;

/** A wall ahead along y = 6 (x from 4 down to −4, 0.2 m apart: 41 points, the static
 *  world), then a car's side to the left along y = 2 (x from 0 down to −3.8, 0.2 m
 *  apart: 20 points), in beam order. */
Eigen::Matrix2Xd
wallAndCar ()
{
  Eigen::Matrix2Xd points (2, 61);
  for (int k = 0; k < 41; ++k)
    points.col (k) << 4.0 - 0.2 * k, 6.0;
  for (int k = 0; k < 20; ++k)
    points.col (41 + k) << -0.2 * k, 2.0;
  return points;
}

/** The wall in the static world (identity), the car's first ten points in cluster 1
 *  (motion \a front) and its last ten in cluster 2 (motion \a back); every point matched
 *  to itself. */
JointResult
carInTwo (const Rigid2d& front, const Rigid2d& back)
{
  JointResult result;
  result.cluster_motions = {Rigid2d::Identity (), front, back};
  result.static_cluster = 0;
  for (int i = 0; i < 61; ++i) {
    result.source_cluster.push_back (i < 41 ? 0 : i < 51 ? 1 : 2);
    result.source_match.push_back (i);
  }
  return result;
}

/** What the target sees when every point of \a result moved by its cluster's motion
 *  (the outliers stay). */
Eigen::Matrix2Xd
targetOf (const Eigen::Matrix2Xd& source, const JointResult& result)
{
  Eigen::Matrix2Xd target = source;
  for (Eigen::Index i = 0; i < source.cols (); ++i)
    if (result.source_cluster[i] != kOutlierCluster)
      target.col (i) = result.cluster_motions[result.source_cluster[i]] * source.col (i);
  return target;
}

/** mergeAdjacentClustersThatMoveAlike with the target that \a result's motions make of \a source. */
int
mergeOverItsOwnTarget (const Eigen::Matrix2Xd& source, JointResult& result)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  return mergeAdjacentClustersThatMoveAlike (source, targetOf (source, result), parameters, result);
}

int
count (const std::vector<int>& labels, int label)
{
  return static_cast<int> (std::count (labels.begin (), labels.end (), label));
}

TEST (JointAdjacentClusters, TwoHalvesOfACarThatMoveAlikeBecomeOne)
{
  // 0.2 m spacing: overlap radius min(0.15, max(0.03, 2 · 0.2)) = 0.15 m. Halves 0.1 m
  // apart in their motions are one car; the larger (here the first, of equal size)
  // keeps its motion.
  JointResult result = carInTwo (translation (1.0, 0.0), translation (1.1, 0.0));
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  const int car = result.source_cluster[41];
  EXPECT_NE (car, result.static_cluster);
  EXPECT_EQ (count (result.source_cluster, car), 20);
  EXPECT_EQ (count (result.source_cluster, result.static_cluster), 41);
  EXPECT_TRUE (result.cluster_motions[car].isApprox (translation (1.0, 0.0)));
  for (int i = 0; i < 61; ++i)
    EXPECT_EQ (result.source_match[i], i) << i;  // matches untouched
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{41, 20}));
}

TEST (JointAdjacentClusters, ClustersThatMoveApartOrDoNotMeetOnOneSurfaceStay)
{
  // 0.2 m apart in their motions, across the car's side: beyond the 0.15 m overlap
  // radius, and the target shows the back half where its own motion puts it.
  JointResult apart = carInTwo (translation (1.0, 0.0), translation (1.0, 0.2));
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), apart), 0);
  EXPECT_EQ (apart.cluster_motions.size (), 3u);
  // A rotation about the car's front that swings its back 0.19 m apart.
  const Rigid2d turned = Eigen::Translation2d (0.0, 2.0) * Eigen::Rotation2Dd (0.05) * Eigen::Translation2d (0.0, -2.0);
  JointResult swung = carInTwo (translation (1.0, 0.0), translation (1.0, 0.0) * turned);
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), swung), 0);
  // A static point between them: they do not meet.
  JointResult separated = carInTwo (translation (1.0, 0.0), translation (1.05, 0.0));
  separated.source_cluster[51] = 0;
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), separated), 0);
  // Nor through an outlier.
  separated.source_cluster[51] = kOutlierCluster;
  separated.source_match[51] = kNoMatch;
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), separated), 0);
  // The car's halves on two surfaces: its back half half as far again along the same
  // bearings, 1.6 m beyond the front's last point, past a breakpoint.
  Eigen::Matrix2Xd two_surfaces = wallAndCar ();
  for (int i = 51; i < 61; ++i)
    two_surfaces.col (i) *= 1.5;
  JointResult split = carInTwo (translation (1.0, 0.0), translation (1.05, 0.0));
  EXPECT_EQ (mergeOverItsOwnTarget (two_surfaces, split), 0);
  // The static world is never merged into, however alike: the wall meets no moving cluster.
  JointResult one_moving = carInTwo (translation (0.0, 0.0), translation (0.0, 0.0));
  for (int i = 41; i < 61; ++i)
    one_moving.source_cluster[i] = 1;
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), one_moving), 0);
}

TEST (JointAdjacentClusters, ChainsMergeLargestFirstAndBadResultsAreRejected)
{
  // Three clusters along the car (6, 8 and 6 points), each 0.1 m from the next in its
  // motion: the middle (largest) takes both neighbours, each within 0.15 m of it.
  JointResult result = carInTwo (translation (1.0, 0.0), translation (1.1, 0.0));
  result.cluster_motions.push_back (translation (1.2, 0.0));
  for (int i = 41; i < 61; ++i)
    result.source_cluster[i] = i < 47 ? 1 : i < 55 ? 2 : 3;
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), result), 2);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_TRUE (result.cluster_motions[result.source_cluster[41]].isApprox (translation (1.1, 0.0)));

  JointResult no_static = carInTwo (translation (1.0, 0.0), translation (1.0, 0.0));
  no_static.static_cluster = -1;
  EXPECT_EQ (mergeOverItsOwnTarget (wallAndCar (), no_static), 0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult short_result = carInTwo (translation (1.0, 0.0), translation (1.0, 0.0));
  short_result.source_cluster.pop_back ();
  EXPECT_THROW (mergeAdjacentClustersThatMoveAlike (wallAndCar (), wallAndCar (), parameters, short_result),
                std::invalid_argument);
  JointResult bad_cluster = carInTwo (translation (1.0, 0.0), translation (1.0, 0.0));
  bad_cluster.source_cluster[45] = 7;
  EXPECT_THROW (mergeAdjacentClustersThatMoveAlike (wallAndCar (), wallAndCar (), parameters, bad_cluster),
                std::invalid_argument);
  JointResult bad_match = carInTwo (translation (1.0, 0.0), translation (1.0, 0.0));
  bad_match.source_match[45] = 61;  // the target has 61 points
  EXPECT_THROW (mergeAdjacentClustersThatMoveAlike (wallAndCar (), wallAndCar (), parameters, bad_match),
                std::invalid_argument);
}

/** wallAndCar () and a static post of three points beyond the car's back, at
 *  x = −6 and bearings about 175° (the last in beam order). */
Eigen::Matrix2Xd
wallCarAndPost ()
{
  Eigen::Matrix2Xd points (2, 64);
  points.leftCols (61) = wallAndCar ();
  for (int k = 0; k < 3; ++k)
    points.col (61 + k) << -6.0, 0.6 - 0.1 * k;
  return points;
}

/** \a scene with its car (points 41 … 60) moved by \a T and the rest in place. */
Eigen::Matrix2Xd
withCarMoved (Eigen::Matrix2Xd scene, const Rigid2d& T)
{
  for (int i = 41; i < 61; ++i)
    scene.col (i) = T * scene.col (i);
  return scene;
}

/** carInTwo () over \a points source points, those past the car's in the static world. */
JointResult
carInTwoOf (int points, const Rigid2d& front, const Rigid2d& back)
{
  JointResult result = carInTwo (front, back);
  for (int i = 61; i < points; ++i) {
    result.source_cluster.push_back (0);
    result.source_match.push_back (i);
  }
  return result;
}

TEST (JointAdjacentClusters, HalvesOfACarSlidAlongItsSideBecomeOneWhereTheTargetCannotTell)
{
  // The car moved 1.1 m along its own side. Its halves were fitted 1.0 m and 1.3 m:
  // 0.3 m apart, beyond the 0.15 m overlap radius, yet either motion puts the back
  // half's points within 0.1 m of the car's points in the target (0.2 m apart).
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = carInTwoOf (64, translation (1.0, 0.0), translation (1.3, 0.0));
  const Eigen::Matrix2Xd target = withCarMoved (wallCarAndPost (), translation (1.1, 0.0));
  EXPECT_EQ (mergeAdjacentClustersThatMoveAlike (wallCarAndPost (), target, parameters, result), 1);
  const int car = result.source_cluster[41];
  EXPECT_EQ (count (result.source_cluster, car), 20);
  EXPECT_TRUE (result.cluster_motions[car].isApprox (translation (1.0, 0.0)));
}

TEST (JointAdjacentClusters, TheCarsEndInTheTargetsViewTellsASlideApart)
{
  // The car moved 0.3 m back. Its front (12 points) was fitted 0.6 m back, its back
  // (8 points) 0.3 m. The front's motion puts the car's last point 0.3 m past the
  // target's last car point: where the post beyond shows that the target saw through.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  const auto front_twelve = [] (int points) {
    JointResult result = carInTwoOf (points, translation (-0.6, 0.0), translation (-0.3, 0.0));
    for (int i = 51; i < 53; ++i)
      result.source_cluster[i] = 1;
    return result;
  };
  JointResult with_post = front_twelve (64);
  const Eigen::Matrix2Xd target = withCarMoved (wallCarAndPost (), translation (-0.3, 0.0));
  EXPECT_EQ (mergeAdjacentClustersThatMoveAlike (wallCarAndPost (), target, parameters, with_post), 0);
  EXPECT_EQ (with_post.cluster_motions.size (), 3u);
  // Without the post the target's view ends at the car's last point: the point past it
  // is out of view, and the two motions explain every point in view alike.
  JointResult without_post = front_twelve (61);
  EXPECT_EQ (mergeAdjacentClustersThatMoveAlike (wallAndCar (), withCarMoved (wallAndCar (), translation (-0.3, 0.0)),
                                                 parameters, without_post),
             1);
  EXPECT_TRUE (without_post.cluster_motions[without_post.source_cluster[41]].isApprox (translation (-0.6, 0.0)));
}

/** The wall and the car of wallAndCar () in the static world (identity), the car's
 *  points [\a begin, \a end) in cluster 1 (motion \a T); every point matched to itself. */
JointResult
partOfTheCarMoving (int begin, int end, const Rigid2d& T)
{
  JointResult result;
  result.cluster_motions = {Rigid2d::Identity (), T};
  result.static_cluster = 0;
  for (int i = 0; i < 61; ++i) {
    result.source_cluster.push_back (i >= begin && i < end ? 1 : 0);
    result.source_match.push_back (i);
  }
  return result;
}

TEST (JointAdjacentClusters, TheStaticRestOfACarsSideJoinsItsMovingEnd)
{
  // The car moved 1 m along its side. Only its last five points (its back) were given
  // the car's motion; the static motion puts the other fifteen on the car's side in the
  // target too (0.2 m apart there, within 0.15 m of none but their own), as does the car's.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  const Eigen::Matrix2Xd target = withCarMoved (wallAndCar (), translation (1.0, 0.0));
  JointResult result = partOfTheCarMoving (56, 61, translation (1.0, 0.0));
  EXPECT_EQ (extendMovingClustersOverTheirSurfaces (wallAndCar (), target, parameters, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  const int car = result.source_cluster[41];
  EXPECT_NE (car, result.static_cluster);
  EXPECT_EQ (count (result.source_cluster, car), 20);
  EXPECT_EQ (count (result.source_cluster, result.static_cluster), 41);  // the wall, a surface of its own
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{41, 20}));
  for (int i = 41; i < 56; ++i)  // under the car's motion each lands on its own target point
    EXPECT_EQ (result.source_match[i], i) << i;
}

TEST (JointAdjacentClusters, StaticPointsTheMovingMotionExplainsWorseStay)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // The car's back moved 0.5 m across its side (the target shows it there), its front
  // stood: the back's motion puts the front 0.5 m off the car's side.
  Eigen::Matrix2Xd target = wallAndCar ();
  for (int i = 56; i < 61; ++i)
    target.col (i) += Eigen::Vector2d (0.0, 0.5);
  JointResult result = partOfTheCarMoving (56, 61, translation (0.0, 0.5));
  EXPECT_EQ (extendMovingClustersOverTheirSurfaces (wallAndCar (), target, parameters, result), 0);
  EXPECT_EQ (count (result.source_cluster, result.source_cluster[60]), 5);
  // Between two moving clusters, the run joins the one whose motion explains it: the
  // car moved 1 m along its side; its back has that motion, its front one 0.3 m across.
  JointResult two = partOfTheCarMoving (56, 61, translation (1.0, 0.0));
  two.cluster_motions.push_back (translation (1.0, 0.3));
  for (int i = 41; i < 46; ++i)
    two.source_cluster[i] = 2;
  EXPECT_EQ (extendMovingClustersOverTheirSurfaces (wallAndCar (), withCarMoved (wallAndCar (), translation (1.0, 0.0)),
                                                   parameters, two),
             1);
  EXPECT_EQ (count (two.source_cluster, two.source_cluster[50]), 15);
  EXPECT_EQ (two.source_cluster[50], two.source_cluster[60]);
  EXPECT_EQ (count (two.source_cluster, two.source_cluster[41]), 5);
  // Without a static world nothing is extended; inconsistent results are rejected.
  JointResult no_static = partOfTheCarMoving (56, 61, translation (1.0, 0.0));
  no_static.static_cluster = -1;
  EXPECT_EQ (extendMovingClustersOverTheirSurfaces (wallAndCar (), target, parameters, no_static), 0);
  JointResult short_result = partOfTheCarMoving (56, 61, translation (1.0, 0.0));
  short_result.source_match.pop_back ();
  EXPECT_THROW (extendMovingClustersOverTheirSurfaces (wallAndCar (), target, parameters, short_result),
                std::invalid_argument);
  // A NaN point in either scan is named, by this step and by the merge.
  Eigen::Matrix2Xd with_nan = wallAndCar ();
  with_nan (0, 50) = std::numeric_limits<double>::quiet_NaN ();
  JointResult any = partOfTheCarMoving (56, 61, translation (1.0, 0.0));
  EXPECT_THROW (extendMovingClustersOverTheirSurfaces (with_nan, target, parameters, any), std::invalid_argument);
  EXPECT_THROW (extendMovingClustersOverTheirSurfaces (wallAndCar (), with_nan, parameters, any), std::invalid_argument);
  EXPECT_THROW (mergeAdjacentClustersThatMoveAlike (with_nan, target, parameters, any), std::invalid_argument);
  EXPECT_THROW (mergeAdjacentClustersThatMoveAlike (wallAndCar (), with_nan, parameters, any), std::invalid_argument);
  try {
    mergeAdjacentClustersThatMoveAlike (with_nan, target, parameters, any);
  }
  catch (const std::invalid_argument& e) {
    EXPECT_NE (std::string (e.what ()).find ("NaN"), std::string::npos) << e.what ();
  }
}

}  // namespace
