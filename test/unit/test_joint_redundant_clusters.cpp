#include <pcl_crf/joint/joint_estimation.h>

#include <gtest/gtest.h>

#include "synthetic_scene.h"

#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::kOutlierCluster;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::removeClustersANearerClusterExplains;
using pcl_crf::joint::removeClustersTheStaticWorldExplains;

/** A wall of 101 target points 0.1 m apart along y = 5 m, x = 0 … 10 m. */
Eigen::Matrix2Xd
wall ()
{
  Eigen::Matrix2Xd target (2, 101);
  for (int j = 0; j < 101; ++j)
    target.col (j) = Eigen::Vector2d (0.1 * j, 5.0);
  return target;
}

/** Appends \a count source points of cluster \a cluster matched to target points
 *  \a first, first + 1, … */
void
addPoints (JointResult& result, int cluster, int first, int count)
{
  for (int k = 0; k < count; ++k) {
    result.source_cluster.push_back (cluster);
    result.source_match.push_back (first + k);
  }
}

/** \a clusters clusters of identity motion, the static world (cluster 0) with 80 points
 *  matched to target points 0–79. */
JointResult
staticWorldOnWall (int clusters)
{
  JointResult result;
  result.cluster_motions.assign (static_cast<std::size_t> (clusters), pcl_crf::Rigid2d::Identity ());
  result.static_cluster = 0;
  addPoints (result, 0, 0, 80);
  return result;
}

/** The static world (cluster 0) matched to target points 0–79; cluster 1 to 10–19 (all
 *  of them the static world's); cluster 2 to 90–99 (none); cluster 3 to 79–82 (half of
 *  them explained: 79 the static world's, 80 within 0.15 m of it, 81 and 82 0.2 m and
 *  0.3 m away); one outlier. */
JointResult
wallResult ()
{
  JointResult result = staticWorldOnWall (4);
  addPoints (result, 1, 10, 10);
  addPoints (result, 2, 90, 10);
  addPoints (result, 3, 79, 4);
  result.source_cluster.push_back (kOutlierCluster);
  result.source_match.push_back (kNoMatch);
  result.cluster_sizes = {80, 10, 10, 4};
  return result;
}

TEST (JointRedundantClusters, AClusterOnTargetPointsTheStaticWorldExplainsBecomesOutliers)
{
  // Spacing 0.1 m: the overlap radius is min(0.15, max(0.03, 2 · 0.1)) = 0.15 m.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = wallResult ();
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 3u);
  EXPECT_EQ (result.static_cluster, 0);
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{80, 10, 4}));
  for (int i = 80; i < 90; ++i) {  // cluster 1's points
    EXPECT_EQ (result.source_cluster[i], kOutlierCluster);
    EXPECT_EQ (result.source_match[i], kNoMatch);
  }
  EXPECT_EQ (result.source_cluster[90], 1);  // cluster 2, renumbered
  EXPECT_EQ (result.source_match[90], 90);
  EXPECT_EQ (result.source_cluster[100], 2);  // cluster 3, renumbered
  ASSERT_EQ (result.outliers.size (), 11u);
  EXPECT_EQ (result.outliers.front (), 80);
  EXPECT_EQ (result.outliers.back (), 104);
  // Nothing left to remove.
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, result), 0);
}

TEST (JointRedundantClusters, TheRadiusFollowsTheTargetSpacing)
{
  // With a 0.25 m metric radius, target point 81 (0.2 m from the static world's 79) is
  // explained too, three of cluster 3's four, so it goes as well; cluster 2 (1.1 m
  // away) stays.
  pcl_crf::matching::SegmentMotionParameters parameters;
  parameters.overlap_spacings = 0.0;
  parameters.overlap_radius = 0.25;
  JointResult result = wallResult ();
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, result), 2);
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{80, 10}));
  EXPECT_EQ (result.source_match[90], 90);
}

TEST (JointRedundantClusters, AClusterMostlyOnTargetPointsTheStaticWorldExplainsGoes)
{
  // A car piece of 10 points: 6 matched to the static world's target points 70–75, 4 to
  // 90–93, beyond its reach (1.4 m away): most of it repeats the static world.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = staticWorldOnWall (3);
  addPoints (result, 1, 70, 6);
  addPoints (result, 1, 90, 4);
  addPoints (result, 2, 72, 5);  // 5 of 10 explained: half is no majority, it stays
  addPoints (result, 2, 95, 5);
  result.cluster_sizes = {80, 10, 10};
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, result), 1);
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{80, 10}));
  for (int i = 80; i < 90; ++i) {
    EXPECT_EQ (result.source_cluster[i], kOutlierCluster);
    EXPECT_EQ (result.source_match[i], kNoMatch);
  }
  EXPECT_EQ (result.source_cluster[90], 1);
  EXPECT_EQ (result.source_match[95], 95);
}

TEST (JointRedundantClusters, LeavesResultsWithoutAStaticWorldOrMatchesAlone)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult no_static = wallResult ();
  no_static.static_cluster = -1;
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, no_static), 0);
  EXPECT_EQ (no_static.cluster_motions.size (), 4u);

  JointResult unmatched = wallResult ();  // cluster 1 loses its matches: no evidence either way
  for (int i = 80; i < 90; ++i)
    unmatched.source_match[i] = kNoMatch;
  EXPECT_EQ (removeClustersTheStaticWorldExplains (wall (), parameters, unmatched), 0);
}

