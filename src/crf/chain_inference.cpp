#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

void
requireFeasible (double log_value, const char* method)
{
  if (!std::isfinite (log_value))
    throw std::invalid_argument (std::string ("[pcl_crf::crf::") + method +
                                 "] every labelling of the chain is forbidden (-inf score)");
}

/** Edge marginal p(y_i = s, y_{i+1} = t) = exp(α_i(s) + P_i(s, t) + u_{i+1}(t) + β_{i+1}(t) − log Z). */
Eigen::MatrixXd
edgeMarginal (const Eigen::VectorXd& alpha, const Eigen::MatrixXd& pairwise, const Eigen::VectorXd& unary_next,
              const Eigen::VectorXd& beta_next, double log_partition)
{
  Eigen::MatrixXd log_joint = pairwise.colwise () + alpha;
  const Eigen::RowVectorXd column_term = ((unary_next + beta_next).array () - log_partition).matrix ().transpose ();
  log_joint.rowwise () += column_term;
  Eigen::MatrixXd joint = safeExp (log_joint.array ()).matrix ();
  return joint / joint.sum ();
}

}  // namespace

std::vector<Eigen::VectorXd>
forwardMessages (const ChainPotentials& chain)
{
  std::vector<Eigen::VectorXd> alpha (chain.size ());
  if (chain.size () == 0)
    return alpha;
  alpha[0] = chain.unary[0];
  for (std::size_t i = 0; i + 1 < chain.size (); ++i)
  {
    // α_{i+1}(t) = u_{i+1}(t) + log Σ_s exp(α_i(s) + P_i(s, t))
    alpha[i + 1] = logVectorMatrix (alpha[i], chain.pairwise[i]) + chain.unary[i + 1];
  }
  return alpha;
}

std::vector<Eigen::VectorXd>
backwardMessages (const ChainPotentials& chain)
{
  const std::size_t n = chain.size ();
  std::vector<Eigen::VectorXd> beta (n);
  if (n == 0)
    return beta;
  beta[n - 1] = Eigen::VectorXd::Zero (chain.unary[n - 1].size ());
  for (std::size_t i = n - 1; i-- > 0;)
  {
    // β_i(s) = log Σ_t exp(P_i(s, t) + u_{i+1}(t) + β_{i+1}(t))
    beta[i] = logMatrixVector (chain.pairwise[i], chain.unary[i + 1] + beta[i + 1]);
  }
  return beta;
}

MapResult
maxProduct (const ChainPotentials& chain)
{
  chain.validate ();
  MapResult result;
  const std::size_t n = chain.size ();
  if (n == 0)
    return result;
  std::vector<std::vector<int>> back (n);
  Eigen::VectorXd delta = chain.unary[0];
  for (std::size_t i = 0; i + 1 < n; ++i)  // δ_{i+1}(t) = u_{i+1}(t) + max_s [δ_i(s) + P_i(s, t)]
    delta = maxVectorMatrix (delta, chain.pairwise[i], &back[i + 1]) + chain.unary[i + 1];

  Eigen::Index last = 0;
  result.log_score = delta.maxCoeff (&last);
  requireFeasible (result.log_score, "maxProduct");
  result.labels.resize (n);
  result.labels[n - 1] = static_cast<int> (last);
  for (std::size_t i = n - 1; i > 0; --i)
    result.labels[i - 1] = back[i][result.labels[i]];
  return result;
}

MarginalResult
sumProduct (const ChainPotentials& chain, bool with_edge_marginals)
{
  chain.validate ();
  MarginalResult result;
  const std::size_t n = chain.size ();
  if (n == 0)
    return result;
  const std::vector<Eigen::VectorXd> alpha = forwardMessages (chain);
  const std::vector<Eigen::VectorXd> beta = backwardMessages (chain);
  result.log_partition = logSumExp (alpha[n - 1]);  // log Z = log Σ_s exp(α_{n−1}(s))
  requireFeasible (result.log_partition, "sumProduct");

  result.node_marginals.resize (n);
  for (std::size_t i = 0; i < n; ++i)
    result.node_marginals[i] = normalizedExp (alpha[i] + beta[i]);  // p(y_i) ∝ exp(α_i + β_i)
  if (!with_edge_marginals)
    return result;
  result.edge_marginals.resize (n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    result.edge_marginals[i] =
        edgeMarginal (alpha[i], chain.pairwise[i], chain.unary[i + 1], beta[i + 1], result.log_partition);
  return result;
}

}  // namespace crf
}  // namespace pcl_crf
