#include <pcl_crf/matching/range_profile.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::matching::hiddenBehindAReturn;
using pcl_crf::matching::inFieldOfView;
using pcl_crf::matching::makeRangeProfile;
using pcl_crf::matching::seesThrough;
using pcl_crf::matching::seesThroughFirmly;
using pcl_crf::matching::seesThroughToAReturn;

constexpr double kDegree = M_PI / 180.0;
constexpr double kLambda = 10.0 * kDegree;  // breakpoint angle
constexpr double kNoise = 0.01;

Eigen::Vector2d
polar (double degrees, double range)
{
  return range * Eigen::Vector2d (std::cos (degrees * kDegree), std::sin (degrees * kDegree));
}

/** Returns from the given beams (degrees) on a wall x = 5 m. */
Eigen::Matrix2Xd
wallScan (const std::vector<int>& beams)
{
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (beams.size ()));
  for (std::size_t k = 0; k < beams.size (); ++k)
    scan.col (static_cast<Eigen::Index> (k)) = polar (beams[k], 5.0 / std::cos (beams[k] * kDegree));
  return scan;
}

/** Beams every degree over [−45°, 45°] on the wall; 10°–20° saw nothing, and −20°
 *  dropped out. */
Eigen::Matrix2Xd
wallWithOpening ()
{
  std::vector<int> beams;
  for (int degrees = -45; degrees <= 45; ++degrees)
    if ((degrees < 10 || degrees > 20) && degrees != -20)
      beams.push_back (degrees);
  return wallScan (beams);
}

/** The breakpoint distance at range r for 1° steps: r sin 1° / sin 9° + 3σ. */
double
margin (double r)
{
  return r * std::sin (kDegree) / std::sin (9.0 * kDegree) + 3.0 * kNoise;
}

TEST (RangeProfile, SortsReturnsByBearingAndFindsTheStepAndFarthestReturn)
{
  Eigen::Matrix2Xd scan = wallWithOpening ();
  std::swap (scan (0, 0), scan (0, 5));  // any order
  std::swap (scan (1, 0), scan (1, 5));
  const auto profile = makeRangeProfile (scan);
  ASSERT_EQ (profile.bearings.size (), 79);  // 91 beams, 11 in the opening, one dropped
  EXPECT_NEAR (profile.bearings (0), -45.0 * kDegree, 1e-12);
  EXPECT_NEAR (profile.bearings (78), 45.0 * kDegree, 1e-12);
  EXPECT_NEAR (profile.ranges (0), 5.0 * std::sqrt (2.0), 1e-12);
  EXPECT_NEAR (profile.step, kDegree, 1e-12);
  EXPECT_NEAR (profile.max_range, 5.0 * std::sqrt (2.0), 1e-12);
  EXPECT_FALSE (profile.full_circle);
}

TEST (RangeProfile, APointBeforeTheReturnsAroundItWasSeenThrough)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  // At 0.5° the returns at 0° and 1° lie at 5 m and 5.0008 m; margin (3) = 0.365 m.
  EXPECT_TRUE (seesThrough (profile, polar (0.5, 3.0), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (0.5, 5.0 - margin (4.4) - 0.01), kLambda, kNoise));
  // On the wall, just before it (within the margin) or behind it: not seen through.
  EXPECT_FALSE (seesThrough (profile, polar (0.5, 4.8), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (0.5, 5.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (0.5, 6.0), kLambda, kNoise));
}

TEST (RangeProfile, DirectionsWithoutReturnsAreFreeUpToTheFarthestReturn)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  // 15°: the nearest returns (9°, 21°) are 6 steps away; free up to 7.07 m.
  EXPECT_TRUE (seesThrough (profile, polar (15.0, 5.0), kLambda, kNoise));  // 5 + 0.588 < 7.07
  EXPECT_FALSE (seesThrough (profile, polar (15.0, 6.6), kLambda, kNoise));  // 6.6 + 0.766 > 7.07
  // 9.5°: the return at 9° (5.066 m) is within a step, the one at 21° is not.
  EXPECT_TRUE (seesThrough (profile, polar (9.5, 3.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (9.5, 5.0), kLambda, kNoise));
  // A dropped beam is no opening: at −20.2° the return at −21° (5.356 m) is within a step.
  EXPECT_FALSE (seesThrough (profile, polar (-20.2, 5.2), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (-20.2, 4.0), kLambda, kNoise));
}

