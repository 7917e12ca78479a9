#pragma once

#include <pcl_crf/crf/chain_potentials.h>

#include <Eigen/Core>

#include <random>
#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief The most probable labelling of a chain and its unnormalised log-probability. */
struct MapResult
{
  /** label of every node. */
  std::vector<int> labels;
  /** Σ unary + Σ pairwise of \c labels (ChainPotentials::score). */
  double log_score = 0.0;
};

/** \brief Exact marginals of a chain. */
struct MarginalResult
{
  /** node i: p(y_i = s), sums to 1. */
  std::vector<Eigen::VectorXd> node_marginals;
  /** edge i: S_i x S_{i+1} matrix p(y_i = s, y_{i+1} = t); empty unless requested. */
  std::vector<Eigen::MatrixXd> edge_marginals;
  /** log Z, the log of the sum of exp(score) over all labellings. */
  double log_partition = 0.0;
};

/** \brief What ChainInference::compute () computes (bit flags, combine with |). */
enum ChainOutputs : unsigned
{
  /** the MAP labelling and its log-score (max-product, Viterbi). */
  kMapLabels = 1u,
  /** log Z and the node marginals (sum-product, forward–backward). */
  kNodeMarginals = 2u,
  /** log Z, the node and the edge marginals. */
  kEdgeMarginals = 4u | kNodeMarginals,
  /** max-product and sum-product (node marginals). */
  kMapAndMarginals = kMapLabels | kNodeMarginals
};

/** \brief Exact inference on chains with reused buffers: max-product and sum-product
 *  in one pass over the potentials, without allocating once the buffers have grown
 *  to the largest chain seen. Keep one object per thread and call compute () for
 *  chain after chain; the results are views into it, valid until the next compute ().
 *
 *  Max-product runs in log space. Sum-product runs in probability space with scaled
 *  messages (Rabiner's scaling): α_i(s) = F_i + log f_i(s) with max_s f_i(s) = 1, β
 *  likewise, node marginals ∝ f_i h_i. Each unary vector and each edge is
 *  exponentiated once after subtracting its maximum, exp(u_i − max u_i) and
 *  exp(P_i − max P_i), for both passes (on chains of more than 32768 transitions in
 *  all the backward pass exponentiates the edges again, which bounds the memory); a
 *  message costs one logarithm. A message in which an allowed entry would not be an
 *  accurate normal number (a sum below S · 1e−290, where terms lost to underflow
 *  could matter, or an underflowed product) is computed by log-sum-exp instead and
 *  kept in log space. The results agree with the log-space definition
 *  (forwardMessages (), backwardMessages ()) to rounding, also for potentials of any
 *  magnitude and for forbidden (−∞) states and transitions.
 *
 *  \code
 *  pcl_crf::crf::ChainInference inference;   // keep it: its buffers are reused
 *  inference.compute (chain, pcl_crf::crf::kMapAndMarginals);
 *  const std::vector<int>& map = inference.mapLabels ();
 *  const double p = inference.nodeMarginal (i) (map[i]);
 *  \endcode
 */
class ChainInference
{
public:
  /** \brief Runs inference on \a chain.
   *  \param[in] chain the potentials (validated)
   *  \param[in] outputs what to compute (ChainOutputs flags); default kMapAndMarginals
   *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
   */
  void
  compute (const PackedChainPotentials& chain, unsigned outputs = kMapAndMarginals);

  /** \brief As above for a ChainPotentials (copied into an internal packed chain). */
  void
  compute (const ChainPotentials& chain, unsigned outputs = kMapAndMarginals);

  /** \brief Number of nodes of the last chain. */
  std::size_t
  size () const { return states_.size (); }

  /** \brief MAP label of every node (kMapLabels). */
  const std::vector<int>&
  mapLabels () const { return labels_; }

  /** \brief Σ unary + Σ pairwise of mapLabels () (kMapLabels). */
  double
  mapLogScore () const { return map_log_score_; }

  /** \brief log Z (kNodeMarginals). */
  double
  logPartition () const { return log_partition_; }

  /** \brief p(y_i = s) of node i's states, sums to 1 (kNodeMarginals). */
  Eigen::Map<const Eigen::VectorXd>
  nodeMarginal (std::size_t i) const { return {marginals_.data () + node_offset_[i], states_[i]}; }

  /** \brief S_i x S_{i+1} p(y_i = s, y_{i+1} = t) of edge i (kEdgeMarginals). */
  Eigen::Map<const Eigen::MatrixXd>
  edgeMarginal (std::size_t i) const
  {
    return {edge_marginals_.data () + edge_offset_[i], states_[i], states_[i + 1]};
  }

private:
  void
  run (const PackedChainPotentials& chain, unsigned outputs);

  /** Viterbi's δ and the scaled forward messages, in one pass over the edges. */
  void
  forward (const PackedChainPotentials& chain, bool with_map, bool with_marginals);

  void
  backtrack ();

