#include <pcl_crf/core/beam_order.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

/** Points at the bearings \a degrees, 2 to 6 m from the origin. */
Eigen::Matrix2Xd
atBearings (const std::vector<double>& degrees)
{
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (degrees.size ()));
  for (std::size_t k = 0; k < degrees.size (); ++k) {
    const double bearing = degrees[k] * kPi / 180.0, range = 2.0 + static_cast<double> (k % 5);
    points.col (static_cast<Eigen::Index> (k)) << range * std::cos (bearing), range * std::sin (bearing);
  }
  return points;
}

/** A laser's beams from \a first, \a count of them \a step degrees apart (negative: clockwise). */
std::vector<double>
beams (double first, int count, double step)
{
  std::vector<double> degrees;
  for (int b = 0; b < count; ++b)
    degrees.push_back (first + b * step);
  return degrees;
}

std::vector<int>
identity (std::size_t n)
{
  std::vector<int> order (n);
  std::iota (order.begin (), order.end (), 0);
  return order;
}

/** \a points' columns in the order \a order. */
Eigen::Matrix2Xd
reordered (const Eigen::Matrix2Xd& points, const std::vector<int>& order)
{
  Eigen::Matrix2Xd out (2, points.cols ());
  for (std::size_t k = 0; k < order.size (); ++k)
    out.col (static_cast<Eigen::Index> (k)) = points.col (order[k]);
  return out;
}

}  // namespace

TEST (BeamOrder, BacktrackIsTheWayBackOverTheWayForward)
{
  // Steps +10°, −5°, +15°: 25° forward, 5° back.
  EXPECT_NEAR (pcl_crf::bearingBacktrack (atBearings ({0.0, 10.0, 5.0, 20.0})), 5.0 / 25.0, 1e-12);
  // Clockwise the other way round: 25° clockwise, 5° back.
  EXPECT_NEAR (pcl_crf::bearingBacktrack (atBearings ({20.0, 5.0, 10.0, 0.0})), 5.0 / 25.0, 1e-12);
  // Across ±180°: 170° → −170° is a step of +20°, not −340°.
  EXPECT_EQ (pcl_crf::bearingBacktrack (atBearings ({150.0, 170.0, -170.0, -150.0})), 0.0);
  // A point at the origin has no bearing and is passed over; two bearings make no way.
  Eigen::Matrix2Xd with_origin = atBearings ({0.0, 10.0, 5.0, 20.0});
  with_origin.col (1).setZero ();
  EXPECT_EQ (pcl_crf::bearingBacktrack (with_origin), 0.0);
  EXPECT_EQ (pcl_crf::bearingBacktrack (atBearings ({0.0, 10.0})), 0.0);
}

TEST (BeamOrder, ALasersScanCounterClockwiseIsInBeamOrderFromAnyStart)
{
  const std::vector<std::vector<double>> scans = {
      beams (-90.0, 361, 0.5),    // a SICK
      beams (-135.0, 1081, 0.25), // a Hokuyo's 270°
      beams (37.0, 720, 0.5),     // all round, from 37° across ±180°
  };
  for (const std::vector<double>& degrees : scans) {
    const Eigen::Matrix2Xd scan = atBearings (degrees);
    EXPECT_EQ (pcl_crf::bearingBacktrack (scan), 0.0);
    EXPECT_TRUE (pcl_crf::inBeamOrder (scan));
  }
  // Listed from their backs, the partial views are read as listed.
  EXPECT_EQ (pcl_crf::beamOrder (atBearings (scans[0])), identity (361));
  EXPECT_EQ (pcl_crf::beamOrder (atBearings (scans[1])), identity (1081));
}

TEST (BeamOrder, A360ScanIsCutAtItsWidestBreakWhateverBeamItsListingStartsOn)
{
  // A wall 5 m round a 360° laser (0.5° beams), a box 1 m away on beams 100–139 and a
  // car 3 m away on beams 140–199: the widest jump between neighbours is onto the box
  // (5 m -> 1 m). Listed from any beam, the chain starts there.
  const auto range = [] (int beam) { return beam >= 100 && beam < 140 ? 1.0 : beam >= 140 && beam < 200 ? 3.0 : 5.0; };
  for (const int first : {0, 37, 120, 600}) {
    Eigen::Matrix2Xd scan (2, 720);
    std::vector<int> beam_of (720);
    for (int k = 0; k < 720; ++k) {
      beam_of[k] = (first + k) % 720;
      const double bearing = beam_of[k] * 0.5 * kPi / 180.0;
      scan.col (k) << range (beam_of[k]) * std::cos (bearing), range (beam_of[k]) * std::sin (bearing);
    }
    const std::vector<int> order = pcl_crf::beamOrder (scan);
    ASSERT_EQ (order.size (), 720u);
    for (int k = 0; k < 720; ++k)
      ASSERT_EQ (beam_of[order[k]], (100 + k) % 720) << "listed from beam " << first << ", chain point " << k;
  }
  // With a sector without a return (beams 400–459 left out) the chain starts after it.
  Eigen::Matrix2Xd open (2, 660);
  for (int k = 0, beam = 470; k < 660; ++k, beam = (beam + 1) % 720) {
    if (beam == 400)
      beam = 460;
    const double bearing = beam * 0.5 * kPi / 180.0;
    open.col (k) << range (beam) * std::cos (bearing), range (beam) * std::sin (bearing);
  }
  const std::vector<int> order = pcl_crf::beamOrder (open);
  EXPECT_EQ (order.front (), 650);  // beam 460: 470 + 650 − 720 + 60 left out
}

