#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>

namespace pcl_crf {
namespace crf {

/** \brief Stopping rules of the L-BFGS driver (liblbfgs, Nocedal 1980; Liu & Nocedal 1989). */
struct LbfgsOptions
{
  /** maximum number of L-BFGS iterations (0: no limit); default 200. */
  int max_iterations = 200;
  /** gradient test: stop when ||g|| < epsilon · max(1, ||x||); default 1e-5. */
  double epsilon = 1e-5;
  /** decrease test: stop when (f_{k−past} − f_k) / |f_k| < delta; default 1e-7. */
  double delta = 1e-7;
  /** iterations back for the decrease test (0 disables it); default 5. */
  int past = 5;
};

/** \brief Outcome of a minimisation. */
struct LbfgsResult
{
  /** the last accepted point. */
  Eigen::VectorXd x;
  /** objective at x. */
  double value = 0.0;
  /** L-BFGS iterations performed (0 when x0 already satisfied the gradient test). */
  int iterations = 0;
  /** true on the gradient test, the decrease test or "already minimised". */
  bool converged = false;
  /** what stopped the optimiser, in words (liblbfgs return code mapped to text). */
  std::string status;
};

/** \brief The hook an optimiser calls: returns f(x) and writes ∇f(x) into gradient
 *  (already sized like x).
 */
using Objective = std::function<double (const Eigen::VectorXd& x, Eigen::VectorXd& gradient)>;

/** \brief Minimises a smooth objective with liblbfgs (Moré–Thuente line search).
 *
 *  The decrease test is done by this driver on |f| (liblbfgs 1.10 divides by a
 *  signed f and would stop at once on negative objectives). An exception thrown
 *  by the objective stops the optimiser and is rethrown.
 *
 *  \code
 *  auto quadratic = [] (const Eigen::VectorXd& x, Eigen::VectorXd& g) { g = 2.0 * x; return x.squaredNorm (); };
 *  const pcl_crf::crf::LbfgsResult r = pcl_crf::crf::minimizeLbfgs (quadratic, Eigen::VectorXd::Ones (3));
 *  \endcode
 *  \throws std::invalid_argument for an empty or non-finite x0 or bad options.
 */
LbfgsResult
minimizeLbfgs (const Objective& objective, const Eigen::VectorXd& x0, const LbfgsOptions& options = {});

}  // namespace crf
}  // namespace pcl_crf
