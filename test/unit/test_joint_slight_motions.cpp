#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/matching/segment_motions.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "box_between_walls.h"
#include "synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::Rigid2d;
using pcl_crf::joint::JointResult;
using pcl_crf::joint::SlightMotionTest;
using pcl_crf::joint::separateSegmentsThatMovedSlightly;
using pcl_crf::test::boxBetweenWalls;
using pcl_crf::test::kBoxBegin;
using pcl_crf::test::kBoxEnd;
using pcl_crf::test::kPoints;
using pcl_crf::test::kWallPoints;
using pcl_crf::test::onBox;
using pcl_crf::test::translation;
using pcl_crf::test::wallsAround;

constexpr int kMinPoints = 3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();
constexpr double kInfinity = std::numeric_limits<double>::infinity ();

/** Every point in the static world (identity), matched to the target point of its own index. */
JointResult
allStatic ()
{
  JointResult result;
  result.cluster_motions = {Rigid2d::Identity ()};
  result.static_cluster = 0;
  result.source_cluster.assign (kPoints, 0);
  for (int i = 0; i < kPoints; ++i)
    result.source_match.push_back (i);
  return result;
}

/** separateSegmentsThatMovedSlightly () of the box between walls against \a target,
 *  everything static, with the default test and the matcher's segment parameters. */
int
separate (const Eigen::Matrix2Xd& target, JointResult& result, const SlightMotionTest& test = {})
{
  return separateSegmentsThatMovedSlightly (boxBetweenWalls (), target, pcl_crf::matching::SegmentMotionParameters (),
                                            test, kMinPoints, result);
}

TEST (JointSlightMotions, ABoxThatMovedTwoCentimetresIsSeparatedWithItsMotion)
{
  // 2 cm is within the box's 3 cm overlap radius (3 range_noise), so a target point is
  // near every box point under the static motion; but each sits 2 cm off the box's face,
  // 21 points at σ² = 0.01² + (0.5 · 1° · 0.6 m)²: D ≈ 66 ≥ 32.
  const Rigid2d box_motion = translation (0.02, 0.0);
  JointResult result = allStatic ();
  for (int i = kBoxBegin; i < kBoxEnd; ++i)
    result.source_match[i] = i + 1;  // a beam off, as under the static motion
  EXPECT_EQ (separate (boxBetweenWalls (box_motion), result), 1);
  ASSERT_EQ (result.cluster_motions.size (), 2u);
  EXPECT_EQ (result.static_cluster, 0);  // the walls, the larger cluster
  EXPECT_NEAR (result.cluster_motions[1].translation ().x (), 0.02, 1e-6);
  EXPECT_NEAR (result.cluster_motions[1].translation ().y (), 0.0, 1e-6);
  for (int i = 0; i < kPoints; ++i) {
    EXPECT_EQ (result.source_cluster[i], onBox (i) ? 1 : 0) << "point " << i;
    EXPECT_EQ (result.source_match[i], i) << "matched under the box's own motion";
  }
}

TEST (JointSlightMotions, OneCentimetreOrNoMotionIsNotEnoughEvidence)
{
  // 1 cm: D ≈ 21 · 0.01² / (0.01² + 0.0052²) ≈ 16.5, below 32.
  for (const double shift : {0.0, 0.01}) {
    JointResult result = allStatic ();
    EXPECT_EQ (separate (boxBetweenWalls (translation (shift, 0.0)), result), 0) << "shift " << shift;
    EXPECT_EQ (result.source_cluster, allStatic ().source_cluster);
  }
  // Lower bars take the 1 cm box (each point shows 0.79 variances).
  JointResult result = allStatic ();
  SlightMotionTest lenient;
  lenient.min_deviance = 10.0;
  lenient.min_mean_deviance = 0.5;
  EXPECT_EQ (separate (boxBetweenWalls (translation (0.01, 0.0)), result, lenient), 1);
}

TEST (JointSlightMotions, AStaticMotionThatFitsLooselyEverywhereNeedsMoreEvidence)
{
  // Everything moved 2 cm, the static motion stayed at identity: the walls' residuals
  // (1–2 cm) make the pair's misfit, σ² grows by their median over 0.4549, and the box,
  // 2 cm off like everything else, is no longer evidence of its own motion.
  const Eigen::Matrix2Xd target = translation (0.02, 0.0) * boxBetweenWalls ();
  JointResult result = allStatic ();
  EXPECT_EQ (separate (target, result), 0);
  EXPECT_EQ (result.source_cluster, allStatic ().source_cluster);
}

