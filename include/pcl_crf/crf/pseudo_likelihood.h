#pragma once

#include <pcl_crf/crf/chain_features.h>
#include <pcl_crf/crf/lbfgs_minimizer.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Maximum pseudo-likelihood learning of a log-linear chain CRF (Besag 1975;
 *  used for CRF-Matching by Ramos et al., RSS 2007, Sec. IV).
 *
 *  Objective (minimised), with the neighbours clamped to their true labels:
 *  \f[ -\sum_{chains}\sum_i \Big[ s_i(y_i) - \log\sum_s e^{s_i(s)} \Big] + \frac{\|w\|^2}{2\sigma^2}, \f]
 *  \f[ s_i(s) = w_u\cdot f_u(i,s) + w_p\cdot f_p(i-1, y_{i-1}, s) + w_p\cdot f_p(i, s, y_{i+1}). \f]
 *  Its gradient is expected minus observed features plus w / σ².
 *
 *  \code
 *  pcl_crf::crf::PseudoLikelihood learner (training_chains, 10.0);
 *  const pcl_crf::crf::LbfgsResult fit = learner.train ();
 *  const pcl_crf::crf::ChainPotentials chain = pcl_crf::crf::potentials (test_features, fit.x);
 *  \endcode
 */
/** \brief true when a chain of \a chains has an edge (without one no pairwise weight
 *  can be learned: PseudoLikelihood then learns the unary weights only). */
bool
hasAnEdge (const std::vector<LabelledChain>& chains);

class PseudoLikelihood
{
public:
  /** \param[in] chains training chains (copied); all must share D_u, and all with edges D_p
   *  \param[in] prior_sigma standard deviation σ of the Gaussian prior on each weight
   *             (> 0; +inf disables the prior); default 10
   *  \throws std::invalid_argument for invalid features, labels or σ.
   */
  explicit PseudoLikelihood (std::vector<LabelledChain> chains, double prior_sigma = 10.0);

  /** \brief Sets σ of the Gaussian prior (> 0, +inf: none). \throws std::invalid_argument */
  void
  setPriorSigma (double prior_sigma);

  double
  getPriorSigma () const { return prior_sigma_; }

  /** \brief Number of weights, D_u + D_p. */
  int
  getDimension () const { return unary_dimension_ + pairwise_dimension_; }

  int
  getUnaryDimension () const { return unary_dimension_; }

  int
  getPairwiseDimension () const { return pairwise_dimension_; }

  /** \brief Negative log pseudo-likelihood plus prior at w, and its exact gradient.
   *  \param[in] w weights [w_u; w_p]
   *  \param[out] grad gradient, resized to w's size
   *  \throws std::invalid_argument when w has the wrong size.
   */
  double
  objectiveAndGradient (const Eigen::VectorXd& w, Eigen::VectorXd& grad) const;

  /** \brief Minimises the objective with L-BFGS from w = 0. */
  LbfgsResult
  train (const LbfgsOptions& options = {}) const;

  /** \brief Minimises the objective with L-BFGS from w0. */
  LbfgsResult
  train (const Eigen::VectorXd& w0, const LbfgsOptions& options) const;

private:
  /** Adds chain c's negative log PL to the return value and its gradient to grad. */
  double
  chainTerm (const LabelledChain& chain, const Eigen::VectorXd& w, Eigen::VectorXd& grad) const;

  std::vector<LabelledChain> chains_;
  int unary_dimension_ = 0;
  int pairwise_dimension_ = 0;
  double prior_sigma_ = 10.0;
};

}  // namespace crf
}  // namespace pcl_crf
