#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

/** A probability-space message sum below this times its number of terms is recomputed
 *  in log space: each term lost to underflow is below 2.2e-308 (on the scale where the
 *  largest factors are 1), so above it the lost terms are below 2.2e-18 of the sum. */
constexpr double kSafeSumPerTerm = 1e-290;

void
requireFeasible (double log_value, const char* method)
{
  if (!std::isfinite (log_value))
    throw std::invalid_argument (std::string ("[pcl_crf::crf::") + method +
                                 "] every labelling of the chain is forbidden (-inf score)");
}

/** log Σ_k exp(term (k)) for k < count, by log-sum-exp (the exact path of a message
 *  entry whose probability-space sum underflowed). */
template <typename Term> double
logSumExpOf (int count, Term term)
{
  double maximum = kLogZero;
  for (int k = 0; k < count; ++k)
    maximum = std::max (maximum, term (k));
  if (maximum == kLogZero)
    return kLogZero;
  double sum = 0.0;
  for (int k = 0; k < count; ++k)
    sum += std::exp (term (k) - maximum);
  return maximum + std::log (sum);
}

/** Edge marginal p(y_i = s, y_{i+1} = t) = exp(α_i(s) + P_i(s, t) + u_{i+1}(t) + β_{i+1}(t) − log Z). */
template <typename Alpha, typename Pairwise, typename Unary, typename Beta, typename Joint> void
fillEdgeMarginal (const Alpha& alpha, const Pairwise& pairwise, const Unary& unary_next, const Beta& beta_next,
                  double log_partition, Joint&& joint)
{
  for (Eigen::Index t = 0; t < pairwise.cols (); ++t)
  {
    const double column_term = (unary_next (t) + beta_next (t)) - log_partition;
    joint.col (t) = ((pairwise.col (t) + alpha).array () + column_term).exp ();
  }
  flushDenormals (joint.data (), joint.size ());
  joint /= joint.sum ();
}

}  // namespace

void
ChainInference::compute (const PackedChainPotentials& chain, unsigned outputs)
{
  chain.validate ();
  run (chain, outputs);
}

void
ChainInference::compute (const ChainPotentials& chain, unsigned outputs)
{
  chain.validate ();
  packed_.assign (chain);
  run (packed_, outputs);
}

void
ChainInference::run (const PackedChainPotentials& chain, unsigned outputs)
{
  const std::size_t n = chain.size ();
  states_.resize (n);
  node_offset_.resize (n);
  edge_offset_.resize (n);
  std::size_t node_total = 0, edge_total = 0;
  int max_states = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    states_[i] = chain.states (i);
    max_states = std::max (max_states, states_[i]);
    node_offset_[i] = node_total;
    edge_offset_[i] = edge_total;
    node_total += static_cast<std::size_t> (states_[i]);
    if (i + 1 < n)
      edge_total += static_cast<std::size_t> (states_[i]) * static_cast<std::size_t> (chain.states (i + 1));
  }
  map_log_score_ = 0.0;
  log_partition_ = 0.0;
  labels_.clear ();
  if (outputs & kMapLabels)
  {
    delta_.resize (node_total);
    back_.resize (node_total);
    viterbi (chain);
  }
  if (outputs & kNodeMarginals)
  {
    edge_exp_.resize (edge_total);
    edge_shift_.resize (n);
    alpha_.resize (node_total);
    beta_.resize (node_total);
    marginals_.resize (node_total);
    scratch_.resize (3 * static_cast<std::size_t> (max_states));
    const bool with_edges = (outputs & kEdgeMarginals) == kEdgeMarginals;
    if (with_edges)
      edge_marginals_.resize (edge_total);
    forwardBackward (chain, with_edges);
  }
}

