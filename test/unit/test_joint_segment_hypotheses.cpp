#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/segment_motions.h>

#include <gtest/gtest.h>

#include "box_between_walls.h"
#include "synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::KnnIndex;
using pcl_crf::Rigid2d;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::LadderStart;
using pcl_crf::joint::addSegmentMotionHypotheses;
using pcl_crf::joint::keepLadderClustersTheFinalClusteringMerged;
using pcl_crf::test::boxBetweenWalls;
using pcl_crf::test::kBoxBegin;
using pcl_crf::test::kBoxEnd;
using pcl_crf::test::kBoxPoints;
using pcl_crf::test::kPoints;
using pcl_crf::test::kWallPoints;
using pcl_crf::test::onBox;
using pcl_crf::test::translation;

/** Every point in the static world's cluster (identity) but the first, an outlier. */
LadderStart
everythingStatic ()
{
  LadderStart start;
  start.motions = {Rigid2d::Identity ()};
  start.cluster.assign (kPoints, 0);
  start.cluster[0] = 1;  // the outlier cluster
  return start;
}

TEST (JointSegmentHypotheses, ASegmentTheStaticMotionLeavesAndIcpExplainsStartsItsOwnCluster)
{
  // The box moved 5 cm away, beyond its 3 cm overlap radius (3 range_noise).
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const KnnIndex target_points (boxBetweenWalls (translation (0.05, 0.0)));
  LadderStart start = everythingStatic ();
  EXPECT_EQ (addSegmentMotionHypotheses (source, target_points, Rigid2d::Identity (),
                                         pcl_crf::matching::SegmentMotionParameters (), start),
             1);
  ASSERT_EQ (start.motions.size (), 2u);
  EXPECT_NEAR (start.motions[1].translation ().x (), 0.05, 1e-6);
  EXPECT_NEAR (start.motions[1].translation ().y (), 0.0, 1e-6);
  EXPECT_NEAR (std::atan2 (start.motions[1].linear () (1, 0), start.motions[1].linear () (0, 0)), 0.0, 1e-6);
  for (int i = 1; i < kPoints; ++i)
    EXPECT_EQ (start.cluster[i], onBox (i) ? 1 : 0) << "point " << i;
  EXPECT_EQ (start.cluster[0], 2) << "the outlier cluster is numbered after the new one";
}

TEST (JointSegmentHypotheses, NoHypothesisWhereTheStaticMotionExplainsTheSegment)
{
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // Still, or moved by 2 cm, within the overlap radius: the static motion explains it.
  for (const double shift : {0.0, 0.02}) {
    const KnnIndex target_points (boxBetweenWalls (translation (shift, 0.0)));
    LadderStart start = everythingStatic ();
    EXPECT_EQ (addSegmentMotionHypotheses (source, target_points, Rigid2d::Identity (), parameters, start), 0)
        << "shift " << shift;
    EXPECT_EQ (start.motions.size (), 1u);
    EXPECT_EQ (start.cluster, everythingStatic ().cluster);
  }
  // Gone from the target: the box's points are far from everything, under any motion
  // ICP reaches within the gate.
  Eigen::Matrix2Xd without_box (2, 2 * kWallPoints);
  without_box << source.leftCols (kWallPoints), source.rightCols (kWallPoints);
  LadderStart start = everythingStatic ();
  EXPECT_EQ (addSegmentMotionHypotheses (source, KnnIndex (without_box), Rigid2d::Identity (), parameters, start), 0);
}

TEST (JointSegmentHypotheses, ASegmentOutsideTheStaticClusterIsLeftToItsCluster)
{
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const KnnIndex target_points (boxBetweenWalls (translation (0.05, 0.0)));
  LadderStart start = everythingStatic ();
  start.motions.push_back (translation (0.05, 0.0));  // the box already has a cluster of its own
  for (int& l : start.cluster)
    l = l == 1 ? 2 : l;
  for (int i = kBoxBegin; i < kBoxEnd; ++i)
    start.cluster[i] = 1;
  const LadderStart before = start;
  EXPECT_EQ (addSegmentMotionHypotheses (source, target_points, Rigid2d::Identity (),
                                         pcl_crf::matching::SegmentMotionParameters (), start),
             0);
  EXPECT_EQ (start.cluster, before.cluster);
}

TEST (JointSegmentHypotheses, AStartOfAnotherSizeIsAnError)
{
  LadderStart start = everythingStatic ();
  start.cluster.pop_back ();
  EXPECT_THROW (addSegmentMotionHypotheses (boxBetweenWalls (), KnnIndex (boxBetweenWalls ()), Rigid2d::Identity (),
                                            pcl_crf::matching::SegmentMotionParameters (), start),
                std::invalid_argument);
}

/** The ladder: the walls static (identity), the box in cluster 1 of \a box_motion;
 *  every point matched to its own index. */
JointResult
ladderWithBox (const Rigid2d& box_motion)
{
  JointResult ladder;
  ladder.cluster_motions = {Rigid2d::Identity (), box_motion};
  ladder.static_cluster = 0;
  for (int i = 0; i < kPoints; ++i) {
    ladder.source_cluster.push_back (onBox (i) ? 1 : 0);
    ladder.source_match.push_back (i);
  }
  return ladder;
}

