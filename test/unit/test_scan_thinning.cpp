// Tests of thinning scans to a model's beam spacing and of lifting the associations
// found on the thinned scans back to every point.

#include <pcl_crf/core/scan_thinning.h>
#include <pcl_crf/matching/lifted_matches.h>

#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using namespace pcl_crf;

constexpr double kDegree = M_PI / 180.0;

/** Points on a circle of radius 5 m at bearings first + k step, for every k of \a beams. */
Eigen::Matrix2Xd
arcScan (double first, double step, const std::vector<int>& beams)
{
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (beams.size ()));
  for (std::size_t k = 0; k < beams.size (); ++k) {
    const double bearing = first + step * beams[k];
    points.col (static_cast<Eigen::Index> (k)) << 5.0 * std::cos (bearing), 5.0 * std::sin (bearing);
  }
  return points;
}

std::vector<int>
range (int count)
{
  std::vector<int> values (static_cast<std::size_t> (count));
  for (int k = 0; k < count; ++k)
    values[static_cast<std::size_t> (k)] = k;
  return values;
}

TEST (ScanThinning, MedianSpacingIgnoresMissingReturns)
{
  std::vector<int> beams;
  for (int k = 0; k < 1081; ++k)
    if (k % 7 != 3)  // every seventh return missing
      beams.push_back (k);
  EXPECT_NEAR (medianBeamSpacing (arcScan (-135 * kDegree, 0.25 * kDegree, beams)), 0.25 * kDegree, 1e-12);
  EXPECT_EQ (medianBeamSpacing (Eigen::Matrix2Xd (2, 0)), 0.0);
  EXPECT_EQ (medianBeamSpacing (arcScan (0.0, kDegree, {4})), 0.0);
}

TEST (ScanThinning, FactorIsTheRoundedRatioOfTheSpacings)
{
  EXPECT_EQ (thinningFactor (0.25 * kDegree, 0.5 * kDegree), 2);
  EXPECT_EQ (thinningFactor (0.2501 * kDegree, 0.5 * kDegree), 2);  // measured a little coarser
  EXPECT_EQ (thinningFactor (0.2 * kDegree, 0.5 * kDegree), 2);     // never coarser than the model
  EXPECT_EQ (thinningFactor (kDegree / 6, 0.5 * kDegree), 3);
  EXPECT_EQ (thinningFactor (0.125 * kDegree, 0.5 * kDegree), 4);
  EXPECT_EQ (thinningFactor (kDegree / 3, 0.5 * kDegree), 1);  // 1.5: 0.67° would be coarser
  EXPECT_EQ (thinningFactor (0.4 * kDegree, 0.5 * kDegree), 1);
  EXPECT_EQ (thinningFactor (kDegree, 0.5 * kDegree), 1);        // coarser than the model
  EXPECT_EQ (thinningFactor (0.0, 0.5 * kDegree), 1);            // unknown spacings
  EXPECT_EQ (thinningFactor (0.25 * kDegree, 0.0), 1);
  EXPECT_THROW (thinningFactor (-1.0, 0.5), std::invalid_argument);
  EXPECT_THROW (thinningFactor (0.1, std::numeric_limits<double>::quiet_NaN ()), std::invalid_argument);
}

TEST (ScanThinning, KeepsEveryOtherBeamAcrossMissingReturns)
{
  // Beams 0 … 10 at 0.25°, beam 3 missing: the even beams 0, 2, 4, 6, 8, 10 are
  // points 0, 2, 3, 5, 7, 9.
  const Eigen::Matrix2Xd scan = arcScan (-10 * kDegree, 0.25 * kDegree, {0, 1, 2, 4, 5, 6, 7, 8, 9, 10});
  const ThinnedScan thinned = thinToSpacing (scan, 0.5 * kDegree);
  EXPECT_EQ (thinned.kept, (std::vector<int>{0, 2, 3, 5, 7, 9}));
  ASSERT_EQ (thinned.points.cols (), 6);
  EXPECT_EQ (thinned.points.col (2), scan.col (3));
  EXPECT_TRUE (thinned.isThinned (scan.cols ()));
}

TEST (ScanThinning, FullTurnThroughTheBackOfTheSensorKeepsEveryOtherBeam)
{
  // 1440 beams over 360° starting at 170°, so the bearings jump from +180° to −180°.
  const Eigen::Matrix2Xd scan = arcScan (170 * kDegree, 0.25 * kDegree, range (1440));
  const ThinnedScan thinned = thinToSpacing (scan, 0.5 * kDegree);
  ASSERT_EQ (thinned.kept.size (), 720u);
  for (std::size_t k = 0; k < thinned.kept.size (); ++k)
    EXPECT_EQ (thinned.kept[k], static_cast<int> (2 * k));
}

TEST (ScanThinning, ScansAtOrBelowTheModelsResolutionAreLeftAlone)
{
  const Eigen::Matrix2Xd scan = arcScan (-90 * kDegree, 0.5 * kDegree, range (361));
  for (const double model_spacing : {0.5 * kDegree, 0.9 * kDegree, 0.0}) {
    const ThinnedScan thinned = thinToSpacing (scan, model_spacing);
    EXPECT_EQ (thinned.kept, range (361));
    EXPECT_FALSE (thinned.isThinned (scan.cols ()));
  }
}

