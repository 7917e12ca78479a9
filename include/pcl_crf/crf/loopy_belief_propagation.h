#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Log-potentials of a general pairwise CRF (any graph, possibly with loops).
 *
 *  log p(y) = Σ_v unary[v](y_v) + Σ_e edges[e].log_potential(y_a, y_b) − log Z.
 *  Same value rules as ChainPotentials: −∞ forbids, NaN and +∞ are invalid.
 */
struct PairwiseGraph
{
  struct Edge
  {
    /** end nodes, a != b. */
    int a = 0;
    int b = 0;
    /** S_a x S_b log-potentials. */
    Eigen::MatrixXd log_potential;
  };

  /** node v: log-potential of each of its S_v states. */
  std::vector<Eigen::VectorXd> unary;
  std::vector<Edge> edges;

  /** \brief \throws std::invalid_argument naming the first problem (zero states,
   *  node index out of range, self loop, size mismatch, NaN, +∞).
   */
  void
  validate () const;
};

/** \brief Which semiring the messages use. */
enum class LoopyMode
{
  /** messages sum over the sender's states: beliefs approximate marginals. */
  SumProduct,
  /** messages maximise over the sender's states: beliefs approximate max-marginals. */
  MaxProduct
};

/** \brief Parameters of loopy belief propagation (flooding schedule). */
struct LoopyOptions
{
  LoopyMode mode = LoopyMode::SumProduct;
  /** maximum number of flooding sweeps (every message updated once per sweep); default 100. */
  int max_iterations = 100;
  /** fraction λ ∈ [0, 1) of the previous message kept: m ← (1 − λ) m_new + λ m_old,
   *  mixed in the probability domain; entries the new message forbids (−∞) stay
   *  forbidden. Default 0 (no damping). */
  double damping = 0.0;
  /** converged when no normalised message entry (probability domain) changes by more
   *  than this in a sweep; default 1e-6. */
  double tolerance = 1e-6;
};

/** \brief Output of loopy belief propagation. */
struct LoopyResult
{
  /** node v: normalised belief (sums to 1). */
  std::vector<Eigen::VectorXd> beliefs;
  /** argmax of every belief (with MaxProduct: the approximate MAP labelling). */
  std::vector<int> labels;
  /** flooding sweeps performed. */
  int iterations = 0;
  /** true when the message change fell below LoopyOptions::tolerance. */
  bool converged = false;
};

/** \brief Loopy belief propagation in log space with a flooding schedule
 *  (Pearl; Murphy, Weiss & Jordan, UAI 1999). Exact on trees.
 *
 *  \code
 *  pcl_crf::crf::LoopyOptions options;
 *  options.mode = pcl_crf::crf::LoopyMode::MaxProduct;
 *  options.damping = 0.5;
 *  const pcl_crf::crf::LoopyResult r = pcl_crf::crf::loopyBeliefPropagation (graph, options);
 *  \endcode
 *  \throws std::invalid_argument for an invalid graph or options, or when every
 *  state of a node ends up forbidden.
 */
LoopyResult
loopyBeliefPropagation (const PairwiseGraph& graph, const LoopyOptions& options = {});

}  // namespace crf
}  // namespace pcl_crf