void
ChainInference::viterbi (const PackedChainPotentials& chain)
{
  const std::size_t n = size ();
  if (n == 0)
    return;
  // δ_{i+1}(t) = u_{i+1}(t) + max_s [δ_i(s) + P_i(s, t)], lowest s on ties
  Eigen::Map<Eigen::VectorXd> (delta_.data (), states_[0]) = chain.unary (0);
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const int s_count = states_[i];
    const double* delta = delta_.data () + node_offset_[i];
    double* next = delta_.data () + node_offset_[i + 1];
    int* back = back_.data () + node_offset_[i + 1];
    const Eigen::Map<const Eigen::MatrixXd> pairwise = chain.pairwise (i);
    const Eigen::Map<const Eigen::VectorXd> unary = chain.unary (i + 1);
    for (int t = 0; t < states_[i + 1]; ++t)
    {
      const double* column = pairwise.data () + static_cast<std::ptrdiff_t> (t) * s_count;
      int best = 0;
      double value = delta[0] + column[0];
      for (int s = 1; s < s_count; ++s)
        if (delta[s] + column[s] > value)
        {
          value = delta[s] + column[s];
          best = s;
        }
      next[t] = value + unary (t);
      back[t] = best;
    }
  }
  const double* last = delta_.data () + node_offset_[n - 1];
  int best = 0;
  for (int s = 1; s < states_[n - 1]; ++s)
    if (last[s] > last[best])
      best = s;
  map_log_score_ = last[best];
  requireFeasible (map_log_score_, "maxProduct");
  labels_.resize (n);
  labels_[n - 1] = best;
  for (std::size_t i = n - 1; i > 0; --i)
    labels_[i - 1] = back_[node_offset_[i] + static_cast<std::size_t> (labels_[i])];
}