TEST (JointSlightMotions, AFarWallThatMovedTwoCentimetresIsWithinItsBeamSpacing)
{
  // The right wall 2 cm farther away (6.02 m): at 6 m the beams land 10 cm apart, and
  // half of that is the outline's uncertainty, σ ≈ 5 cm: D ≈ 41 · 0.02² / 0.0028 ≈ 6.
  Eigen::Matrix2Xd target = boxBetweenWalls ();
  for (int i = kBoxEnd; i < kPoints; ++i)
    target.col (i) *= 6.02 / 6.0;
  JointResult result = allStatic ();
  EXPECT_EQ (separate (target, result), 0);
  // Without the along-beam uncertainty the wall would be separated.
  SlightMotionTest range_noise_only;
  range_noise_only.along_beam_steps = 0.0;
  JointResult strict = allStatic ();
  EXPECT_EQ (separate (target, strict, range_noise_only), 1);
  EXPECT_EQ (strict.source_cluster[kBoxEnd], 1);
}

TEST (JointSlightMotions, PointsBeyondTheEndOfTheTargetSurfaceSayNothing)
{
  // The target dropped the box's last 8 returns (no return there: nothing seen through).
  // The static motion puts those source points beyond the end of the target's box, up
  // to 8 cm from it; that is no evidence of motion, and the box stays static.
  const Eigen::Matrix2Xd full = boxBetweenWalls ();
  Eigen::Matrix2Xd target (2, kPoints - 8);
  target << full.leftCols (kBoxEnd - 8), full.rightCols (kWallPoints);
  JointResult result = allStatic ();
  std::fill (result.source_match.begin (), result.source_match.end (), pcl_crf::kNoMatch);
  EXPECT_EQ (separate (target, result), 0);
  EXPECT_EQ (result.source_cluster, allStatic ().source_cluster);
}

TEST (JointSlightMotions, PointsHiddenBehindATargetReturnSayNothing)
{
  // In the target a wider board stands 12 cm in front of where the box was (x = 0.48, y
  // from −0.15 to 0.15): more than the breakpoint distance (9 cm there) nearer, so the
  // target could not have seen the box. ICP would pull the box onto the board, within
  // the 15 cm gate; but hidden points are no evidence, and the box stays static.
  std::vector<Eigen::Vector2d> board;
  for (int k = 0; k <= 30; ++k)
    board.push_back (Eigen::Vector2d (0.48, -0.15 + 0.01 * k));
  JointResult result = allStatic ();
  std::fill (result.source_match.begin (), result.source_match.end (), pcl_crf::kNoMatch);
  EXPECT_EQ (separate (wallsAround (board), result), 0);
  EXPECT_EQ (result.source_cluster, allStatic ().source_cluster);
}

/** The walls of boxBetweenWalls () with a 60-point panel in place of the box (x = 0.6, y
 *  from −0.1475 to 0.1475, 5 mm apart), the panel moved by \a shift along x. */
Eigen::Matrix2Xd
panelBetweenWalls (double shift)
{
  std::vector<Eigen::Vector2d> panel;
  for (int k = 0; k < 60; ++k)
    panel.push_back (Eigen::Vector2d (0.6 + shift, -0.1475 + 0.005 * k));
  return wallsAround (panel);
}

TEST (JointSlightMotions, ALongSegmentNeedsItsPointsToShowTheMotion)
{
  // The panel moved 9 mm: each of its 60 points favours the panel's own motion by
  // 0.009² / (0.01² + 0.0052²) ≈ 0.64 variances, D ≈ 38 in all. That passes 32, but no
  // point shows the motion beyond its noise: not separated. Asking no least mean, it is.
  const Eigen::Matrix2Xd source = panelBetweenWalls (0.0);
  const auto separated = [&source] (const SlightMotionTest& test) {
    JointResult result = allStatic ();
    result.source_cluster.assign (source.cols (), 0);
    result.source_match.assign (source.cols (), pcl_crf::kNoMatch);
    return separateSegmentsThatMovedSlightly (source, panelBetweenWalls (0.009),
                                              pcl_crf::matching::SegmentMotionParameters (), test, kMinPoints, result);
  };
  EXPECT_EQ (separated ({}), 0);
  SlightMotionTest any_mean;
  any_mean.min_mean_deviance = 0.0;
  EXPECT_EQ (separated (any_mean), 1);
}

