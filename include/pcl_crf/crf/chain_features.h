#pragma once

#include <pcl_crf/crf/chain_potentials.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Feature values of a log-linear chain CRF (Ramos et al., RSS 2007, Eq. (2)):
 *  log-potentials are w_u · f_u(i, s) and w_p · f_p(i, s, t).
 *
 *  Layout (cache-friendly: one dense matrix per node and per edge, one row per
 *  state or state pair, so a potential table is a single matrix-vector product):
 *  - \c unary[i] is S_i x D_u, row s = f_u(i, s);
 *  - \c pairwise[i] is (S_i · S_{i+1}) x D_p, row s + S_i · t = f_p(i, s, t)
 *    (the S_i x S_{i+1} table flattened column-major, as Eigen stores matrices).
 *
 *  \code
 *  pcl_crf::crf::ChainFeatures f;
 *  f.unary = {Eigen::MatrixXd::Random (2, 3), Eigen::MatrixXd::Random (2, 3)};   // D_u = 3
 *  f.pairwise = {Eigen::MatrixXd::Identity (4, 1)};                               // D_p = 1
 *  const Eigen::VectorXd w = Eigen::VectorXd::Ones (4);                           // [w_u; w_p]
 *  const pcl_crf::crf::ChainPotentials chain = pcl_crf::crf::potentials (f, w);
 *  \endcode
 */
struct ChainFeatures
{
  std::vector<Eigen::MatrixXd> unary;
  std::vector<Eigen::MatrixXd> pairwise;

  /** \brief Number of nodes. */
  std::size_t
  size () const { return unary.size (); }

  /** \brief S_i, the number of states of node i. */
  int
  states (std::size_t i) const { return static_cast<int> (unary[i].rows ()); }

  /** \brief D_u (columns of the unary matrices); 0 for an empty chain. */
  int
  unaryDimension () const { return unary.empty () ? 0 : static_cast<int> (unary[0].cols ()); }

  /** \brief D_p (columns of the pairwise matrices); 0 for a chain without edges. */
  int
  pairwiseDimension () const { return pairwise.empty () ? 0 : static_cast<int> (pairwise[0].cols ()); }

  /** \brief Row of pairwise[i] that holds f_p(i, s, t), given S_i. */
  static Eigen::Index
  pairRow (int s, int t, int states_i) { return s + static_cast<Eigen::Index> (states_i) * t; }

  /** \brief \throws std::invalid_argument naming the first problem: zero states, edge
   *  count != n − 1, inconsistent D_u or D_p, wrong row count, non-finite value.
   */
  void
  validate () const;
};

/** \brief Log-potentials of a feature chain under weights = [w_u (D_u); w_p (D_p)]:
 *  unary_i(s) = w_u · f_u(i, s), pairwise_i(s, t) = w_p · f_p(i, s, t).
 *  A chain without edges accepts any number of (unused) pairwise weights.
 *  \throws std::invalid_argument for invalid features or a weight count mismatch.
 */
ChainPotentials
potentials (const ChainFeatures& features, const Eigen::VectorXd& weights);

/** \brief A training example: features plus the true label of every node. */
struct LabelledChain
{
  ChainFeatures features;
  std::vector<int> labels;
};

}  // namespace crf
}  // namespace pcl_crf