TEST (RangeProfile, OnTheEvidenceOfReturnsOnlyADirectionWithoutReturnsSaysNothing)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  const auto distance = pcl_crf::matching::breakpointDistance (profile, kLambda, kNoise);
  // Where returns lie within a step, as seesThrough ().
  EXPECT_TRUE (seesThroughToAReturn (profile, polar (0.5, 3.0), distance));
  EXPECT_FALSE (seesThroughToAReturn (profile, polar (0.5, 4.8), distance));
  EXPECT_TRUE (seesThroughToAReturn (profile, polar (9.5, 3.0), distance));
  EXPECT_TRUE (seesThroughToAReturn (profile, polar (-20.2, 4.0), distance));
  // In the opening (no return within a step) seesThrough () says free, this says nothing.
  EXPECT_TRUE (seesThrough (profile, polar (15.0, 5.0), distance));
  EXPECT_FALSE (seesThroughToAReturn (profile, polar (15.0, 5.0), distance));
  EXPECT_FALSE (seesThroughToAReturn (profile, polar (15.0, 1.0), distance));
  // Outside the field of view neither does.
  EXPECT_FALSE (seesThroughToAReturn (profile, polar (60.0, 1.0), distance));
}

/** Beams every degree over [−10°, 10°]: a post's outline at 6.8 m up to −2°, −1°
 *  dropped at its edge, then a wall at 14 m. */
Eigen::Matrix2Xd
postBeforeAWall ()
{
  std::vector<Eigen::Vector2d> returns;
  for (int degrees = -10; degrees <= 10; ++degrees)
    if (degrees != -1)
      returns.push_back (polar (degrees, degrees < 0 ? 6.8 : 14.0));
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (returns.size ()));
  for (std::size_t k = 0; k < returns.size (); ++k)
    scan.col (static_cast<Eigen::Index> (k)) = returns[k];
  return scan;
}

TEST (RangeProfile, BesideADroppedEdgeReturnASeenThroughPointIsNoFirmEvidence)
{
  const auto profile = makeRangeProfile (postBeforeAWall ());
  const auto distance = pcl_crf::matching::breakpointDistance (profile, kLambda, kNoise);
  // −0.2°: the wall's return at 0° saw past it; the post's at −2° lies 1.8° away, across
  // the dropped beam. Its breakpoint distance across 1.8° is
  // 6.8 sin 1.8° / sin 8.2° + 0.03 = 1.53 m, across one step margin (6.8) = 0.79 m.
  const double across_the_gap = 6.8 * std::sin (1.8 * kDegree) / std::sin (8.2 * kDegree) + 3.0 * kNoise;
  EXPECT_NEAR (distance.slopeAcross (1.8 * kDegree) * 6.8 + distance.offset, across_the_gap, 1e-12);
  // 1 m behind the post's outline: beyond one step's distance, within the gap's. The
  // post's edge may lie anywhere up to the wall's beam, and the point on it.
  const Eigen::Vector2d behind_the_edge = polar (-0.2, 7.8);
  EXPECT_TRUE (seesThrough (profile, behind_the_edge, distance));
  EXPECT_FALSE (seesThroughFirmly (profile, behind_the_edge, distance));
  // 2.5 m behind it, beyond the gap's distance too: the post does not reach it.
  EXPECT_TRUE (seesThroughFirmly (profile, polar (-0.2, 9.3), distance));
  // With the beam at −1° returned (nearer than the point), the beams either side
  // disagree: not seen through at all.
  Eigen::Matrix2Xd whole (2, postBeforeAWall ().cols () + 1);
  whole << postBeforeAWall (), polar (-1.0, 6.8);
  EXPECT_FALSE (seesThrough (makeRangeProfile (whole), behind_the_edge, distance));
  // Past a return within one step on both sides there is no gap to continue across.
  EXPECT_TRUE (seesThroughFirmly (profile, polar (4.5, 7.8), distance));
  // No λ beyond the bearing difference: the slope is infinite.
  EXPECT_TRUE (std::isinf (distance.slopeAcross (kLambda)));
}

