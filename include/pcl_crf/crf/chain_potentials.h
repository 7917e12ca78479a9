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

/** \brief The log-potentials of a chain, as ChainPotentials defines them, packed in
 *  contiguous buffers that keep their capacity: an iterative algorithm can build a new
 *  chain every round without allocating (see ChainInference).
 *
 *  Nodes are appended one by one; appending node i + 1 adds the S_i x S_{i+1} edge i.
 *  New entries are 0 until set through unary () and pairwise (), which are views
 *  valid until the next addNode (), clear () or assign ().
 *
 *  \code
 *  pcl_crf::crf::PackedChainPotentials chain;
 *  chain.addNode (2);
 *  chain.addNode (3);                   // adds the 2 x 3 edge 0
 *  chain.unary (0) << 0.0, 1.0;
 *  chain.unary (1) << 0.5, 0.0, -1.0;
 *  chain.pairwise (0) (1, 2) = pcl_crf::crf::kLogZero;   // a forbidden transition (crf/log_space.h)
 *  chain.clear ();                      // ready for the next chain, capacity kept
 *  \endcode
 */
class PackedChainPotentials
{
public:
  /** \brief Removes every node (the buffers keep their capacity). */
  void
  clear ();

  /** \brief Reserves room for \a nodes nodes with \a unary_entries states in all and
   *  \a pairwise_entries = Σ S_i S_{i+1} transitions (to build a chain with one allocation). */
  void
  reserve (std::size_t nodes, std::size_t unary_entries, std::size_t pairwise_entries);

  /** \brief Appends a node with \a states ≥ 1 states (and the edge from the previous node).
   *  \throws std::invalid_argument when states < 1. */
  void
  addNode (int states);

  /** \brief Replaces the content with a copy of \a chain (not validated). */
  void
  assign (const ChainPotentials& chain);

  /** \brief Number of nodes. */
  std::size_t
  size () const { return states_.size (); }

  /** \brief Number of states of node i. */
  int
  states (std::size_t i) const { return states_[i]; }

  /** \brief Node i: log-potential of each of its S_i states. */
  Eigen::Map<Eigen::VectorXd>
  unary (std::size_t i) { return {unary_.data () + unary_offset_[i], states_[i]}; }

  Eigen::Map<const Eigen::VectorXd>
  unary (std::size_t i) const { return {unary_.data () + unary_offset_[i], states_[i]}; }

  /** \brief Edge i (between nodes i and i + 1): S_i x S_{i+1} log-potentials, column-major. */
  Eigen::Map<Eigen::MatrixXd>
  pairwise (std::size_t i) { return {pairwise_.data () + pairwise_offset_[i], states_[i], states_[i + 1]}; }

  Eigen::Map<const Eigen::MatrixXd>
  pairwise (std::size_t i) const { return {pairwise_.data () + pairwise_offset_[i], states_[i], states_[i + 1]}; }

  /** \brief The checks of ChainPotentials::validate () (except the shapes, which hold by construction).
   *  \throws std::invalid_argument naming the first problem. */
  void
  validate () const;

  /** \brief Unnormalised log-probability of one labelling, as ChainPotentials::score ().
   *  \throws std::invalid_argument when labels has the wrong size or a label is out of range. */
  double
  score (const std::vector<int>& labels) const;

private:
  std::vector<int> states_;
  std::vector<std::size_t> unary_offset_;     // node i's first entry in unary_
  std::vector<std::size_t> pairwise_offset_;  // edge i's first entry in pairwise_
  std::vector<double> unary_;
  std::vector<double> pairwise_;
};

}  // namespace crf
}  // namespace pcl_crf
