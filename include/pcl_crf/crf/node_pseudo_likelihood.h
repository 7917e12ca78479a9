#pragma once

#include <pcl_crf/crf/lbfgs_minimizer.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief One factor of the pseudo-likelihood of any log-linear CRF (Besag 1975):
 *  the conditional p(y_v | its Markov blanket) of one node v with its neighbours
 *  clamped to their true labels.
 *
 *  Row s of \c features is the sum of every feature vector of the factors that
 *  touch v, evaluated with v in state s and the neighbours in their true states,
 *  so that p(y_v = s | blanket) ∝ exp(w · features.row (s)).
 */
struct NodeConditional
{
  /** S_v x D. */
  Eigen::MatrixXd features;
  /** the true state, in [0, S_v). */
  int label = 0;
};

/** \brief Maximum pseudo-likelihood learning over node conditionals of any graph
 *  (chains, ladders, loopy graphs): minimises
 *  \f[ -\sum_v \Big[ w\cdot f_v(y_v) - \log\sum_s e^{w\cdot f_v(s)} \Big] + \frac{\|w\|^2}{2\sigma^2} \f]
 *  with L-BFGS. The gradient is expected minus observed features plus w / σ².
 *
 *  \code
 *  std::vector<pcl_crf::crf::NodeConditional> nodes = ...;   // one per node of every training graph
 *  const pcl_crf::crf::LbfgsResult fit = pcl_crf::crf::learnNodePseudoLikelihood (nodes, 10.0);
 *  \endcode
 *  \param[in] nodes the conditionals, all with the same D ≥ 1 and at least one state
 *  \param[in] prior_sigma σ of the Gaussian prior on every weight (> 0; +inf: none)
 *  \param[in] options L-BFGS stopping rules
 *  \throws std::invalid_argument for no nodes, mismatched D, a label out of range,
 *  non-finite features or σ ≤ 0.
 */
LbfgsResult
learnNodePseudoLikelihood (const std::vector<NodeConditional>& nodes, double prior_sigma,
                           const LbfgsOptions& options = {});

/** \brief The minimised objective of learnNodePseudoLikelihood at \a w, with its
 *  gradient (for tests and diagnostics). */
double
nodePseudoLikelihoodObjective (const std::vector<NodeConditional>& nodes, double prior_sigma,
                               const Eigen::VectorXd& w, Eigen::VectorXd& gradient);

}  // namespace crf
}  // namespace pcl_crf