TEST (RangeProfile, OneBeamPastASurfacesLastReturnIsNoFirmEvidence)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  const auto distance = pcl_crf::matching::breakpointDistance (profile, kLambda, kNoise);
  // 10.5°: no return within a step; the one at 9° (5.066 m) is 1.5 steps away. On the
  // wall's line (5.084 m) the point continues it across the beam at 10°, which a real
  // laser may have dropped at the wall's edge: free for seesThrough (), not firmly.
  const Eigen::Vector2d continuing = polar (10.5, 5.0 / std::cos (10.5 * kDegree));
  EXPECT_TRUE (seesThrough (profile, continuing, distance));
  EXPECT_FALSE (seesThroughFirmly (profile, continuing, distance));
  // Nearer than the wall by more than the breakpoint distance it continues nothing.
  EXPECT_TRUE (seesThroughFirmly (profile, polar (10.5, 3.0), distance));
  // 15°: the nearest returns (9°, 21°) are 6 steps away.
  EXPECT_TRUE (seesThroughFirmly (profile, polar (15.0, 5.0), distance));
  // Where returns lie within a step, as seesThrough ().
  EXPECT_TRUE (seesThroughFirmly (profile, polar (0.5, 3.0), distance));
  EXPECT_FALSE (seesThroughFirmly (profile, polar (0.5, 4.8), distance));
  EXPECT_FALSE (seesThroughFirmly (profile, polar (60.0, 1.0), distance));
}

TEST (RangeProfile, APointBehindEveryReturnAroundItIsHidden)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  const auto distance = pcl_crf::matching::breakpointDistance (profile, kLambda, kNoise);
  // At 0.5° the returns lie at 5 m and 5.0008 m; the margin at the return's range,
  // margin (5.0008) = 0.588 m.
  EXPECT_TRUE (hiddenBehindAReturn (profile, polar (0.5, 6.0), distance));
  EXPECT_TRUE (hiddenBehindAReturn (profile, polar (0.5, 5.0008 + margin (5.0008) + 0.001), distance));
  // On the wall, just behind it (within the margin) or before it: not hidden.
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (0.5, 5.0008 + margin (5.0008) - 0.001), distance));
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (0.5, 5.3), distance));
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (0.5, 5.0), distance));
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (0.5, 3.0), distance));
  // No return within a step (the opening), or outside the field of view: nothing hides it.
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (15.0, 9.0), distance));
  EXPECT_FALSE (hiddenBehindAReturn (profile, polar (60.0, 9.0), distance));
  // 9.5°: the return at 9° (5.066 m) is within a step, the one at 21° is not.
  EXPECT_TRUE (hiddenBehindAReturn (profile, polar (9.5, 6.0), distance));
}

