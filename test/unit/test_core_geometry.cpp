#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/rigid_fit.h>

#include <gtest/gtest.h>

#include <random>

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