/** A pair thinned by hand: the even points of both scans kept. */
matching::ThinnedPair
evenPointsOf (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target)
{
  matching::ThinnedPair thinned;
  for (ThinnedScan* scan : {&thinned.source, &thinned.target}) {
    const Eigen::Matrix2Xd& full = scan == &thinned.source ? source : target;
    for (int i = 0; i < full.cols (); i += 2)
      scan->kept.push_back (i);
    scan->points.resize (2, static_cast<Eigen::Index> (scan->kept.size ()));
    for (std::size_t k = 0; k < scan->kept.size (); ++k)
      scan->points.col (static_cast<Eigen::Index> (k)) = full.col (scan->kept[k]);
  }
  thinned.anchors = matching::thinnedAnchors (source, thinned.source);
  return thinned;
}

TEST (LiftedMatches, AnchorsAreTheNearerKeptNeighbour)
{
  Eigen::Matrix2Xd source (2, 5);
  source << 0.0, 0.9, 1.0, 1.2, 2.0,  // point 1 is nearer to 2, point 3 nearer to 2 too
      0.0, 0.0, 0.0, 0.0, 0.0;
  ThinnedScan kept;
  kept.kept = {0, 2, 4};
  kept.points = source (Eigen::all, kept.kept);
  EXPECT_EQ (matching::thinnedAnchors (source, kept), (std::vector<int>{0, 1, 1, 1, 2}));
  EXPECT_EQ (matching::liftLabels ({0, 1, 1, 1, 2}, {7, -1, 3}), (std::vector<int>{7, -1, -1, -1, 3}));
}

TEST (LiftedMatches, TargetSpanCoversThePointsDroppedAroundAKeptPoint)
{
  ThinnedScan target;
  target.kept = {0, 2, 4, 6};
  EXPECT_EQ (matching::targetSpan (target, 8, 0), Eigen::Vector2i (0, 1));
  EXPECT_EQ (matching::targetSpan (target, 8, 1), Eigen::Vector2i (1, 3));
  EXPECT_EQ (matching::targetSpan (target, 8, 3), Eigen::Vector2i (5, 7));  // up to the last point
}

TEST (LiftedMatches, RecoversEveryTrueMatchOfARigidlyMovedRoom)
{
  // The room every 5 cm, moved; target point i is source point i moved. The thinned
  // scans are matched exactly (kept point k to kept target k); the dropped odd points
  // must find theirs among their neighbours', under a motion 5 mm / 1 mrad off.
  const Rigid2d truth = makeRigid2d (0.3, 0.1, 0.05);
  const ScanPair pair = test::staticRoomPair (truth, Rigid2d::Identity (), 0.05);
  const matching::ThinnedPair thinned = evenPointsOf (pair.source, pair.target);
  const int kept = static_cast<int> (thinned.source.kept.size ());
  const std::vector<int> coarse = range (kept);
  const std::vector<int> groups (static_cast<std::size_t> (kept), 0);
  const Rigid2d estimate = makeRigid2d (0.305, 0.1, 0.051);
  const std::vector<int> lifted =
      matching::liftMatches (pair.source, pair.target, thinned, coarse, groups, {estimate});
  EXPECT_EQ (lifted, pair.source_match);
}

TEST (LiftedMatches, AMoverLeftInTheStaticGroupFollowsItsNeighbours)
{
  // A wall 5 m long sampled every 5 cm drives 0.4 m along itself, but every point is
  // in the group of the room's motion (identity): the matched neighbours' common
  // offset, 8 thinned steps, moves the dropped points along with them.
  Eigen::Matrix2Xd source (2, 100), target (2, 100);
  for (int i = 0; i < 100; ++i) {
    source.col (i) << -4.0 + 0.05 * i, -3.0;
    target.col (i) << -4.0 + 0.05 * i, -3.0;
  }
  const matching::ThinnedPair thinned = evenPointsOf (source, target);
  std::vector<int> coarse, groups;
  for (int k = 0; k < 50; ++k) {
    coarse.push_back (k + 4 < 50 ? k + 4 : kNoMatch);  // 8 points (0.4 m) further on
    groups.push_back (coarse.back () == kNoMatch ? -1 : 0);
  }
  const std::vector<int> lifted = matching::liftMatches (source, target, thinned, coarse, groups, {Rigid2d::Identity ()});
  for (int i = 0; i < 92; ++i)
    EXPECT_EQ (lifted[i], i + 8) << i;
  for (int i = 92; i < 100; ++i)  // anchored at unmatched kept points
    EXPECT_EQ (lifted[i], kNoMatch) << i;
}

TEST (LiftedMatches, RejectsInconsistentInput)
{
  const ScanPair pair = test::staticRoomPair (Rigid2d::Identity (), Rigid2d::Identity (), 0.1);
  const matching::ThinnedPair thinned = evenPointsOf (pair.source, pair.target);
  const std::size_t kept = thinned.source.kept.size ();
  const std::vector<int> coarse = range (static_cast<int> (kept));
  const std::vector<int> groups (kept, 0);
  EXPECT_THROW (matching::liftMatches (pair.source, pair.target, thinned, {1, 2}, groups, {Rigid2d::Identity ()}),
                std::invalid_argument);
  EXPECT_THROW (matching::liftMatches (pair.source, pair.target, thinned, coarse, groups, {}), std::invalid_argument);
  std::vector<int> outside = coarse;
  outside[0] = static_cast<int> (thinned.target.kept.size ());
  EXPECT_THROW (matching::liftMatches (pair.source, pair.target, thinned, outside, groups, {Rigid2d::Identity ()}),
                std::invalid_argument);
  EXPECT_THROW (matching::liftMatches (pair.source.leftCols (10), pair.target, thinned, coarse, groups,
                                       {Rigid2d::Identity ()}),
                std::invalid_argument);
}

}  // namespace