/** The walls of boxBetweenWalls () with a rod in place of the box (x = 0.6, y from −0.2 to
 *  0.2, 2 cm apart), the rod turned by \a degrees about its lower end. */
Eigen::Matrix2Xd
rodBetweenWalls (double degrees)
{
  const Rigid2d turn = translation (0.6, -0.2) * Eigen::Rotation2Dd (degrees * M_PI / 180.0) * translation (-0.6, 0.2);
  std::vector<Eigen::Vector2d> rod;
  for (int k = 0; k <= 20; ++k)
    rod.push_back (turn * Eigen::Vector2d (0.6, -0.2 + 0.02 * k));
  return wallsAround (rod);
}

TEST (JointSlightMotions, AMotionThatMovesAPointBeyondTheGateIsNotSlight)
{
  // The rod turned by 15° about its lower end: its top moved 10 cm, within the 15 cm
  // gate, and ICP follows it. Turned by 25°, the top moved 17 cm: ICP still follows,
  // pairing the lower points first, but that is a larger motion than the step is for.
  const Eigen::Matrix2Xd source = rodBetweenWalls (0.0);
  const pcl_crf::matching::SegmentMotionParameters parameters;
  const auto separated = [&] (double degrees) {
    JointResult result = allStatic ();
    result.source_cluster.assign (source.cols (), 0);
    result.source_match.assign (source.cols (), pcl_crf::kNoMatch);
    return separateSegmentsThatMovedSlightly (source, rodBetweenWalls (-degrees), parameters, {}, kMinPoints, result);
  };
  EXPECT_EQ (separated (15.0), 1);
  EXPECT_EQ (separated (25.0), 0);
}

TEST (JointSlightMotions, ResultsAndSettingsOutOfRangeAreErrors)
{
  const Eigen::Matrix2Xd target = boxBetweenWalls (translation (0.02, 0.0));
  JointResult short_result = allStatic ();
  short_result.source_cluster.pop_back ();
  short_result.source_match.pop_back ();
  EXPECT_THROW (separate (target, short_result), std::invalid_argument);
  for (const double bad : {0.0, -1.0, kNaN, kInfinity}) {
    JointResult result = allStatic ();
    SlightMotionTest test;
    test.min_deviance = bad;
    EXPECT_THROW (separate (target, result, test), std::invalid_argument) << "min_deviance " << bad;
  }
  for (const double bad : {-0.5, kNaN, kInfinity}) {
    JointResult result = allStatic ();
    SlightMotionTest test;
    test.min_mean_deviance = bad;
    EXPECT_THROW (separate (target, result, test), std::invalid_argument) << "min_mean_deviance " << bad;
  }
  for (const double bad : {-0.5, kNaN, kInfinity}) {
    JointResult result = allStatic ();
    SlightMotionTest test;
    test.along_beam_steps = bad;
    EXPECT_THROW (separate (target, result, test), std::invalid_argument) << "along_beam_steps " << bad;
  }
  JointResult result = allStatic ();
  EXPECT_THROW (separateSegmentsThatMovedSlightly (boxBetweenWalls (), target,
                                                   pcl_crf::matching::SegmentMotionParameters (), {}, 0, result),
                std::invalid_argument);
  pcl_crf::joint::JointParameters parameters;
  parameters.slight_motion.min_deviance = -1.0;
  EXPECT_THROW (pcl_crf::joint::validateParameters (parameters), std::invalid_argument);
  parameters = {};
  parameters.slight_motion.min_mean_deviance = -1.0;
  EXPECT_THROW (pcl_crf::joint::validateParameters (parameters), std::invalid_argument);
  parameters = {};
  parameters.slight_motion.along_beam_steps = kNaN;
  EXPECT_THROW (pcl_crf::joint::validateParameters (parameters), std::invalid_argument);
}

}  // namespace
