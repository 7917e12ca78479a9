#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/rigid_fit.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

namespace {

Eigen::Matrix2Xd
randomPoints (int n, unsigned seed)
{
  std::mt19937 rng (seed);
  std::uniform_real_distribution<double> uniform (-10.0, 10.0);
  Eigen::Matrix2Xd points (2, n);
  for (int i = 0; i < n; ++i)
    points.col (i) << uniform (rng), uniform (rng);
  return points;
}

TEST (RigidFit, RecoversKnownMotionExactly)
{
  const Eigen::Matrix2Xd source = randomPoints (50, 1);
  const pcl_crf::Rigid2d truth = pcl_crf::makeRigid2d (1.5, -0.7, 2.8);
  const pcl_crf::Rigid2d fitted = pcl_crf::fitRigid2d (source, truth * source);
  EXPECT_NEAR (pcl_crf::rotationAngle (fitted), 2.8, 1e-12);
  EXPECT_NEAR ((fitted.translation () - truth.translation ()).norm (), 0.0, 1e-10);
}

TEST (RigidFit, ZeroWeightsIgnoreCorruptedPairs)
{
  Eigen::Matrix2Xd source = randomPoints (20, 2);
  const pcl_crf::Rigid2d truth = pcl_crf::makeRigid2d (-0.3, 0.2, 0.1);
  Eigen::Matrix2Xd target = truth * source;
  Eigen::VectorXd weights = Eigen::VectorXd::Ones (20);
  target.col (3) += Eigen::Vector2d (5.0, 5.0);
  weights (3) = 0.0;
  const pcl_crf::Rigid2d fitted = pcl_crf::fitRigid2d (source, target, weights);
  EXPECT_NEAR (pcl_crf::rotationAngle (fitted), 0.1, 1e-12);
  EXPECT_NEAR ((fitted.translation () - truth.translation ()).norm (), 0.0, 1e-10);
}

TEST (RigidFit, AccumulatorRemoveUndoesAddAndResidualMatchesDirectSum)
{
  const Eigen::Matrix2Xd source = randomPoints (30, 3);
  const pcl_crf::Rigid2d truth = pcl_crf::makeRigid2d (0.5, 0.5, -0.4);
  const Eigen::Matrix2Xd target = truth * source;
  pcl_crf::RigidFitAccumulator accumulator;
  for (int i = 0; i < 30; ++i)
    accumulator.add (source.col (i), target.col (i), 0.5 + 0.01 * i);
  accumulator.add (Eigen::Vector2d (1, 1), Eigen::Vector2d (9, -9), 2.0);
  accumulator.remove (Eigen::Vector2d (1, 1), Eigen::Vector2d (9, -9), 2.0);
  EXPECT_NEAR (pcl_crf::rotationAngle (accumulator.solve ()), -0.4, 1e-10);
  // Residual of a wrong motion equals the directly summed squared errors.
  const pcl_crf::Rigid2d wrong = pcl_crf::makeRigid2d (0.1, 0.0, 0.0);
  double direct = 0.0;
  for (int i = 0; i < 30; ++i)
    direct += (0.5 + 0.01 * i) * (wrong * source.col (i) - target.col (i)).squaredNorm ();
  EXPECT_NEAR (accumulator.residual (wrong), direct, 1e-8 * direct);
  EXPECT_NEAR (accumulator.residual (accumulator.solve ()), 0.0, 1e-8);
}

TEST (RigidFit, DegenerateInputs)
{
  pcl_crf::RigidFitAccumulator empty;
  EXPECT_FALSE (empty.isWellPosed ());
  EXPECT_TRUE (empty.solve ().isApprox (pcl_crf::Rigid2d::Identity ()));
  pcl_crf::RigidFitAccumulator single;
  single.add (Eigen::Vector2d (1, 2), Eigen::Vector2d (3, 5));
  EXPECT_FALSE (single.isWellPosed ());
  EXPECT_NEAR ((single.solve () * Eigen::Vector2d (1, 2) - Eigen::Vector2d (3, 5)).norm (), 0.0, 1e-12);
  EXPECT_THROW (pcl_crf::fitRigid2d (Eigen::Matrix2Xd (2, 3), Eigen::Matrix2Xd (2, 2)), std::invalid_argument);
}

TEST (KnnIndex, BatchedSearchEqualsBruteForce)
{
  const Eigen::Matrix2Xd points = randomPoints (500, 4);
  const Eigen::Matrix2Xd queries = randomPoints (100, 5);
  const pcl_crf::KnnIndex index (points);
  const auto result = index.search (queries, 3);
  ASSERT_EQ (result.indices.rows (), 3);
  ASSERT_EQ (result.indices.cols (), 100);
  for (int q = 0; q < 100; ++q) {
    Eigen::VectorXd d = (points.colwise () - queries.col (q)).colwise ().squaredNorm ();
    Eigen::Index best;
    d.minCoeff (&best);
    EXPECT_EQ (result.indices (0, q), best);
    EXPECT_NEAR (result.squared_distances (0, q), d (best), 1e-12);
    EXPECT_LE (result.squared_distances (0, q), result.squared_distances (1, q));
  }
}

TEST (KnnIndex, CopiesOfAPointAreNeighboursInTheirOrder)
{
  // Points 1, 3 and 4 are one point; 0 and 2 are 1 m and 2 m from it. FLANN's tree
  // cannot split copies (100 000 of them took minutes through CRFMatcher): it holds
  // the distinct points and every search expands them into their copies, in order.
  Eigen::MatrixXd points (2, 5);
  points << 1, 0, 2, 0, 0,
            0, 0, 0, -0.0, 0;
  const pcl_crf::KnnIndex index (points);
  EXPECT_EQ (index.size (), 5);
  EXPECT_TRUE (index.points ().isApprox (points));
  const auto result = index.search (Eigen::MatrixXd::Zero (2, 1), 6);
  const std::vector<int> expected_indices = {1, 3, 4, 0, 2, -1};
  const std::vector<double> expected_distances = {0, 0, 0, 1, 4, std::numeric_limits<double>::infinity ()};
  for (int r = 0; r < 6; ++r) {
    EXPECT_EQ (result.indices (r, 0), expected_indices[r]) << r;
    EXPECT_EQ (result.squared_distances (r, 0), expected_distances[r]) << r;
  }
  const auto two = index.search (Eigen::Vector2d (0.9, 0.0), 2);  // point 0, then the first copy
  EXPECT_EQ (two.indices (0, 0), 0);
  EXPECT_EQ (two.indices (1, 0), 1);
  EXPECT_NEAR (two.squared_distances (1, 0), 0.81, 1e-12);

  // A scan with 20 000 copies of one of its points: the same neighbours as brute force.
  Eigen::MatrixXd crowded (2, 20500);
  crowded.leftCols (500) = randomPoints (500, 7);
  crowded.rightCols (20000).colwise () = crowded.col (17);
  const pcl_crf::KnnIndex crowded_index (crowded);
  const Eigen::Matrix2Xd queries = randomPoints (50, 8);
  const auto found = crowded_index.search (queries, 3);
  for (Eigen::Index q = 0; q < queries.cols (); ++q) {
    const Eigen::VectorXd d2 = (crowded.colwise () - queries.col (q)).colwise ().squaredNorm ();
    std::vector<double> sorted (d2.data (), d2.data () + d2.size ());
    std::partial_sort (sorted.begin (), sorted.begin () + 3, sorted.end ());
    for (int r = 0; r < 3; ++r)
      EXPECT_DOUBLE_EQ (found.squared_distances (r, q), sorted[r]) << q << " " << r;
  }
  const auto at_copy = crowded_index.search (crowded.col (17), 3);
  EXPECT_EQ (at_copy.indices (0, 0), 17);
  EXPECT_EQ (at_copy.indices (1, 0), 500);
  EXPECT_EQ (at_copy.indices (2, 0), 501);
}

TEST (KnnIndex, FewerPointsThanKAndBadInput)
{
  Eigen::MatrixXd two (2, 2);
  two << 0, 1, 0, 0;
  const pcl_crf::KnnIndex index (two);
  const auto result = index.search (Eigen::MatrixXd::Zero (2, 1), 4);
  EXPECT_EQ (result.indices (0, 0), 0);
  EXPECT_EQ (result.indices (1, 0), 1);
  EXPECT_EQ (result.indices (2, 0), -1);
  EXPECT_THROW (index.search (Eigen::MatrixXd::Zero (3, 1), 1), std::invalid_argument);
  EXPECT_THROW (index.search (Eigen::MatrixXd::Zero (2, 1), 0), std::invalid_argument);
  // k rows are returned per query: a huge k used to allocate them (terabytes for 1e9).
  EXPECT_EQ (index.search (Eigen::MatrixXd::Zero (2, 3), pcl_crf::KnnIndex::kMaxNeighbours).indices.rows (),
             pcl_crf::KnnIndex::kMaxNeighbours);
  EXPECT_THROW (index.search (Eigen::MatrixXd::Zero (2, 300), 1000000000), std::invalid_argument);
  Eigen::MatrixXd bad = two;
  bad (0, 0) = std::nan ("");
  EXPECT_THROW (pcl_crf::KnnIndex {bad}, std::invalid_argument);
  EXPECT_THROW (index.search (bad.col (0), 1), std::invalid_argument);
  // A query 1e154 m away: every squared distance overflows, FLANN keeps no neighbour
  // (its output used to be left unwritten: garbage indices, then a crash downstream).
  EXPECT_THROW (index.search (Eigen::Vector2d (1e154, 1e154), 1), std::invalid_argument);
  const auto far = index.search (Eigen::Vector2d (1e150, 0.0), 2);  // still finite: both found (a tie)
  EXPECT_EQ (far.indices.col (0).sum (), 1);
  EXPECT_EQ (far.indices.col (0).minCoeff (), 0);
}

}  // namespace
