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

/** \brief Forward–backward (sum-product with log-sum-exp): node marginals, optional
 *  edge marginals and log Z. Stable for long chains with large log-potentials.
 *  \param[in] chain the potentials
 *  \param[in] with_edge_marginals also fill MarginalResult::edge_marginals
 *             (memory Σ S_i S_{i+1} doubles); default false
 *  \throws std::invalid_argument when the chain is invalid or every labelling is forbidden.
 */
MarginalResult
sumProduct (const ChainPotentials& chain, bool with_edge_marginals = false);

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