TEST (RangeProfile, NothingOutsideTheFieldOfViewWasSeenThrough)
{
  const auto profile = makeRangeProfile (wallWithOpening ());
  EXPECT_FALSE (seesThrough (profile, polar (60.0, 1.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (-90.0, 1.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (180.0, 1.0), kLambda, kNoise));
}

TEST (RangeProfile, AFieldOfViewAcrossTheBackWraps)
{
  // A rear scanner: beams over [135°, 225°] on a circle of radius 4 m.
  Eigen::Matrix2Xd scan (2, 91);
  for (int k = 0; k <= 90; ++k)
    scan.col (k) = polar (135.0 + k, 4.0);
  const auto profile = makeRangeProfile (scan);
  EXPECT_FALSE (profile.full_circle);
  EXPECT_NEAR (profile.step, kDegree, 1e-9);
  EXPECT_TRUE (seesThrough (profile, polar (180.0, 2.0), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (-179.7, 2.0), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (179.7, 2.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (180.0, 3.9), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (0.0, 1.0), kLambda, kNoise));  // in front: not looked at
}

TEST (RangeProfile, AFullCircleWrapsAtTheBack)
{
  Eigen::Matrix2Xd scan (2, 360);
  for (int k = 0; k < 360; ++k)
    scan.col (k) = polar (-179.0 + k, 4.0);
  const auto profile = makeRangeProfile (scan);
  EXPECT_TRUE (profile.full_circle);
  EXPECT_TRUE (seesThrough (profile, polar (179.9, 2.0), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (-179.9, 2.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (profile, polar (-179.9, 3.9), kLambda, kNoise));
  EXPECT_TRUE (seesThrough (profile, polar (90.3, 3.5 - margin (3.5)), kLambda, kNoise));
}

TEST (RangeProfile, TooFewReturnsSayNothingAndNonFinitePointsAreRejected)
{
  EXPECT_FALSE (seesThrough (makeRangeProfile (Eigen::Matrix2Xd (2, 0)), polar (0.0, 1.0), kLambda, kNoise));
  EXPECT_FALSE (seesThrough (makeRangeProfile (wallScan ({0})), polar (0.0, 1.0), kLambda, kNoise));
  // A breakpoint angle no larger than the step leaves no margin to judge by.
  EXPECT_FALSE (seesThrough (makeRangeProfile (wallWithOpening ()), polar (0.5, 1.0), 0.5 * kDegree, kNoise));
  Eigen::Matrix2Xd bad = wallWithOpening ();
  bad (1, 3) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (makeRangeProfile (bad), std::invalid_argument);
}

/** seesThrough () as its documentation defines it, by looking at every return, for a
 *  profile whose field of view does not wrap (it is [first, last] bearing). */
bool
seesThroughByEveryReturn (const pcl_crf::matching::RangeProfile& profile, const Eigen::Vector2d& point,
                          const pcl_crf::matching::BreakpointDistance& distance)
{
  const double theta = std::atan2 (point.y (), point.x ()), range = point.norm ();
  const double margin = range * distance.slope + distance.offset;
  if (theta < profile.bearings (0) || theta > profile.bearings (profile.bearings.size () - 1))
    return false;
  bool near_return = false;
  for (Eigen::Index j = 0; j < profile.bearings.size (); ++j) {
    if (std::abs (std::remainder (profile.bearings (j) - theta, 2.0 * M_PI)) > profile.step)
      continue;
    near_return = true;
    if (profile.ranges (j) <= range + margin)
      return false;
  }
  return near_return || range + margin < profile.max_range;
}

TEST (RangeProfile, IrregularBeamsAnswerAsEveryReturnWould)
{
  // A 270° scan of a wavy room whose beams drop out singly and in runs of up to 30,
  // and a third of which have a second return half a step on (the lookup's guess
  // from evenly stepped bearings misses either way there): seesThrough
  // agrees with the definition over every return for points all over the field of
  // view, at every range.
  std::vector<Eigen::Vector2d> returns;
  unsigned state = 12345u;
  const auto next = [&state] () { return (state = state * 1103515245u + 12345u) >> 16; };
  for (int k = 0; k <= 1080; ++k) {
    if (next () % 7 == 0)
      k += static_cast<int> (next () % 30);  // a run of dropped beams
    const double degrees = -135.0 + 0.25 * k;
    if (degrees > 135.0)
      break;
    returns.push_back (polar (degrees, 4.0 + std::sin (5.0 * degrees * kDegree)));
    if (next () % 3 == 0)  // a second return half a step on: bearings denser than the step
      returns.push_back (polar (degrees + 0.125, 4.5 + std::sin (5.0 * degrees * kDegree)));
  }
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (returns.size ()));
  for (std::size_t k = 0; k < returns.size (); ++k)
    scan.col (static_cast<Eigen::Index> (k)) = returns[k];
  const auto profile = makeRangeProfile (scan);
  const auto distance = pcl_crf::matching::breakpointDistance (profile, kLambda, kNoise);
  int seen_through = 0, checked = 0;
  for (double degrees = -134.9; degrees < 134.9; degrees += 0.0731)
    for (double range : {0.5, 3.3, 3.9, 4.6, 5.2, 6.0}) {
      const Eigen::Vector2d point = polar (degrees, range);
      const bool expected = seesThroughByEveryReturn (profile, point, distance);
      ASSERT_EQ (seesThrough (profile, point, distance), expected) << degrees << "° at " << range << " m";
      seen_through += expected ? 1 : 0;
      ++checked;
    }
  EXPECT_GT (seen_through, checked / 4);  // both answers are well represented
  EXPECT_LT (seen_through, 3 * checked / 4);
}

TEST (RangeProfile, TheFieldOfViewSpansTheReturnsAcrossInnerGapsOrGoesAllRound)
{
  const auto profile = makeRangeProfile (wallWithOpening ());  // returns over [−45°, 45°]
  EXPECT_TRUE (inFieldOfView (profile, polar (0.0, 3.0)));
  EXPECT_TRUE (inFieldOfView (profile, polar (15.0, 30.0)));  // in the opening: still in view
  EXPECT_TRUE (inFieldOfView (profile, polar (-45.0, 1.0)));
  EXPECT_FALSE (inFieldOfView (profile, polar (46.0, 3.0)));
  EXPECT_FALSE (inFieldOfView (profile, polar (-50.0, 3.0)));
  EXPECT_FALSE (inFieldOfView (profile, polar (180.0, 3.0)));

  Eigen::Matrix2Xd circle (2, 360);
  for (int k = 0; k < 360; ++k)
    circle.col (k) = polar (k, 4.0);
  EXPECT_TRUE (inFieldOfView (makeRangeProfile (circle), polar (-179.5, 9.0)));
  EXPECT_FALSE (inFieldOfView (makeRangeProfile (wallScan ({0})), polar (0.0, 1.0)));  // one return: no view known
}

}  // namespace

namespace {

/** A 360-beam laser (1° apart, from −179°) whose returns lie on a circle of 4 m except
 *  in [60°, 120°], where it saw nothing in range (a sector wider than any other gap,
 *  so the returns alone make it the sensor's back). */
Eigen::Matrix2Xd
roundScanWithEmptySector ()
{
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 360; ++k) {
    const int degrees = -179 + k;
    if (degrees < 60 || degrees > 120)
      points.push_back (polar (degrees, 4.0));
  }
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    scan.col (static_cast<Eigen::Index> (k)) = points[k];
  return scan;
}

pcl_crf::SensorInfo
laser (int beams, double first_degrees, double step_degrees)
{
  pcl_crf::SensorInfo sensor;
  sensor.beam_count = beams;
  sensor.angle_min = first_degrees * kDegree;
  sensor.angle_increment = step_degrees * kDegree;
  sensor.range_max = 8.0;
  return sensor;
}

}  // namespace

TEST (RangeProfile, ARoundLaserHasNoBackWhereverItsReturnsLeaveASectorEmpty)
{
  const Eigen::Matrix2Xd scan = roundScanWithEmptySector ();
  const Eigen::Vector2d in_sector = polar (90.0, 1.0), behind_return = polar (0.0, 4.5);

  const auto inferred = makeRangeProfile (scan);
  EXPECT_FALSE (inferred.full_circle);
  EXPECT_FALSE (inFieldOfView (inferred, in_sector));  // taken for the back
  EXPECT_FALSE (seesThrough (inferred, in_sector, kLambda, kNoise));

  const auto known = makeRangeProfile (scan, laser (360, -179.0, 1.0));
  EXPECT_TRUE (known.full_circle);
  EXPECT_TRUE (inFieldOfView (known, in_sector));
  EXPECT_TRUE (seesThrough (known, in_sector, kLambda, kNoise));              // free up to the farthest return
  EXPECT_FALSE (seesThroughToAReturn (known, in_sector, pcl_crf::matching::breakpointDistance (known, kLambda, kNoise)));  // no return says so
  EXPECT_FALSE (seesThrough (known, behind_return, kLambda, kNoise));
  EXPECT_TRUE (seesThrough (known, polar (0.0, 3.0), kLambda, kNoise));
  // The same beams swept clockwise.
  EXPECT_TRUE (makeRangeProfile (scan, laser (360, 180.0, -1.0)).full_circle);
}

TEST (RangeProfile, ALaserWithABackKeepsTheFieldOfViewOfItsReturns)
{
  const Eigen::Matrix2Xd scan = wallWithOpening ();  // returns over [−45°, 45°]
  const auto inferred = makeRangeProfile (scan);
  for (const auto& sensor : {laser (91, -45.0, 1.0), laser (181, -90.0, 1.0), pcl_crf::SensorInfo{}}) {
    const auto profile = makeRangeProfile (scan, sensor);
    EXPECT_FALSE (profile.full_circle);
    EXPECT_DOUBLE_EQ (profile.bearings (0), inferred.bearings (0));
    EXPECT_DOUBLE_EQ (profile.bearings (profile.bearings.size () - 1), inferred.bearings (inferred.bearings.size () - 1));
    EXPECT_TRUE (seesThrough (profile, polar (15.0, 3.0), kLambda, kNoise));  // the opening
    EXPECT_FALSE (seesThrough (profile, polar (-60.0, 1.0), kLambda, kNoise));
  }
  EXPECT_NEAR (inferred.bearings (0), -45.0 * kDegree, 1e-12);
  EXPECT_NEAR (inferred.bearings (inferred.bearings.size () - 1), 45.0 * kDegree, 1e-12);
}

TEST (RangeProfile, ASensorThatDescribesNoBeamsSensiblyIsRejected)
{
  const Eigen::Matrix2Xd scan = wallWithOpening ();
  EXPECT_THROW (makeRangeProfile (scan, laser (1, 0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW (makeRangeProfile (scan, laser (-5, 0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW (makeRangeProfile (scan, laser (91, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW (makeRangeProfile (scan, laser (91, std::numeric_limits<double>::quiet_NaN (), 1.0)),
                std::invalid_argument);
  EXPECT_THROW (makeRangeProfile (scan, laser (91, 0.0, std::numeric_limits<double>::infinity ())),
                std::invalid_argument);
}