TEST (BeamOrder, AClockwiseScanIsReadBackwards)
{
  // Mounted upside down, or listed the other way by a converter: the chains read it
  // counter-clockwise, as the models learned; with a little jitter as well.
  std::vector<double> degrees = beams (90.0, 361, -0.5);
  const Eigen::Matrix2Xd scan = atBearings (degrees);
  EXPECT_EQ (pcl_crf::bearingBacktrack (scan), 0.0);
  EXPECT_FALSE (pcl_crf::inBeamOrder (scan));
  std::vector<int> backwards = identity (degrees.size ());
  std::reverse (backwards.begin (), backwards.end ());
  EXPECT_EQ (pcl_crf::beamOrder (scan), backwards);
  for (std::size_t k = 10; k + 1 < degrees.size (); k += 40)
    std::swap (degrees[k], degrees[k + 1]);
  const Eigen::Matrix2Xd jittered = atBearings (degrees);
  EXPECT_GT (pcl_crf::bearingBacktrack (jittered), 0.0);
  EXPECT_FALSE (pcl_crf::inBeamOrder (jittered));
  EXPECT_EQ (pcl_crf::beamOrder (jittered), backwards);
  // Fewer than two bearings turn no way: left as they are.
  EXPECT_EQ (pcl_crf::beamOrder (atBearings ({20.0})), identity (1));
  EXPECT_EQ (pcl_crf::beamOrder (Eigen::Matrix2Xd::Zero (2, 3)), identity (3));
}

TEST (BeamOrder, AShuffledScanIsSortedBackIntoItsBeams)
{
  std::mt19937 rng (44);
  for (const std::vector<double>& degrees : {beams (-90.0, 361, 0.5), beams (60.0, 300, 0.5)}) {
    const Eigen::Matrix2Xd scan = atBearings (degrees);
    std::vector<int> shuffle = identity (degrees.size ());
    std::shuffle (shuffle.begin (), shuffle.end (), rng);
    const Eigen::Matrix2Xd shuffled = reordered (scan, shuffle);
    EXPECT_GT (pcl_crf::bearingBacktrack (shuffled), 0.9);
    EXPECT_FALSE (pcl_crf::inBeamOrder (shuffled));
    // Sorted counter-clockwise from the first beam after the back (the widest gap; the
    // second scan's 150° of beams cross ±180°): the laser's own order again.
    EXPECT_EQ (reordered (shuffled, pcl_crf::beamOrder (shuffled)), scan);
  }
}

TEST (BeamOrder, AScanSortedByXIsSortedByBearing)
{
  // As a voxel grid leaves a scan: by x in 0.5 m columns, by y within each.
  const Eigen::Matrix2Xd scan = atBearings (beams (-90.0, 361, 0.5));
  std::vector<int> by_x = identity (static_cast<std::size_t> (scan.cols ()));
  std::sort (by_x.begin (), by_x.end (), [&scan] (int a, int b) {
    const double column_a = std::floor (scan (0, a) / 0.5), column_b = std::floor (scan (0, b) / 0.5);
    return column_a < column_b || (column_a == column_b && scan (1, a) < scan (1, b));
  });
  const Eigen::Matrix2Xd sorted = reordered (scan, by_x);
  EXPECT_FALSE (pcl_crf::inBeamOrder (sorted));
  EXPECT_EQ (reordered (sorted, pcl_crf::beamOrder (sorted)), scan);
}

TEST (BeamOrder, ALittleJitterKeepsTheLasersOrderAndASortPutsTheOriginFirst)
{
  // Neighbours swapped here and there (bearings jittering across each other), up to a
  // tenth of the way back: still the laser's order, left as it is.
  std::vector<double> degrees = beams (-90.0, 361, 0.5);
  for (std::size_t k = 10; k + 1 < degrees.size (); k += 40)
    std::swap (degrees[k], degrees[k + 1]);
  const Eigen::Matrix2Xd jittered = atBearings (degrees);
  EXPECT_GT (pcl_crf::bearingBacktrack (jittered), 0.0);
  EXPECT_LT (pcl_crf::bearingBacktrack (jittered), 0.1);
  EXPECT_EQ (pcl_crf::beamOrder (jittered), identity (degrees.size ()));
  // Points at the origin come first when a scan is sorted.
  Eigen::Matrix2Xd mixed = atBearings ({30.0, -20.0, 25.0, -20.0, 10.0, 0.0});
  mixed.col (5).setZero ();
  ASSERT_FALSE (pcl_crf::inBeamOrder (mixed));  // 75° forward, 95° back
  EXPECT_EQ (pcl_crf::beamOrder (mixed), (std::vector<int>{5, 1, 3, 4, 2, 0}));
  // Equal bearings (point 3 a copy of point 1) in index order, decreasing when the scan
  // goes mostly clockwise, as this one: listed the other way round, it is read in the
  // same order of its points.
  mixed.col (3) = mixed.col (1);
  EXPECT_EQ (pcl_crf::beamOrder (mixed), (std::vector<int>{5, 3, 1, 4, 2, 0}));
  std::vector<int> backwards = identity (6);
  std::reverse (backwards.begin (), backwards.end ());
  const Eigen::Matrix2Xd reversed = reordered (mixed, backwards);
  EXPECT_EQ (pcl_crf::beamOrder (reversed), (std::vector<int>{0, 2, 4, 1, 3, 5}));  // points 5, 3, 1, 4, 2, 0
}
