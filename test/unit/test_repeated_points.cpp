#include <pcl_crf/core/repeated_points.h>
#include <pcl_crf/core/prediction.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/scan_matching.h>


#include <gtest/gtest.h>

#include "hokuyo_pairs.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace pcl_crf;

const joint::JointModel&
jointModel ()
{
  static const joint::JointModel model =
      joint::loadJointModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/joint.model");
  return model;
}

/** \a scan with copies of its columns \a copied appended, in that order. */
Eigen::Matrix2Xd
withCopies (const Eigen::Matrix2Xd& scan, const std::vector<int>& copied)
{
  Eigen::Matrix2Xd out (2, scan.cols () + static_cast<Eigen::Index> (copied.size ()));
  out.leftCols (scan.cols ()) = scan;
  for (std::size_t k = 0; k < copied.size (); ++k)
    out.col (scan.cols () + static_cast<Eigen::Index> (k)) = scan.col (copied[k]);
  return out;
}

const matching::CrfMatchingModel&
matchingModel ()
{
  static const matching::CrfMatchingModel model =
      matching::loadModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-matching.model");
  return model;
}

/** \a scan with a copy of every \a every -th point inserted right after it (a driver
 *  that repeats a return); \a position receives each point's column in the result. */
Eigen::Matrix2Xd
withRepeatedReturns (const Eigen::Matrix2Xd& scan, int every, std::vector<int>& position)
{
  std::vector<Eigen::Vector2d> points;
  position.clear ();
  for (Eigen::Index i = 0; i < scan.cols (); ++i) {
    position.push_back (static_cast<int> (points.size ()));
    points.push_back (scan.col (i));
    if (i % every == every - 1)
      points.push_back (scan.col (i));
  }
  Eigen::Matrix2Xd out (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    out.col (static_cast<Eigen::Index> (k)) = points[k];
  return out;
}

/** CRF-Matching of \a pair with a copy of every \a every_source -th source and every
 *  \a every_target -th target point inserted after it equals CRF-Matching of the pair,
 *  every copy taking its first copy's result and every match and state naming a first
 *  copy. */
void
expectCopiesMatchedAsTheirFirstCopy (const ScanPair& pair, int every_source, int every_target)
{
  std::vector<int> in_source, in_target;
  const Eigen::Matrix2Xd source = withRepeatedReturns (pair.source, every_source, in_source);
  const Eigen::Matrix2Xd target = withRepeatedReturns (pair.target, every_target, in_target);
  const matching::MotionGuess guess = matching::MotionGuess::fromOdometry (pair.odometry);
  const matching::MatchResult plain = matching::matchScans (pair.source, pair.target, guess, matchingModel ());
  const matching::MatchResult r = matching::matchScans (source, target, guess, matchingModel ());
  ASSERT_EQ (r.matches.size (), static_cast<std::size_t> (source.cols ()));
  ASSERT_EQ (r.candidates.size (), source.cols ());
  ASSERT_EQ (r.marginals.size (), static_cast<std::size_t> (source.cols ()));
  EXPECT_TRUE (r.T_target_source.isApprox (plain.T_target_source, 0.0));
  EXPECT_EQ (r.inlier_count, plain.inlier_count + static_cast<int> (std::count_if (
                                 in_source.begin (), in_source.end (), [&] (int k) {
                                   return k + 1 < source.cols () && source.col (k + 1) == source.col (k) &&
                                          r.matches[static_cast<std::size_t> (k)] != kNoMatch;
                                 })));
  const auto inTarget = [&] (int j) { return j == kNoMatch ? kNoMatch : in_target[static_cast<std::size_t> (j)]; };
  for (std::size_t i = 0; i < in_source.size (); ++i) {
    const auto k = static_cast<std::size_t> (in_source[i]);
    EXPECT_EQ (r.matches[k], inTarget (plain.matches[i])) << i;
    ASSERT_EQ (r.candidates.count (static_cast<int> (k)), plain.candidates.count (static_cast<int> (i))) << i;
    for (int c = 0; c < plain.candidates.count (static_cast<int> (i)); ++c)
      EXPECT_EQ (r.candidates.target (static_cast<int> (k), c), inTarget (plain.candidates.target (static_cast<int> (i), c)));
    EXPECT_TRUE (r.marginals[k].isApprox (plain.marginals[i], 0.0)) << i;
    if (k + 1 < static_cast<std::size_t> (source.cols ()) && source.col (k + 1) == source.col (k)) {  // its copy
      EXPECT_EQ (r.matches[k + 1], r.matches[k]);
      EXPECT_EQ (r.map_probability (k + 1), r.map_probability (k));
    }
  }
}

/** The motion of point i's cluster in \a r, or the identity for an outlier. */
Rigid2d
motionOf (const joint::JointResult& r, std::size_t i)
{
  const int l = r.source_cluster[i];
  return l == kOutlierCluster ? Rigid2d::Identity () : r.cluster_motions[static_cast<std::size_t> (l)];
}

}  // namespace