TEST (JointRedundantClusters, RejectsInconsistentResults)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult sizes = wallResult ();
  sizes.source_match.pop_back ();
  EXPECT_THROW (removeClustersTheStaticWorldExplains (wall (), parameters, sizes), std::invalid_argument);
  JointResult match = wallResult ();
  match.source_match[3] = 101;
  EXPECT_THROW (removeClustersTheStaticWorldExplains (wall (), parameters, match), std::invalid_argument);
  JointResult cluster = wallResult ();
  cluster.source_cluster[3] = 4;
  EXPECT_THROW (removeClustersTheStaticWorldExplains (wall (), parameters, cluster), std::invalid_argument);
  JointResult static_cluster = wallResult ();
  static_cluster.static_cluster = 4;
  EXPECT_THROW (removeClustersTheStaticWorldExplains (wall (), parameters, static_cluster), std::invalid_argument);
}

/** A street seen twice from a standing sensor: a wall of 41 points 0.1 m apart along
 *  y = −5 m (x = 0 … 4 m) in both scans, and in the oncoming lane (y = 5 m) two cars of 11
 *  points each. In the source the near car spans x = 1 … 2 m and the far one 6 … 7 m;
 *  in the target the far car has come 2 m nearer (4 … 5 m) and the near one has left
 *  the view. Points: the wall, then the near car, then the far car; the target's
 *  points: the wall, then the far car. With \a post, the target also shows a post where
 *  the near car stood in the source (its 11 points last). */
void
leaderLeftTheView (Eigen::Matrix2Xd& source, Eigen::Matrix2Xd& target, bool post = false)
{
  source.resize (2, 63);
  target.resize (2, post ? 63 : 52);
  for (int k = 0; k < 41; ++k)
    source.col (k) = target.col (k) = Eigen::Vector2d (0.1 * k, -5.0);
  for (int k = 0; k < 11; ++k) {
    source.col (41 + k) = Eigen::Vector2d (1.0 + 0.1 * k, 5.0);
    source.col (52 + k) = Eigen::Vector2d (6.0 + 0.1 * k, 5.0);
    target.col (41 + k) = Eigen::Vector2d (4.0 + 0.1 * k, 5.0);
    if (post)
      target.col (52 + k) = Eigen::Vector2d (1.0 + 0.1 * k, 5.0);
  }
}

/** The wall in the static world (identity); the far car (cluster 2) with its true motion,
 *  2 m nearer; the near car (cluster 1) with the motion that carries it 3 m on, onto
 *  the far car's view in the target. Every point matched to the target point its
 *  cluster's motion puts it on. */
JointResult
leaderOnTheFollower ()
{
  JointResult result;
  result.cluster_motions = {pcl_crf::Rigid2d::Identity (), pcl_crf::test::translation (3.0, 0.0),
                            pcl_crf::test::translation (-2.0, 0.0)};
  result.static_cluster = 0;
  addPoints (result, 0, 0, 41);
  addPoints (result, 1, 41, 11);
  addPoints (result, 2, 41, 11);
  return result;
}

TEST (JointRedundantClusters, OfTwoClustersClaimingOneViewTheOneThatMovedFartherGoes)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  Eigen::Matrix2Xd source, target;
  leaderLeftTheView (source, target);
  JointResult result = leaderOnTheFollower ();
  EXPECT_EQ (removeClustersANearerClusterExplains (source, target, parameters, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  // The far car keeps its cluster, motion and matches; the near one becomes outliers,
  // and, since the static motion puts it where the target shows nothing, moved away.
  const int far = result.source_cluster[52];
  EXPECT_NE (far, result.static_cluster);
  EXPECT_TRUE (result.cluster_motions[far].isApprox (pcl_crf::test::translation (-2.0, 0.0)));
  std::vector<int> near_car;
  for (int i = 41; i < 52; ++i) {
    EXPECT_EQ (result.source_cluster[i], kOutlierCluster) << i;
    EXPECT_EQ (result.source_match[i], kNoMatch) << i;
    EXPECT_EQ (result.source_match[i + 11], i) << i;
    near_car.push_back (i);
  }
  EXPECT_EQ (result.moved_away, near_car);
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{41, 11}));
}

TEST (JointRedundantClusters, ARemovedClusterTheStaticMotionExplainsIsNotMovedAway)
{
  // A post in the target where the near car stood: the static motion explains its points,
  // so they are outliers, not moved away.
  const pcl_crf::matching::SegmentMotionParameters parameters;
  Eigen::Matrix2Xd source, target;
  leaderLeftTheView (source, target, true);
  JointResult result = leaderOnTheFollower ();
  EXPECT_EQ (removeClustersANearerClusterExplains (source, target, parameters, result), 1);
  EXPECT_EQ (result.source_cluster[41], kOutlierCluster);
  EXPECT_TRUE (result.moved_away.empty ());
  // Clusters that claim different views both stay: the far car matched elsewhere.
  JointResult apart = leaderOnTheFollower ();
  leaderLeftTheView (source, target);
  for (int i = 52; i < 63; ++i)
    apart.source_match[i] = i - 52;  // onto the wall
  EXPECT_EQ (removeClustersANearerClusterExplains (source, target, parameters, apart), 0);
  EXPECT_EQ (apart.cluster_motions.size (), 3u);
  // Without a static world nothing is removed; inconsistent results are rejected.
  JointResult no_static = leaderOnTheFollower ();
  no_static.static_cluster = -1;
  EXPECT_EQ (removeClustersANearerClusterExplains (source, target, parameters, no_static), 0);
  JointResult short_result = leaderOnTheFollower ();
  short_result.source_cluster.pop_back ();
  EXPECT_THROW (removeClustersANearerClusterExplains (source, target, parameters, short_result),
                std::invalid_argument);
}

}  // namespace
