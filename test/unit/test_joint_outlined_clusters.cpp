#include <pcl_crf/joint/joint_estimation.h>

#include <gtest/gtest.h>

#include "synthetic_scene.h"

#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::kOutlierCluster;
using pcl_crf::Rigid2d;
using pcl_crf::test::translation;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::removeClustersOnTheStaticOutline;

/** Points along y = \a y at x = first, first + step, ... (\a count of them), in beam order
 *  for a sensor at the origin (counter-clockwise: x decreasing when y > 0). */
std::vector<Eigen::Vector2d>
line (double y, double first, double step, int count)
{
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < count; ++k)
    points.emplace_back (first + k * step, y);
  return points;
}

Eigen::Matrix2Xd
scan (const std::vector<std::vector<Eigen::Vector2d>>& parts)
{
  std::vector<Eigen::Vector2d> all;
  for (const auto& part : parts)
    all.insert (all.end (), part.begin (), part.end ());
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (all.size ()));
  for (std::size_t i = 0; i < all.size (); ++i)
    points.col (static_cast<Eigen::Index> (i)) = all[i];
  return points;
}

/** The sensor drove 0.5 m forward (static motion: x − 0.5). A wall to its right along
 *  y = −3, seen at grazing incidence 1 m between samples, then a wall ahead along y = 5
 *  (x from 2 down to −2, 0.25 m apart), both static. */
struct GrazingWall
{
  Eigen::Matrix2Xd source, target;
  int wall_points = 5;

  /** \a target_first: the x of the target's first sample of the grazing wall. */
  explicit GrazingWall (double target_first, int target_samples = 5)
  {
    source = scan ({line (-3.0, 10.0, 1.0, wall_points), line (5.0, 2.0, -0.25, 17)});
    target = scan ({line (-3.0, target_first, 1.0, target_samples), line (5.0, 1.5, -0.25, 17)});
  }

  /** The wall ahead in the static world (cluster 0), matched to the same target points;
   *  the grazing wall in cluster 1 of motion \a T, matched to its nearest target point. */
  JointResult
  result (const Rigid2d& T) const
  {
    JointResult r;
    r.cluster_motions = {translation (-0.5, 0.0), T};
    r.static_cluster = 0;
    const int target_wall = static_cast<int> (target.cols ()) - 17;
    for (int i = 0; i < wall_points; ++i) {
      Eigen::Index j;
      (target.leftCols (target_wall).colwise () - T * source.col (i)).colwise ().squaredNorm ().minCoeff (&j);
      r.source_cluster.push_back (1);
      r.source_match.push_back (static_cast<int> (j));
    }
    for (int k = 0; k < 17; ++k) {
      r.source_cluster.push_back (0);
      r.source_match.push_back (target_wall + k);
    }
    return r;
  }
};

TEST (JointOutlinedClusters, AGrazingWallSlidByWholeSamplesIsTheStaticWorld)
{
  // Target samples at x = 9.2, 10.2, ..., 14.2: a motion 0.8 m back (0.3 m more than the
  // static one) puts every source sample on a target sample; the static motion puts them
  // between two, on the wall's outline. Both explain all five: the static world is the
  // simpler explanation.
  const GrazingWall scene (9.2, 6);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  JointResult result = scene.result (translation (-0.8, 0.0));
  ASSERT_EQ (removeClustersOnTheStaticOutline (scene.source, scene.target, parameters, result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 1u);
  EXPECT_EQ (result.static_cluster, 0);
  for (int i = 0; i < scene.wall_points; ++i) {
    EXPECT_EQ (result.source_cluster[i], kOutlierCluster) << i;
    EXPECT_EQ (result.source_match[i], kNoMatch) << i;
  }
  for (Eigen::Index i = scene.wall_points; i < scene.source.cols (); ++i)
    EXPECT_EQ (result.source_cluster[i], 0) << i;
}

TEST (JointOutlinedClusters, AClusterItsOwnMotionExplainsBetterOrOffTheOutlineStays)
{
  const pcl_crf::matching::SegmentMotionParameters parameters;
  {
    // The target sees the grazing wall only up to x = 11.8: the static motion puts 3 of
    // the 5 samples on it (x 9.5 to 11.5), a motion 1.2 m back 4 (on the samples 8.8 to
    // 11.8; the fifth, at 12.8, is off). Its own motion explains more: it stays.
    const GrazingWall scene (8.8, 4);
    JointResult result = scene.result (translation (-1.2, 0.0));
    EXPECT_EQ (removeClustersOnTheStaticOutline (scene.source, scene.target, parameters, result), 0);
    EXPECT_EQ (result.cluster_motions.size (), 2u);
  }
  {
    // Under the static motion the wall's samples lie 0.1 m off the target's outline
    // (y = −3.1 there), farther than 3 range_noise (0.03 m): it stays.
    GrazingWall scene (9.2, 6);
    for (int k = 0; k < 6; ++k)
      scene.target (1, k) = -3.1;
    JointResult result = scene.result (translation (-0.8, -0.1));
    EXPECT_EQ (removeClustersOnTheStaticOutline (scene.source, scene.target, parameters, result), 0);
  }
  {
    // A result without a static world, or the static world alone, is left as it is.
    const GrazingWall scene (9.2);
    JointResult no_static = scene.result (translation (-0.8, 0.0));
    no_static.static_cluster = -1;
    EXPECT_EQ (removeClustersOnTheStaticOutline (scene.source, scene.target, parameters, no_static), 0);
    JointResult bad = scene.result (translation (-0.8, 0.0));
    bad.source_cluster.pop_back ();
    EXPECT_THROW (removeClustersOnTheStaticOutline (scene.source, scene.target, parameters, bad),
                  std::invalid_argument);
  }
}

}  // namespace