TEST (RepeatedPoints, EachPointNamesItsFirstCopy)
{
  Eigen::Matrix2Xd points (2, 6);
  points << 1.0, 0.0, 1.0, -0.0, 2.0, 1.0,  //
      1.0, 0.0, 1.0, 0.0, 2.0, 1.5;
  const std::vector<int> first = firstOfEqualPoints (points);
  EXPECT_EQ (first, (std::vector<int>{0, 1, 0, 1, 4, 5}));  // −0 is 0; (1, 1.5) is not (1, 1)
  EXPECT_TRUE (repeatsAPoint (first));
  EXPECT_EQ (firstCopies (first), (std::vector<int>{0, 1, 4, 5}));
  EXPECT_FALSE (repeatsAPoint (firstOfEqualPoints (Eigen::Matrix2Xd::Identity (2, 2))));
  EXPECT_TRUE (firstOfEqualPoints (Eigen::Matrix2Xd (2, 0)).empty ());
}

TEST (JointEstimation, RepeatedPointsTakeTheResultOfTheirFirstCopy)
{
  // Test pair 16 (a car 3.8 m against the world) with source points 5, 100 and 200 and
  // target points 0 and 50 repeated at the ends of the scans: the estimate on the first
  // copies is the pair's own, and every copy takes its first copy's match and cluster.
  const ScanPair pair = loadScanPair (std::string (PCL_CRF_SOURCE_DIR) + "/data/default/test/pair_0016");
  const std::vector<int> source_copied{5, 100, 200};
  const Eigen::Matrix2Xd source = withCopies (pair.source, source_copied);
  const Eigen::Matrix2Xd target = withCopies (pair.target, {0, 50});
  const joint::JointResult plain = joint::estimateJoint (pair.source, pair.target, pair.odometry, jointModel ());
  const joint::JointResult r = joint::estimateJoint (source, target, pair.odometry, jointModel ());
  ASSERT_EQ (r.source_match.size (), static_cast<std::size_t> (source.cols ()));
  ASSERT_GE (plain.cluster_motions.size (), 2u);
  EXPECT_TRUE (r.T_source_target.isApprox (plain.T_source_target, 0.0));
  EXPECT_EQ (r.cluster_motions.size (), plain.cluster_motions.size ());
  const auto n = static_cast<std::size_t> (pair.source.cols ());
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ (r.source_match[i], plain.source_match[i]) << i;
    EXPECT_EQ (r.source_cluster[i] == kOutlierCluster, plain.source_cluster[i] == kOutlierCluster) << i;
    EXPECT_TRUE (motionOf (r, i).isApprox (motionOf (plain, i), 0.0)) << i;
  }
  for (std::size_t k = 0; k < source_copied.size (); ++k) {
    const auto copy = n + k, first = static_cast<std::size_t> (source_copied[k]);
    EXPECT_EQ (r.source_match[copy], r.source_match[first]);
    EXPECT_EQ (r.source_cluster[copy], r.source_cluster[first]);
  }
  int sizes = static_cast<int> (r.outliers.size ());
  for (const int size : r.cluster_sizes)
    sizes += size;
  EXPECT_EQ (sizes, source.cols ());
}

