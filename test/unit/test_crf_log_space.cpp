#include <pcl_crf/crf/log_space.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace {

TEST (CrfLogSpace, ForbiddenEntriesStayExactlyZero)
{
  // Eigen's vectorised exp maps -inf to ~5.6e-309; the helpers must not.
  const double inf = std::numeric_limits<double>::infinity ();
  for (int n : {1, 2, 3, 4, 8, 9})
  {
    const Eigen::VectorXd all_forbidden = Eigen::VectorXd::Constant (n, -inf);
    EXPECT_EQ (pcl_crf::crf::logSumExp (all_forbidden), -inf);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero (n, n);
    m.col (n - 1).setConstant (-inf);
    EXPECT_EQ (pcl_crf::crf::logVectorMatrix (Eigen::VectorXd::Zero (n), m) (n - 1), -inf);
    EXPECT_EQ (pcl_crf::crf::logMatrixVector (m.transpose (), Eigen::VectorXd::Zero (n)) (n - 1), -inf);
    EXPECT_EQ (pcl_crf::crf::logMatrixVector (m, all_forbidden) (0), -inf);
    Eigen::VectorXd one_allowed = all_forbidden;
    one_allowed (n - 1) = 1000.0;
    const Eigen::VectorXd p = pcl_crf::crf::normalizedExp (one_allowed);
    EXPECT_EQ (p (n - 1), 1.0);
    EXPECT_EQ (p.head (n - 1).sum (), 0.0);
  }
  EXPECT_NEAR (pcl_crf::crf::logSumExp (Eigen::Vector2d (1000.0, 1000.0)), 1000.0 + std::log (2.0), 1e-12);
}

TEST (CrfLogSpace, ProductsMatchTheirDefinitions)
{
  std::mt19937 rng (8);
  std::normal_distribution<double> normal (0.0, 30.0);
  const Eigen::MatrixXd m = Eigen::MatrixXd::NullaryExpr (4, 3, [&] () { return normal (rng); });
  const Eigen::VectorXd left = Eigen::VectorXd::NullaryExpr (4, [&] () { return normal (rng); });
  const Eigen::VectorXd right = Eigen::VectorXd::NullaryExpr (3, [&] () { return normal (rng); });
  std::vector<int> argmax;
  const Eigen::VectorXd forward = pcl_crf::crf::logVectorMatrix (left, m);
  const Eigen::VectorXd forward_max = pcl_crf::crf::maxVectorMatrix (left, m, &argmax);
  for (Eigen::Index t = 0; t < 3; ++t)
  {
    EXPECT_NEAR (forward (t), pcl_crf::crf::logSumExp (left + m.col (t)), 1e-12);
    Eigen::Index best;
    EXPECT_EQ (forward_max (t), (left + m.col (t)).maxCoeff (&best));
    EXPECT_EQ (argmax[t], best);
  }
  const Eigen::VectorXd backward = pcl_crf::crf::logMatrixVector (m, right);
  const Eigen::VectorXd backward_max = pcl_crf::crf::maxMatrixVector (m, right);
  for (Eigen::Index s = 0; s < 4; ++s)
  {
    EXPECT_NEAR (backward (s), pcl_crf::crf::logSumExp (m.row (s).transpose () + right), 1e-12);
    EXPECT_EQ (backward_max (s), (m.row (s).transpose () + right).maxCoeff ());
  }
}

}  // namespace