  /** log Z and the scaled backward messages. */
  void
  backward (const PackedChainPotentials& chain);

  void
  nodeMarginals ();

  /** exp(P_i − shift_i) of edge i: computed (with its shift) when \a compute, else the
   *  stored table or, beyond the storage bound, computed again with the stored shift. */
  double*
  edgeTable (const PackedChainPotentials& chain, std::size_t i, bool compute);

  /** exp(u_i − max u_i) into unary_exp_; false when an allowed state underflowed. */
  bool
  scaleUnary (const PackedChainPotentials& chain, std::size_t i);

  /** \a scaled = exp(log_values − scale), scale = max log_values (−∞: all 0). */
  static void
  rescale (const double* log_values, int count, double* scaled, double& scale);

  /** α_i(s) and β_i(s) in log space, from either representation. */
  double
  logForward (std::size_t i, int s) const;

  double
  logBackward (std::size_t i, int s) const;

  std::vector<int> states_;
  std::vector<std::size_t> node_offset_, edge_offset_;  // into the per-state and per-edge buffers
  // max-product
  std::vector<double> delta_;
  std::vector<int> back_;
  std::vector<int> labels_;
  double map_log_score_ = 0.0;
  // sum-product: α_i(s) = forward_scale_[i] + log forward_ (s), β likewise, unless the
  // node's message took the log-space path: then alpha_ / beta_ hold it exactly.
  bool store_tables_ = true;
  std::vector<double> edge_exp_;    // exp(P_i − shift_i) of every edge, or of one
  std::vector<double> edge_shift_;  // max P_i (0 when all are −∞)
  std::vector<double> unary_exp_;   // exp(u_i − max u_i)
  std::vector<double> unary_shift_;
  std::vector<double> forward_, backward_, forward_scale_, backward_scale_;
  std::vector<double> alpha_, beta_;
  std::vector<char> exact_forward_, exact_backward_;
  std::vector<double> marginals_, edge_marginals_;
  std::vector<double> scratch_;  // 3 max S_i
  double log_partition_ = 0.0;
  PackedChainPotentials packed_;  // compute (ChainPotentials)
};

/** \brief Viterbi (max-product in log space): the MAP labelling.
 *
 *  \code
 *  const pcl_crf::crf::MapResult map = pcl_crf::crf::maxProduct (chain);
 *  \endcode
 *  Time O(Σ S_i S_{i+1}); ties are broken towards the lowest state index.
 *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
 */
MapResult
maxProduct (const ChainPotentials& chain);

/** \brief maxProduct () with the buffers of \a workspace (no allocation besides the result). */
MapResult
maxProduct (const ChainPotentials& chain, ChainInference& workspace);

/** \brief Forward–backward (sum-product, see ChainInference): node marginals, optional
 *  edge marginals and log Z. Stable for long chains with large log-potentials.
 *  \param[in] chain the potentials
 *  \param[in] with_edge_marginals also fill MarginalResult::edge_marginals
 *             (memory Σ S_i S_{i+1} doubles); default false
 *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
 */
MarginalResult
sumProduct (const ChainPotentials& chain, bool with_edge_marginals = false);

/** \brief sumProduct () with the buffers of \a workspace (no allocation besides the result). */
MarginalResult
sumProduct (const ChainPotentials& chain, ChainInference& workspace, bool with_edge_marginals = false);

/** \brief maxProduct () and sumProduct () (node marginals) of one packed chain in one
 *  pass over its potentials, used as it is (no copy): the results are those of the two
 *  calls. A ChainPotentials is packed with PackedChainPotentials::assign ().
 *  \param[in] chain the potentials
 *  \param[in,out] workspace the buffers (see ChainInference)
 *  \param[out] map the MAP labelling and its log-score
 *  \param[out] marginals log Z and the node marginals (no edge marginals)
 *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
 */
void
maxAndSumProduct (const PackedChainPotentials& chain, ChainInference& workspace, MapResult& map,
                  MarginalResult& marginals);

/** \brief Forward log-messages α_i(s) = log Σ_{y_0..y_{i−1}} exp(score of y_0..y_{i−1}, s),
 *  including unary_i(s) (Rabiner's α in log space). The chain is not validated.
 */
std::vector<Eigen::VectorXd>
forwardMessages (const ChainPotentials& chain);

/** \brief Backward log-messages β_i(s) = log Σ_{y_{i+1}..} exp(score of the rest given y_i = s),
 *  excluding unary_i; β_{n−1} = 0. The chain is not validated.
 */
std::vector<Eigen::VectorXd>
backwardMessages (const ChainPotentials& chain);

/** \brief Exact sample y ~ p(y) by forward filtering, backward sampling.
 *  \param[in] chain the potentials (validated)
 *  \param[in,out] rng the random generator
 *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
 */
std::vector<int>
sampleChain (const ChainPotentials& chain, std::mt19937& rng);

}  // namespace crf
}  // namespace pcl_crf
