#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Log-potentials of a chain-structured pairwise CRF over labels y_0 … y_{n−1}.
 *
 *  The chain defines the distribution (Ramos et al., RSS 2007, Eq. (1) in log form)
 *  \f[ \log p(y) = \sum_i \mathrm{unary}_i(y_i) + \sum_{i<n-1} \mathrm{pairwise}_i(y_i, y_{i+1}) - \log Z. \f]
 *  Node i has S_i ≥ 1 states (counts may differ between nodes). An entry of −∞
 *  forbids a state or a transition; NaN and +∞ are invalid. An empty chain
 *  (no node, no edge) is valid: its only labelling is empty, with log Z = 0.
 *
 *  \code
 *  pcl_crf::crf::ChainPotentials chain;
 *  chain.unary = {Eigen::Vector2d (0.0, 1.0), Eigen::Vector3d (0.5, 0.0, -1.0)};
 *  chain.pairwise = {Eigen::MatrixXd::Zero (2, 3)};
 *  chain.validate ();   // throws std::invalid_argument naming the problem
 *  \endcode
 */
struct ChainPotentials
{
  /** node i: log-potential of each of its S_i states. */
  std::vector<Eigen::VectorXd> unary;
  /** edge i (between nodes i and i+1): S_i x S_{i+1} log-potentials. */
  std::vector<Eigen::MatrixXd> pairwise;

  /** \brief Number of nodes. */
  std::size_t
  size () const { return unary.size (); }

  /** \brief Number of states of node i. */
  int
  states (std::size_t i) const { return static_cast<int> (unary[i].size ()); }

  /** \brief Checks the shapes and values described above.
   *  \throws std::invalid_argument naming the first problem (zero states, a node
   *  whose states are all forbidden, pairwise count != n − 1, size mismatch, NaN, +∞).
   */
  void
  validate () const;

  /** \brief Unnormalised log-probability Σ unary + Σ pairwise of one labelling.
   *  \throws std::invalid_argument when labels has the wrong size or a label is out of range.
   */
  double
  score (const std::vector<int>& labels) const;
};

}  // namespace crf
}  // namespace pcl_crf