/** The final clustering's result: everything in the static world (identity). */
JointResult
allStatic ()
{
  JointResult result = ladderWithBox (Rigid2d::Identity ());
  result.cluster_motions.resize (1);
  std::fill (result.source_cluster.begin (), result.source_cluster.end (), 0);
  return result;
}

TEST (JointSegmentHypotheses, ALadderClusterTheFinalClusteringMergedIsKeptWhereItMoved)
{
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const Rigid2d box_motion = translation (0.05, 0.0);
  const Eigen::Matrix2Xd target = boxBetweenWalls (box_motion);
  JointResult result = allStatic ();
  EXPECT_EQ (keepLadderClustersTheFinalClusteringMerged (source, target, pcl_crf::matching::SegmentMotionParameters (),
                                                         ladderWithBox (box_motion), result),
             1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_EQ (result.static_cluster, 0);  // the walls, the larger cluster
  EXPECT_TRUE (result.cluster_motions[1].isApprox (box_motion));
  for (int i = 0; i < kPoints; ++i) {
    EXPECT_EQ (result.source_cluster[i], onBox (i) ? 1 : 0) << "point " << i;
    EXPECT_EQ (result.source_match[i], i) << "the matches stand";
  }
}

TEST (JointSegmentHypotheses, ALadderClusterStaysMergedWhereTheDataDoNotSayItMoved)
{
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const Rigid2d box_motion = translation (0.05, 0.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  // The box did not move: the static motion explains it.
  JointResult still = allStatic ();
  EXPECT_EQ (keepLadderClustersTheFinalClusteringMerged (source, boxBetweenWalls (), parameters,
                                                         ladderWithBox (box_motion), still),
             0);
  EXPECT_EQ (still.cluster_motions.size (), 1u);
  // The ladder held only part of the box's static points: the surface is one, and part
  // of it static.
  JointResult part = allStatic ();
  JointResult ladder = ladderWithBox (box_motion);
  for (int i = kBoxBegin; i < kBoxBegin + 5; ++i)
    ladder.source_cluster[i] = 0;
  EXPECT_EQ (keepLadderClustersTheFinalClusteringMerged (source, boxBetweenWalls (box_motion), parameters, ladder, part),
             0);
  EXPECT_EQ (part.source_cluster, allStatic ().source_cluster);
}

/** The target after the box slid 0.3 m to the left (bearings 18° … 34°, hiding the
 *  left wall up to 34°), with a board 0.3 m ahead over the box's old bearings when
 *  \a board. */
Eigen::Matrix2Xd
boxSlidLeft (bool board)
{
  const Eigen::Matrix2Xd before = boxBetweenWalls ();
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < kWallPoints; ++k)
    points.push_back (before.col (k));
  for (int k = 0; board && k < kBoxPoints; ++k)
    points.push_back (0.5 * before.col (kBoxBegin + k));
  for (int k = 0; k < kBoxPoints; ++k)
    points.push_back (translation (0.0, 0.3) * before.col (kBoxBegin + k));
  for (int k = 15; k < kWallPoints; ++k)
    points.push_back (before.col (kBoxEnd + k));
  return pcl_crf::test::asColumns (points);
}

TEST (JointSegmentHypotheses, APointHiddenBehindATargetReturnSaysNothing)
{
  // Without the board, the target saw through where the static motion puts the box, and
  // sees it where the ladder's motion does: kept. With the board, the target could not
  // have seen the box where the static motion puts it, so its absence there is no
  // evidence: the cluster stays merged.
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  const pcl_crf::matching::SegmentMotionParameters parameters;
  const auto unmatched = [] (JointResult result) {  // the targets differ in size here
    std::fill (result.source_match.begin (), result.source_match.end (), pcl_crf::kNoMatch);
    return result;
  };
  const JointResult ladder = unmatched (ladderWithBox (translation (0.0, 0.3)));
  JointResult open = unmatched (allStatic ());
  EXPECT_EQ (keepLadderClustersTheFinalClusteringMerged (source, boxSlidLeft (false), parameters, ladder, open), 1);
  JointResult hidden = unmatched (allStatic ());
  EXPECT_EQ (keepLadderClustersTheFinalClusteringMerged (source, boxSlidLeft (true), parameters, ladder, hidden), 0);
}

TEST (JointSegmentHypotheses, ResultsOfAnotherSizeAreAnError)
{
  const Eigen::Matrix2Xd source = boxBetweenWalls ();
  JointResult ladder = ladderWithBox (translation (0.05, 0.0));
  ladder.source_cluster.pop_back ();
  ladder.source_match.pop_back ();
  JointResult result = allStatic ();
  EXPECT_THROW (keepLadderClustersTheFinalClusteringMerged (source, source, pcl_crf::matching::SegmentMotionParameters (),
                                                            ladder, result),
                std::invalid_argument);
}

}  // namespace
