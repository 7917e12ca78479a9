// Building blocks of CRF-Clustering: segmentation, label completion, N_eff merging
// (Eq. (8)), ego-cluster selection, motion fits and the model file.

#include <pcl_crf/clustering/cluster_fits.h>
#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/clustering_model.h>
#include <pcl_crf/clustering/ego_cluster.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/clustering/scan_segmentation.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace {

using namespace pcl_crf;
using namespace pcl_crf::clustering;

Eigen::Matrix2Xd
pointsOnX (const std::vector<double>& xs)
{
  Eigen::Matrix2Xd points (2, static_cast<Eigen::Index> (xs.size ()));
  for (std::size_t i = 0; i < xs.size (); ++i)
    points.col (i) << xs[i], 1.0;
  return points;
}

TEST (ClusteringSegmentation, BreaksAtGapsAndCapsSegmentLength)
{
  const Eigen::Matrix2Xd points = pointsOnX ({0.0, 0.1, 0.2, 1.0, 1.1, 1.2, 1.3, 1.4});
  EXPECT_EQ (segmentByDistance (points, 0.5), (std::vector<int>{0, 0, 0, 1, 1, 1, 1, 1}));
  EXPECT_EQ (segmentByDistance (points, 0.5, 2), (std::vector<int>{0, 0, 1, 2, 2, 3, 3, 4}));
  EXPECT_EQ (segmentByDistance (points, 0.05), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_THROW (segmentByDistance (points, 0.0), std::invalid_argument);
}

TEST (ClusteringSegmentation, MergesTheNarrowestBreaksBeyondTheMostSegments)
{
  // Breaks of 0.9 m (before point 2), 1.9 m (point 4) and 0.45 m (point 6).
  const Eigen::Matrix2Xd points = pointsOnX ({0.0, 0.1, 1.0, 1.1, 3.0, 3.05, 3.5});
  const std::vector<int> segments = segmentByDistance (points, 0.3);
  ASSERT_EQ (segments, (std::vector<int>{0, 0, 1, 1, 2, 2, 3}));
  std::vector<int> segment = segments;
  mergeNarrowestBreaks (points, 3, segment);
  EXPECT_EQ (segment, (std::vector<int>{0, 0, 1, 1, 2, 2, 2}));
  mergeNarrowestBreaks (points, 2, segment);
  EXPECT_EQ (segment, (std::vector<int>{0, 0, 0, 0, 1, 1, 1}));
  mergeNarrowestBreaks (points, 1, segment);
  EXPECT_EQ (segment, std::vector<int> (7, 0));
  segment = segments;
  mergeNarrowestBreaks (points, 4, segment);
  EXPECT_EQ (segment, segments);
  // Equal breaks: the first ones in scan order stay.
  const Eigen::Matrix2Xd even = pointsOnX ({0.0, 1.0, 2.0, 3.0});
  segment = segmentByDistance (even, 0.5);
  mergeNarrowestBreaks (even, 2, segment);
  EXPECT_EQ (segment, (std::vector<int>{0, 1, 1, 1}));

  segment = segments;
  EXPECT_THROW (mergeNarrowestBreaks (points, 0, segment), std::invalid_argument);
  std::vector<int> short_list{0, 0};
  EXPECT_THROW (mergeNarrowestBreaks (points, 3, short_list), std::invalid_argument);
  for (std::vector<int> bad : {std::vector<int>{1, 1, 1, 1}, std::vector<int>{0, 2, 2, 2}, std::vector<int>{0, 1, 0, 1}})
    EXPECT_THROW (mergeNarrowestBreaks (even, 3, bad), std::invalid_argument);
}

TEST (ClusteringSegmentation, CompletesLabelsFromTheNearestLabelledPointOfTheSegment)
{
  // Two segments; the second holds no labelled point and gets the default label 7.
  const Eigen::Matrix2Xd scan = pointsOnX ({0.0, 0.1, 0.25, 0.3, 0.4, 3.0, 3.1});
  const std::vector<int> labels = completeLabels (scan, {1, 3}, {4, 5}, 0.5, 7);
  EXPECT_EQ (labels, (std::vector<int>{4, 4, 5, 5, 5, 7, 7}));
  EXPECT_THROW (completeLabels (scan, {3, 1}, {4, 5}, 0.5, 7), std::invalid_argument);
  EXPECT_THROW (completeLabels (scan, {1}, {4, 5}, 0.5, 7), std::invalid_argument);
}

TEST (ClusteringSegmentation, CompletesLabelsWithinGivenSegments)
{
  // Segments {0–4} and {5, 6}; −1 marks the points to complete. The second segment has
  // no labelled point and keeps −1; a tie (point 2, 0.15 m from both) takes the one before.
  const Eigen::Matrix2Xd scan = pointsOnX ({0.0, 0.1, 0.25, 0.4, 0.5, 3.0, 3.1});
  const std::vector<int> segment{0, 0, 0, 0, 0, 1, 1};
  EXPECT_EQ (completeLabelsWithinSegments (scan, segment, {-1, 4, -1, 5, -1, -1, -1}, -1),
             (std::vector<int>{4, 4, 4, 5, 5, -1, -1}));
  EXPECT_THROW (completeLabelsWithinSegments (scan, {0, 0}, std::vector<int> (7, -1), -1), std::invalid_argument);
  EXPECT_THROW (completeLabelsWithinSegments (scan, segment, {4, 5}, -1), std::invalid_argument);
}

TEST (ClusteringMerge, EffectiveClusterCountFollowsEq8)
{
  EXPECT_DOUBLE_EQ (effectiveClusterCount (Eigen::Vector3d (1.0, 0.0, 0.0)), 1.0);
  EXPECT_DOUBLE_EQ (effectiveClusterCount (Eigen::Vector2d (0.5, 0.5)), 2.0);
  EXPECT_NEAR (effectiveClusterCount (Eigen::Vector3d (0.6, 0.2, 0.2)), 1.0 / 0.44, 1e-12);
  EXPECT_DOUBLE_EQ (effectiveClusterCount (Eigen::Vector2d (2.0, 2.0)), 2.0);  // normalised
  EXPECT_DOUBLE_EQ (effectiveClusterCount (Eigen::Vector2d::Zero ()), 0.0);
}

TEST (ClusteringMerge, OverSegmentedStaticWorldMergesIntoOneCluster)
{
  // 30 points of one world split into three clusters that explain every point
  // equally well (p = 1/3 each, N_eff = 3), plus a car (cluster 3) sure of itself.
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero (4, 36);
  p.topLeftCorner (3, 30).setConstant (1.0 / 3.0);
  p.block (3, 30, 1, 6).setOnes ();
  std::vector<int> labels (36, 3);
  for (int i = 0; i < 30; ++i)
    labels[i] = i / 10;
  const std::vector<int> kept = mergeAmbiguousClusters (p, labels, 1.7);
  // After removing two copies the last one is certain (N_eff 1) and stays.
  EXPECT_EQ (kept, (std::vector<int>{2, 3}));
  ASSERT_EQ (p.rows (), 2);
  for (int i = 0; i < 30; ++i)
  {
    EXPECT_EQ (labels[i], 0);
    EXPECT_NEAR (p (0, i), 1.0, 1e-12);
  }
  for (int i = 30; i < 36; ++i)
    EXPECT_EQ (labels[i], 1);
}

TEST (ClusteringMerge, DistinctClustersAndEmptyOnesAreHandled)
{
  // Points lean 0.9 / 0.1 towards their own cluster: N_eff = 1.22 < 1.7, all stay;
  // cluster 2 has no point and vanishes.
  Eigen::MatrixXd p (3, 4);
  p << 0.9, 0.9, 0.1, 0.1,  //
      0.1, 0.1, 0.9, 0.9,   //
      0.0, 0.0, 0.0, 0.0;
  std::vector<int> labels = {0, 0, 1, 1};
  EXPECT_EQ (mergeAmbiguousClusters (p, labels, 1.7), (std::vector<int>{0, 1}));
  EXPECT_EQ (labels, (std::vector<int>{0, 0, 1, 1}));
  std::vector<int> bad = {0, 5, 1, 1};
  EXPECT_THROW (mergeAmbiguousClusters (p, bad, 1.7), std::invalid_argument);
}

/** selectClusters () as Eq. (8) states it, recomputed from scratch at every step: the
 *  active cluster whose points have the highest average N_eff (first on ties) goes while
 *  that average exceeds the bound, its points to their most probable active cluster. */
std::vector<int>
selectClustersFromScratch (const Eigen::MatrixXd& p, std::vector<int>& labels, double max_average_neff)
{
  std::vector<bool> active (static_cast<std::size_t> (p.rows ()), true);
  const auto neff = [&] (Eigen::Index i) {
    double total = 0.0, squares = 0.0;
    for (Eigen::Index l = 0; l < p.rows (); ++l)
      if (active[l])
        total += p (l, i), squares += p (l, i) * p (l, i);
    return squares > 0.0 ? total * total / squares : 0.0;
  };
  for (;;) {
    if (std::count (active.begin (), active.end (), true) <= 1)
      break;
    Eigen::VectorXd sum = Eigen::VectorXd::Zero (p.rows ()), count = Eigen::VectorXd::Zero (p.rows ());
    for (std::size_t i = 0; i < labels.size (); ++i)
      sum (labels[i]) += neff (static_cast<Eigen::Index> (i)), count (labels[i]) += 1.0;
    int worst = -1;
    double highest = -1.0;
    for (Eigen::Index l = 0; l < p.rows (); ++l)
      if (active[l] && count (l) > 0.0 && sum (l) / count (l) > highest)
        worst = static_cast<int> (l), highest = sum (l) / count (l);
    if (worst < 0 || highest <= max_average_neff)
      break;
    active[worst] = false;
    for (std::size_t i = 0; i < labels.size (); ++i)
      if (labels[i] == worst) {
        int best = -1;
        for (Eigen::Index l = 0; l < p.rows (); ++l)
          if (active[l] && (best < 0 || p (l, i) > p (best, i)))
            best = static_cast<int> (l);
        labels[i] = best;
      }
  }
  std::vector<int> kept;
  for (Eigen::Index l = 0; l < p.rows (); ++l)
    if (active[l] && std::find (labels.begin (), labels.end (), static_cast<int> (l)) != labels.end ())
      kept.push_back (static_cast<int> (l));
  return kept;
}

TEST (ClusteringMerge, PointsMovedFromClusterToClusterEndWhereEq8Puts)
{
  // 60 clusters over 300 points, 100 of them copies of one point: removing cluster after
  // cluster moves the copies dozens of times (they rank their clusters after four moves).
  std::mt19937 rng (43);
  std::uniform_real_distribution<double> uniform (0.0, 1.0);
  Eigen::MatrixXd p (60, 300);
  for (Eigen::Index i = 0; i < p.cols (); ++i)
    for (Eigen::Index l = 0; l < p.rows (); ++l)
      p (l, i) = std::pow (uniform (rng), 4.0);
  p.rightCols (100).colwise () = p.col (0);
  for (Eigen::Index i = 0; i < p.cols (); ++i)
    p.col (i) /= p.col (i).sum ();
  std::vector<int> labels (300);
  for (std::size_t i = 0; i < labels.size (); ++i)
    labels[i] = static_cast<int> (i % 60);
  for (const double bound : {1.2, 2.0, 6.0}) {
    std::vector<int> fast = labels, reference = labels;
    const std::vector<int> kept = pcl_crf::clustering::selectClusters (p, fast, bound);
    EXPECT_EQ (kept, selectClustersFromScratch (p, reference, bound)) << bound;
    EXPECT_EQ (fast, reference) << bound;
    EXPECT_LT (kept.size (), 60u) << bound;
  }
}

TEST (ClusteringEgo, StaticClusterIsTheMahalanobisNearestToOdometry)
{
  // Odometry: 3 m forward, x well known (σ 0.01 m), y poorly (σ 1 m).
  Odometry odometry;
  odometry.T_source_target = makeRigid2d (3.0, 0.0, 0.0);
  odometry.covariance = Eigen::Vector3d (1e-4, 1.0, 1e-4).asDiagonal ();
  // Cluster A's sensor motion is 0.2 m off in x, B's 0.5 m off in y: A is nearer in
  // Euclidean distance, B in Mahalanobis distance (0.2² / 1e-4 = 400 against 0.5² / 1 = 0.25).
  const Rigid2d a = makeRigid2d (3.2, 0.0, 0.0).inverse ();
  const Rigid2d b = makeRigid2d (3.0, 0.5, 0.0).inverse ();
  EXPECT_NEAR (odometryMahalanobis (a, odometry), 400.0, 1e-6);
  EXPECT_NEAR (odometryMahalanobis (b, odometry), 0.25, 1e-9);
  EXPECT_EQ (selectStaticCluster ({a, b}, odometry), 1);
  EXPECT_EQ (selectStaticCluster ({}, odometry), -1);
  // The angle difference is wrapped: +π − ε and −π + ε are 2ε apart.
  odometry.T_source_target = makeRigid2d (0.0, 0.0, M_PI - 0.01);
  EXPECT_NEAR (odometryMahalanobis (makeRigid2d (0.0, 0.0, -M_PI + 0.01).inverse (), odometry), 0.02 * 0.02 / 1e-4,
               1e-6);
}

TEST (ClusteringEgo, ClusterSizesArePriorOfTheStaticWorld)
{
  // A loose odometry ("not moving", σ 1 m, 0.5 rad), as a recording without odometry
  // has: the world split into a large cluster 0.05 m off (d² = 0.0025) and a small one
  // 0.01 m off (d² = 1e-4). ½ d² − log n: 0.00125 − log 200 = −5.297 against
  // 0.00005 − log 20 = −2.996, so the large one; without sizes, the nearer one.
  Odometry odometry;
  odometry.covariance = Eigen::Vector3d (1.0, 1.0, 0.25).asDiagonal ();
  const Rigid2d large = makeRigid2d (0.05, 0.0, 0.0).inverse (), small = makeRigid2d (0.01, 0.0, 0.0).inverse ();
  EXPECT_EQ (selectStaticCluster ({small, large}, odometry), 0);
  EXPECT_EQ (selectStaticCluster ({small, large}, odometry, {20, 200}), 1);
  // A tight odometry (σ 0.01 m): 0.05 m off is d² = 25, ½ d² = 12.5 outweighs
  // log(200 / 20) = 2.3, so the odometry decides.
  odometry.covariance = Eigen::Vector3d (1e-4, 1e-4, 1e-4).asDiagonal ();
  EXPECT_EQ (selectStaticCluster ({small, large}, odometry, {20, 200}), 0);
  // An empty cluster is never the world while another has points; all empty: no prior.
  EXPECT_EQ (selectStaticCluster ({small, large}, odometry, {0, 5}), 1);
  EXPECT_EQ (selectStaticCluster ({small, large}, odometry, {0, 0}), 0);
  EXPECT_THROW (selectStaticCluster ({small, large}, odometry, {3}), std::invalid_argument);
  odometry.T_source_target.translation ().x () = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (selectStaticCluster ({small, large}, odometry, {20, 200}), std::invalid_argument);
}

TEST (ClusteringFits, HardAndSoftFitsRecoverKnownMotions)
{
  const Rigid2d car = makeRigid2d (1.5, -0.3, 0.2), world = makeRigid2d (-3.0, 0.1, -0.05);
  Eigen::Matrix2Xd source (2, 8), target (2, 8);
  std::vector<int> match (8), labels (8);
  for (int i = 0; i < 8; ++i)
  {
    source.col (i) << 0.7 * i, std::sin (i);
    labels[i] = i < 4 ? 0 : 1;
    target.col (i) = (labels[i] == 0 ? world : car) * Eigen::Vector2d (source.col (i));
    match[i] = i;
  }
  const PointPairs pairs = makePointPairs (source, target, match);
  const std::vector<Rigid2d> hard = fitMotions (pairs, labels, 2);
  const std::vector<Rigid2d> soft = solveFits (accumulateFits (pairs, oneHot (labels, 2)));
  for (const auto& motions : {hard, soft})
  {
    EXPECT_LT ((motions[0].inverse () * world).translation ().norm (), 1e-9);
    EXPECT_LT (std::abs (rotationAngle (motions[1].inverse () * car)), 1e-9);
  }
  EXPECT_LT (squaredResiduals (pairs, hard).row (0).head (4).maxCoeff (), 1e-18);
  match[2] = 9;
  EXPECT_THROW (makePointPairs (source, target, match), std::invalid_argument);
}

TEST (ClusteringFits, OwnPointWeightsKeepEachPairsMarginalForItsMapClusterOnly)
{
  Eigen::MatrixXd marginals (3, 4);
  marginals << 0.7, 0.1, 0.2, 0.0,  //
      0.2, 0.8, 0.3, 0.5,           //
      0.1, 0.1, 0.5, 0.5;
  Eigen::MatrixXd expected (3, 4);
  expected << 0.7, 0.0, 0.0, 0.0,  //
      0.0, 0.8, 0.0, 0.0,          //
      0.0, 0.0, 0.5, 0.0;          // pair 3's label (-1, an outlier) holds no cluster
  EXPECT_EQ (ownPointWeights (marginals, {0, 1, 2, -1}).cwiseNotEqual (expected).count (), 0);
  EXPECT_THROW (ownPointWeights (marginals, {0, 1, 2}), std::invalid_argument);
}

TEST (ClusteringModel, RoundTripsAndRejectsBrokenFiles)
{
  CrfClusteringModel model;
  model.weights << 0.03125, -3.25, 0.0625, 4.5, -0.7 + 1e-13;
  model.features.min_neighbour_distance = 0.02;
  std::stringstream text;
  writeModel (text, model);
  const CrfClusteringModel read = readModel (text, "memory");
  EXPECT_EQ (read.weights, model.weights);
  EXPECT_EQ (read.features.min_neighbour_distance, 0.02);

  const std::string good = text.str ();
  auto reads = [] (const std::string& content) {
    std::istringstream in (content);
    return readModel (in, "broken.model");
  };
  auto replaced = [&good] (const std::string& from, const std::string& to) {
    std::string copy = good;
    copy.replace (copy.find (from), from.size (), to);
    return copy;
  };
  EXPECT_THROW (reads (replaced ("model 1", "model 2")), std::runtime_error);              // version
  EXPECT_THROW (reads (replaced ("stiffness", "# stiffness")), std::runtime_error);        // missing field
  EXPECT_THROW (reads (replaced ("beam_residual -3.25", "beam_residual nan")), std::runtime_error);  // NaN
  EXPECT_THROW (reads (replaced ("beam_residual -3.25", "beam_residual -3 4")), std::runtime_error); // extra value
  EXPECT_THROW (reads (good + "stiffness 1\n"), std::runtime_error);                        // repeated
  EXPECT_THROW (reads (good + "colour 1\n"), std::runtime_error);                           // unknown
  EXPECT_THROW (reads (""), std::runtime_error);
  try
  {
    reads (replaced ("model 1", "model 2"));
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE (std::string (error.what ()).find ("version 2"), std::string::npos);
  }
  EXPECT_THROW (loadModel ("/nonexistent/crf-t.model"), std::runtime_error);
}

TEST (ClusteringModel, VersionIsOneExactIntegerToken)
{
  // "1abc", "1.9" and "1e9" used to read as version 1; trailing words were ignored.
  CrfClusteringModel model;
  std::stringstream text;
  writeModel (text, model);
  const std::string good = text.str ();
  const std::string header = good.substr (0, good.find ('\n'));
  ASSERT_EQ (header.substr (header.size () - 2), " 1");
  const std::string magic = header.substr (0, header.size () - 2);
  const std::pair<std::string, std::string> cases[] = {
      {" 1abc", "model version 1abc is not supported"}, {" 1.9", "model version 1.9 is not supported"},
      {" 1e9", "model version 1e9 is not supported"},   {"", "missing model version"},
      {" 1 junk", "unexpected text 'junk' after the model version"}};
  for (const auto& [version, message] : cases) {
    std::istringstream in (magic + version + good.substr (header.size ()));
    try {
      readModel (in, "broken.model");
      ADD_FAILURE () << "accepted version '" << version << "'";
    }
    catch (const std::runtime_error& error) {
      EXPECT_NE (std::string (error.what ()).find (message), std::string::npos) << error.what ();
    }
  }
}

}  // namespace