void
ChainInference::forwardBackward (const PackedChainPotentials& chain, bool with_edge_marginals)
{
  using Vector = Eigen::Map<Eigen::VectorXd>;
  using ConstMatrix = Eigen::Map<const Eigen::MatrixXd>;
  const std::size_t n = size ();
  if (n == 0)
    return;
  const auto alpha = [this] (std::size_t i) { return Vector (alpha_.data () + node_offset_[i], states_[i]); };
  const auto beta = [this] (std::size_t i) { return Vector (beta_.data () + node_offset_[i], states_[i]); };
  const auto edgeExp = [this] (std::size_t i) {
    return ConstMatrix (edge_exp_.data () + edge_offset_[i], states_[i], states_[i + 1]);
  };

  // exp(P_i − max P_i), shared by both passes; an edge with every transition forbidden is all 0.
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const Eigen::Index size = static_cast<Eigen::Index> (states_[i]) * states_[i + 1];
    const Eigen::Map<const Eigen::ArrayXd> pairwise (chain.pairwise (i).data (), size);
    const double maximum = pairwise.maxCoeff ();
    edge_shift_[i] = maximum == kLogZero ? 0.0 : maximum;
    Eigen::Map<Eigen::ArrayXd> table (edge_exp_.data () + edge_offset_[i], size);
    table = (pairwise - edge_shift_[i]).exp ();
    flushDenormals (table.data (), size);
  }

  // Forward: α_{i+1}(t) = u_{i+1}(t) + log Σ_s exp(α_i(s) + P_i(s, t))
  //                     = u_{i+1}(t) + max α_i + shift_i + log Σ_s exp(α_i(s) − max α_i) E_i(s, t).
  alpha (0) = chain.unary (0);
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const int s_count = states_[i], t_count = states_[i + 1];
    const Vector alpha_i = alpha (i);
    Vector alpha_next = alpha (i + 1);
    const Eigen::Map<const Eigen::VectorXd> unary = chain.unary (i + 1);
    const double maximum = alpha_i.maxCoeff ();
    if (maximum == kLogZero)
    {
      alpha_next.setConstant (kLogZero);
      continue;
    }
    Vector a (scratch_.data (), s_count), sums (scratch_.data () + s_count, t_count);
    a = (alpha_i.array () - maximum).exp ().matrix ();
    flushDenormals (a.data (), s_count);
    const ConstMatrix table = edgeExp (i);
    for (int t = 0; t < t_count; ++t)
      sums (t) = table.col (t).dot (a);
    alpha_next = unary + ((maximum + edge_shift_[i]) + sums.array ().log ()).matrix ();
    const ConstMatrix pairwise = chain.pairwise (i);
    for (int t = 0; t < t_count; ++t)
      if (!(sums (t) >= kSafeSumPerTerm * s_count))
        alpha_next (t) = unary (t) + logSumExpOf (s_count, [&] (int s) { return alpha_i (s) + pairwise (s, t); });
  }

  // Backward: β_i(s) = log Σ_t exp(P_i(s, t) + v(t)), v = u_{i+1} + β_{i+1}; β_{n−1} = 0.
  beta (n - 1).setZero ();
  for (std::size_t i = n - 1; i-- > 0;)
  {
    const int s_count = states_[i], t_count = states_[i + 1];
    Vector v (scratch_.data (), t_count), e (scratch_.data () + t_count, t_count);
    Vector sums (scratch_.data () + 2 * t_count, s_count);
    v = chain.unary (i + 1) + beta (i + 1);
    Vector beta_i = beta (i);
    const double maximum = v.maxCoeff ();
    if (maximum == kLogZero)
    {
      beta_i.setConstant (kLogZero);
      continue;
    }
    e = (v.array () - maximum).exp ().matrix ();
    flushDenormals (e.data (), t_count);
    const ConstMatrix table = edgeExp (i);
    sums.setZero ();
    for (int t = 0; t < t_count; ++t)
      sums += table.col (t) * e (t);
    beta_i = ((maximum + edge_shift_[i]) + sums.array ().log ()).matrix ();
    const ConstMatrix pairwise = chain.pairwise (i);
    for (int s = 0; s < s_count; ++s)
      if (!(sums (s) >= kSafeSumPerTerm * t_count))
        beta_i (s) = logSumExpOf (t_count, [&] (int t) { return pairwise (s, t) + v (t); });
  }

  log_partition_ = logSumExp (alpha (n - 1));  // log Z = log Σ_s exp(α_{n−1}(s))
  requireFeasible (log_partition_, "sumProduct");

  for (std::size_t i = 0; i < n; ++i)  // p(y_i) ∝ exp(α_i + β_i)
  {
    Vector p (marginals_.data () + node_offset_[i], states_[i]);
    p = alpha (i) + beta (i);
    const double maximum = p.maxCoeff ();
    p = (p.array () - maximum).exp ().matrix ();
    flushDenormals (p.data (), p.size ());
    p /= p.sum ();
  }
  if (!with_edge_marginals)
    return;
  for (std::size_t i = 0; i + 1 < n; ++i)
    fillEdgeMarginal (alpha (i), chain.pairwise (i), chain.unary (i + 1), beta (i + 1), log_partition_,
                  Eigen::Map<Eigen::MatrixXd> (edge_marginals_.data () + edge_offset_[i], states_[i], states_[i + 1]));
}

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
maxProduct (const ChainPotentials& chain, ChainInference& workspace)
{
  workspace.compute (chain, kMapLabels);
  MapResult result;
  result.labels = workspace.mapLabels ();
  result.log_score = workspace.mapLogScore ();
  return result;
}

MapResult
maxProduct (const ChainPotentials& chain)
{
  ChainInference workspace;
  return maxProduct (chain, workspace);
}

MarginalResult
sumProduct (const ChainPotentials& chain, ChainInference& workspace, bool with_edge_marginals)
{
  workspace.compute (chain, with_edge_marginals ? kEdgeMarginals : kNodeMarginals);
  MarginalResult result;
  const std::size_t n = workspace.size ();
  result.log_partition = workspace.logPartition ();
  result.node_marginals.reserve (n);
  for (std::size_t i = 0; i < n; ++i)
    result.node_marginals.emplace_back (workspace.nodeMarginal (i));
  if (!with_edge_marginals || n == 0)
    return result;
  result.edge_marginals.reserve (n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    result.edge_marginals.emplace_back (workspace.edgeMarginal (i));
  return result;
}

MarginalResult
sumProduct (const ChainPotentials& chain, bool with_edge_marginals)
{
  ChainInference workspace;
  return sumProduct (chain, workspace, with_edge_marginals);
}

}  // namespace crf
}  // namespace pcl_crf