TEST (JointEstimation, CopiesOfOnePointAreEstimatedAsOnePoint)
{
  // 100 000 copies of one point in each scan took 8.5 s (hundreds of clusters of one
  // point); they are one point and all take its answer.
  constexpr Eigen::Index kCopies = 100000;
  const Eigen::Matrix2Xd source = Eigen::Vector2d (3.0, 1.0).replicate (1, kCopies);
  const Eigen::Matrix2Xd target = Eigen::Vector2d (3.1, 1.0).replicate (1, kCopies);
  const joint::JointResult r = joint::estimateJoint (source, target, Odometry{}, jointModel ());
  ASSERT_EQ (r.source_cluster.size (), static_cast<std::size_t> (kCopies));
  for (Eigen::Index i = 1; i < kCopies; ++i) {
    ASSERT_EQ (r.source_cluster[i], r.source_cluster[0]) << i;
    ASSERT_EQ (r.source_match[i], r.source_match[0]) << i;
  }
  EXPECT_TRUE (r.source_match[0] == kNoMatch || r.source_match[0] == 0);  // the first copy of the target point
}

TEST (CRFMatching, RepeatedPointsTakeTheResultOfTheirFirstCopy)
{
  // Copies of returns inserted in both scans left 16–24 % of CRF-Matching's matches
  // changed on the test split (copies of (0, 0) between the returns): they were nodes
  // of the chain and states of their own. Test pair 16 (a car 3.8 m against the world).
  expectCopiesMatchedAsTheirFirstCopy (
      loadScanPair (std::string (PCL_CRF_SOURCE_DIR) + "/data/default/test/pair_0016"), 7, 5);
}

TEST (CRFMatching, RepeatedPointsOfThinnedScansTakeTheResultOfTheirFirstCopy)
{
  // A 1081-beam pair over 270°: thinned to the model's 0.5°, matched, and lifted back
  // onto the first copies. Every target point repeated: a copy of a kept point lies in
  // the span of the next kept point, where lifting onto the full target could pick it
  // and name the point it repeats (7 of 1081 matches on pair (3, 1) changed so).
  for (const auto& [seed, index] : {std::pair<int, int>{5, 0}, {3, 1}}) {
    SCOPED_TRACE (seed);
    const ScanPair pair = test::hokuyoPair (static_cast<std::uint64_t> (seed), static_cast<std::size_t> (index));
    ASSERT_LT (thinToSpacing (pair.source, matchingModel ().parameters.training_beam_spacing).kept.size (),
               static_cast<std::size_t> (pair.source.cols ()));  // it is thinned
    expectCopiesMatchedAsTheirFirstCopy (pair, 7, 1);
  }
}

TEST (CRFMatching, CopiesOfOnePointAreMatchedAsOnePoint)
{
  // 100 000 copies of one point in each scan took 1.4 s, each a node of the chain.
  constexpr Eigen::Index kCopies = 100000;
  const Eigen::Matrix2Xd source = Eigen::Vector2d (3.0, 1.0).replicate (1, kCopies);
  const Eigen::Matrix2Xd target = Eigen::Vector2d (3.1, 1.0).replicate (1, kCopies);
  const matching::MatchResult r = matching::matchScans (source, target, matching::MotionGuess{}, matchingModel ());
  ASSERT_EQ (r.matches.size (), static_cast<std::size_t> (kCopies));
  for (Eigen::Index i = 0; i < kCopies; ++i) {
    ASSERT_EQ (r.matches[i], r.matches[0]) << i;
    ASSERT_LE (r.candidates.count (static_cast<int> (i)), 1) << i;  // the first copy of the target point at most
  }
  EXPECT_TRUE (r.matches[0] == kNoMatch || r.matches[0] == 0);
}
