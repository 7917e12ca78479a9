#include <pcl_crf/crf/lbfgs_minimizer.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace {

using pcl_crf::crf::LbfgsOptions;
using pcl_crf::crf::minimizeLbfgs;
using pcl_crf::crf::Objective;

double
rosenbrock (const Eigen::VectorXd& x, Eigen::VectorXd& g)
{
  const double a = 1.0 - x (0), b = x (1) - x (0) * x (0);
  g.resize (2);
  g (0) = -2.0 * a - 400.0 * x (0) * b;
  g (1) = 200.0 * b;
  return a * a + 100.0 * b * b;
}

TEST (LbfgsMinimizer, RosenbrockConvergesToOneOne)
{
  const auto r = minimizeLbfgs (rosenbrock, Eigen::Vector2d (-1.2, 1.0));
  EXPECT_TRUE (r.converged) << r.status;
  EXPECT_NEAR (r.x (0), 1.0, 1e-4);
  EXPECT_NEAR (r.x (1), 1.0, 1e-4);
  EXPECT_LT (r.value, 1e-8);
  EXPECT_GT (r.iterations, 0);
}

TEST (LbfgsMinimizer, NegativeQuadraticReachesTheSolution)
{
  // f = ½ xᵀAx − bᵀx, minimum −½ bᵀA⁻¹b < 0 (liblbfgs' own decrease test would stop at once).
  const int n = 10;
  Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr (n, n, [] (Eigen::Index r, Eigen::Index c) {
    return std::sin (1.0 + r * 7.0 + c * 3.0);
  });
  const Eigen::MatrixXd A = M * M.transpose () + Eigen::MatrixXd::Identity (n, n);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced (n, -2.0, 3.0);
  auto quadratic = [&] (const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    g = A * x - b;
    return 0.5 * x.dot (A * x) - b.dot (x);
  };
  LbfgsOptions options;
  options.epsilon = 1e-7;
  const auto r = minimizeLbfgs (quadratic, Eigen::VectorXd::Zero (n), options);
  const Eigen::VectorXd solution = A.ldlt ().solve (b);
  EXPECT_TRUE (r.converged) << r.status;
  EXPECT_LT ((r.x - solution).norm (), 1e-6);
  EXPECT_NEAR (r.value, -0.5 * b.dot (solution), 1e-9);
}

TEST (LbfgsMinimizer, StartAtTheMinimumIsAlreadyMinimized)
{
  auto bowl = [] (const Eigen::VectorXd& x, Eigen::VectorXd& g) { g = 2.0 * x; return x.squaredNorm (); };
  const auto r = minimizeLbfgs (bowl, Eigen::VectorXd::Zero (3));
  EXPECT_TRUE (r.converged);
  EXPECT_EQ (r.iterations, 0);
  EXPECT_NE (r.status.find ("already"), std::string::npos) << r.status;
}

TEST (LbfgsMinimizer, IterationLimitIsNotConvergence)
{
  LbfgsOptions options;
  options.max_iterations = 3;
  const auto r = minimizeLbfgs (rosenbrock, Eigen::Vector2d (-1.2, 1.0), options);
  EXPECT_FALSE (r.converged);
  EXPECT_EQ (r.iterations, 3);
  EXPECT_NE (r.status.find ("maximum"), std::string::npos) << r.status;
  Eigen::VectorXd g;
  EXPECT_DOUBLE_EQ (r.value, rosenbrock (r.x, g));
}

TEST (LbfgsMinimizer, ObjectiveErrorsPropagate)
{
  auto throwing = [] (const Eigen::VectorXd&, Eigen::VectorXd&) -> double { throw std::domain_error ("boom"); };
  EXPECT_THROW (minimizeLbfgs (throwing, Eigen::VectorXd::Ones (2)), std::domain_error);
  auto wrong_size = [] (const Eigen::VectorXd&, Eigen::VectorXd& g) { g = Eigen::VectorXd::Ones (5); return 1.0; };
  EXPECT_THROW (minimizeLbfgs (wrong_size, Eigen::VectorXd::Ones (2)), std::invalid_argument);
  EXPECT_THROW (minimizeLbfgs (rosenbrock, Eigen::VectorXd ()), std::invalid_argument);
}

TEST (LbfgsMinimizer, ANaNObjectiveOrNoObjectiveIsAnError)
{
  // A NaN gradient was reported as "converged: the initial point already minimises".
  auto nan_gradient = [] (const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    g = Eigen::VectorXd::Constant (x.size (), std::nan (""));
    return x.squaredNorm ();
  };
  auto nan_value = [] (const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    g = 2.0 * x;
    return std::nan ("");
  };
  for (const Objective& objective : {Objective (nan_gradient), Objective (nan_value)}) {
    try {
      minimizeLbfgs (objective, Eigen::VectorXd::Ones (2));
      ADD_FAILURE () << "expected std::invalid_argument";
    }
    catch (const std::invalid_argument& e) {
      EXPECT_NE (std::string (e.what ()).find ("returned a NaN value or gradient"), std::string::npos) << e.what ();
    }
  }
  EXPECT_THROW (minimizeLbfgs (Objective (), Eigen::VectorXd::Ones (2)), std::invalid_argument);  // bad_function_call
}

}  // namespace
