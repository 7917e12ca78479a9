#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_model.h>

#include <gtest/gtest.h>

#include "synthetic_scene.h"

#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::kOutlierCluster;
using pcl_crf::Rigid2d;
using pcl_crf::test::translation;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::separateDistantParts;

/** Appends \a count points of cluster \a cluster, 0.2 m apart along x from (\a x, \a y),
 *  each matched to the target point of its own index. */
void
addRun (Eigen::Matrix2Xd& source, JointResult& result, int cluster, double x, double y, int count)
{
  const Eigen::Index first = source.cols ();
  source.conservativeResize (2, first + count);
  for (int k = 0; k < count; ++k) {
    source.col (first + k) = Eigen::Vector2d (x + 0.2 * k, y);
    result.source_cluster.push_back (cluster);
    result.source_match.push_back (static_cast<int> (first + k));
  }
}

/** The static world (cluster 0): two walls 20 m apart, 30 points each. Cluster 1, moving
 *  1 m along x: a car of 10 points (x 5–6.8 m, y 3 m), a gap of 2.2 m, a second car of
 *  8 points (x 9–10.4 m), and 1.9 m on, a cyclist of 3 (x 12.3–12.7 m). Cluster 2,
 *  moving 0.5 m along y: a pedestrian of 4 points at x 30 m. One outlier 5 m from
 *  everything. */
struct Scene
{
  Eigen::Matrix2Xd source{2, 0};
  JointResult result;

  Scene ()
  {
    result.cluster_motions = {Rigid2d::Identity (), translation (1.0, 0.0), translation (0.0, 0.5)};
    result.static_cluster = 0;
    addRun (source, result, 0, 0.0, 10.0, 30);   // points 0–29
    addRun (source, result, 0, 0.0, -10.0, 30);  // 30–59
    addRun (source, result, 1, 5.0, 3.0, 10);    // 60–69
    addRun (source, result, 1, 9.0, 3.0, 8);     // 70–77
    addRun (source, result, 1, 12.3, 3.0, 3);    // 78–80
    addRun (source, result, 2, 30.0, 0.0, 4);    // 81–84
    addRun (source, result, kOutlierCluster, 20.0, 5.0, 1);  // 85
    result.source_match.back () = kNoMatch;
    result.cluster_sizes = {60, 21, 4};
  }
};

TEST (JointDistantParts, AMovingClusterFarApartBecomesOneClusterPerPart)
{
  Scene scene;
  // The car pair splits at its 2.2 m gap; the cyclist, 1.9 m from the second car, stays with it.
  EXPECT_EQ (separateDistantParts (scene.source, 2.0, scene.result), 1);
  const JointResult& result = scene.result;
  ASSERT_EQ (result.cluster_motions.size (), 4u);
  EXPECT_EQ (result.cluster_sizes, (std::vector<int>{60, 11, 10, 4}));
  EXPECT_EQ (result.static_cluster, 0);
  for (int i = 0; i < 60; ++i)
    EXPECT_EQ (result.source_cluster[i], 0);
  for (int i = 60; i < 70; ++i)
    EXPECT_EQ (result.source_cluster[i], 2);  // the first car keeps the motion, now third largest
  for (int i = 70; i < 81; ++i)
    EXPECT_EQ (result.source_cluster[i], 1);  // the second car and the cyclist
  for (int i = 81; i < 85; ++i)
    EXPECT_EQ (result.source_cluster[i], 3);
  EXPECT_EQ (result.source_cluster[85], kOutlierCluster);
  EXPECT_EQ (result.outliers, (std::vector<int>{85}));
  for (int l : {1, 2})
    EXPECT_TRUE (result.cluster_motions[l].isApprox (translation (1.0, 0.0)));
  EXPECT_TRUE (result.cluster_motions[3].isApprox (translation (0.0, 0.5)));
  for (int i = 0; i < 85; ++i)
    EXPECT_EQ (result.source_match[i], i);  // matches untouched
}

TEST (JointDistantParts, AWiderGapKeepsThePartsTogether)
{
  Scene scene;
  EXPECT_EQ (separateDistantParts (scene.source, 2.3, scene.result), 0);
  EXPECT_EQ (scene.result.cluster_motions.size (), 3u);
  EXPECT_EQ (scene.result.source_cluster[60], 1);
  EXPECT_EQ (scene.result.source_cluster[80], 1);
}

TEST (JointDistantParts, ANarrowerGapSplitsTheCyclistToo)
{
  Scene scene;
  EXPECT_EQ (separateDistantParts (scene.source, 1.5, scene.result), 2);
  EXPECT_EQ (scene.result.cluster_sizes, (std::vector<int>{60, 10, 8, 4, 3}));
}

TEST (JointDistantParts, LeavesTheStaticWorldAndResultsWithoutOneWhole)
{
  Scene scene;
  scene.result.static_cluster = -1;  // nothing tells which clusters move
  EXPECT_EQ (separateDistantParts (scene.source, 2.0, scene.result), 0);
  EXPECT_EQ (scene.result.cluster_motions.size (), 3u);
  // The walls, 20 m apart, are one static world: cluster 0 only loses nothing.
  Scene walls;
  separateDistantParts (walls.source, 0.5, walls.result);
  EXPECT_EQ (walls.result.cluster_sizes.front (), 60);
  EXPECT_EQ (walls.result.static_cluster, 0);
}

TEST (JointDistantParts, RejectsNonsenseGapsAndInconsistentResults)
{
  Scene scene;
  for (double gap : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN (), std::numeric_limits<double>::infinity ()})
    EXPECT_THROW (separateDistantParts (scene.source, gap, scene.result), std::invalid_argument);
  JointResult sizes = scene.result;
  sizes.source_cluster.pop_back ();
  EXPECT_THROW (separateDistantParts (scene.source, 2.0, sizes), std::invalid_argument);
  JointResult cluster = scene.result;
  cluster.source_cluster[3] = 7;
  EXPECT_THROW (separateDistantParts (scene.source, 2.0, cluster), std::invalid_argument);
  JointResult static_cluster = scene.result;
  static_cluster.static_cluster = 3;
  EXPECT_THROW (separateDistantParts (scene.source, 2.0, static_cluster), std::invalid_argument);
  pcl_crf::joint::JointParameters parameters;
  parameters.part_gap = 0.0;
  EXPECT_THROW (pcl_crf::joint::validateParameters (parameters), std::invalid_argument);
}

}  // namespace
