#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

/** A probability-space message sum below this times its number of terms is recomputed
 *  in log space: each term lost to underflow is below 2.2e-308 (on the scale where the
 *  largest factors are 1), so above it the lost terms are below 2.2e-18 of the sum. */
constexpr double kSafeSumPerTerm = 1e-290;

/** The exp tables of the edges are kept for the backward pass up to this many entries
 *  (256 KB); beyond, the backward pass computes them again (bounded memory). */
constexpr std::size_t kMaxStoredTableEntries = std::size_t (1) << 15;

/** exp(x), with results below the smallest normal double set to 0 (see flushDenormals). */
inline double
flushedExp (double x)
{
  const double e = std::exp (x);
  return e < std::numeric_limits<double>::min () ? 0.0 : e;
}

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
  std::size_t node_total = 0, edge_total = 0, max_edge = 0;
  int max_states = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    states_[i] = chain.states (i);
    max_states = std::max (max_states, states_[i]);
    node_offset_[i] = node_total;
    edge_offset_[i] = edge_total;
    node_total += static_cast<std::size_t> (states_[i]);
    if (i + 1 < n)
    {
      const std::size_t edge = static_cast<std::size_t> (states_[i]) * static_cast<std::size_t> (chain.states (i + 1));
      edge_total += edge;
      max_edge = std::max (max_edge, edge);
    }
  }
  map_log_score_ = 0.0;
  log_partition_ = 0.0;
  labels_.clear ();
  const bool with_map = (outputs & kMapLabels) != 0;
  const bool with_marginals = (outputs & kNodeMarginals) != 0;
  if (n == 0 || !(with_map || with_marginals))
    return;
  if (with_map)
  {
    delta_.resize (node_total);
    back_.resize (node_total);
  }
  if (with_marginals)
  {
    store_tables_ = edge_total <= kMaxStoredTableEntries;
    edge_exp_.resize (store_tables_ ? edge_total : max_edge);
    edge_shift_.resize (n);
    alpha_.resize (node_total);
    beta_.resize (node_total);
    marginals_.resize (node_total);
    scratch_.resize (3 * static_cast<std::size_t> (max_states));
  }
  forward (chain, with_map, with_marginals);
  if (with_map)
    backtrack ();
  if (!with_marginals)
    return;
  backward (chain);
  nodeMarginals ();
  if ((outputs & kEdgeMarginals) != kEdgeMarginals)
    return;
  edge_marginals_.resize (edge_total);
  for (std::size_t i = 0; i + 1 < n; ++i)
    fillEdgeMarginal (alphaOf (i), chain.pairwise (i), chain.unary (i + 1), betaOf (i + 1), log_partition_,
                      Eigen::Map<Eigen::MatrixXd> (edge_marginals_.data () + edge_offset_[i], states_[i],
                                                   states_[i + 1]));
}

double*
ChainInference::edgeTable (const PackedChainPotentials& chain, std::size_t i, bool compute)
{
  const std::size_t size = static_cast<std::size_t> (states_[i]) * static_cast<std::size_t> (states_[i + 1]);
  double* table = edge_exp_.data () + (store_tables_ ? edge_offset_[i] : 0);
  if (!compute && store_tables_)
    return table;
  const double* pairwise = chain.pairwise (i).data ();
  if (compute)
  {
    double maximum = kLogZero;
    for (std::size_t k = 0; k < size; ++k)
      maximum = std::max (maximum, pairwise[k]);
    edge_shift_[i] = maximum == kLogZero ? 0.0 : maximum;  // every transition forbidden: all 0
  }
  for (std::size_t k = 0; k < size; ++k)
    table[k] = flushedExp (pairwise[k] - edge_shift_[i]);
  return table;
}

void
ChainInference::forward (const PackedChainPotentials& chain, bool with_map, bool with_marginals)
{
  const std::size_t n = size ();
  if (with_map)
    std::copy_n (chain.unary (0).data (), states_[0], delta_.data ());
  if (with_marginals)
    std::copy_n (chain.unary (0).data (), states_[0], alpha_.data ());
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const int s_count = states_[i], t_count = states_[i + 1];
    const double* pairwise = chain.pairwise (i).data ();
    const double* unary = chain.unary (i + 1).data ();
    if (with_map)
    {
      // Viterbi: δ_{i+1}(t) = u_{i+1}(t) + max_s [δ_i(s) + P_i(s, t)], lowest s on ties.
      const double* delta = delta_.data () + node_offset_[i];
      double* next = delta_.data () + node_offset_[i + 1];
      int* back = back_.data () + node_offset_[i + 1];
      for (int t = 0; t < t_count; ++t)
      {
        const double* column = pairwise + static_cast<std::ptrdiff_t> (t) * s_count;
        int best = 0;
        double value = delta[0] + column[0];
        for (int s = 1; s < s_count; ++s)
          if (delta[s] + column[s] > value)
          {
            value = delta[s] + column[s];
            best = s;
          }
        next[t] = value + unary[t];
        back[t] = best;
      }
    }
    if (!with_marginals)
      continue;
    // Forward: α_{i+1}(t) = u_{i+1}(t) + log Σ_s exp(α_i(s) + P_i(s, t))
    //   = u_{i+1}(t) + max α_i + shift_i + log Σ_s exp(α_i(s) − max α_i) exp(P_i(s, t) − shift_i).
    const double* table = edgeTable (chain, i, true);
    const double* alpha = alpha_.data () + node_offset_[i];
    double* next = alpha_.data () + node_offset_[i + 1];
    const double maximum = *std::max_element (alpha, alpha + s_count);
    if (maximum == kLogZero)
    {
      std::fill_n (next, t_count, kLogZero);
      continue;
    }
    double* a = scratch_.data ();
    for (int s = 0; s < s_count; ++s)
      a[s] = flushedExp (alpha[s] - maximum);
    const double offset = maximum + edge_shift_[i];
    const double safe = kSafeSumPerTerm * s_count;
    for (int t = 0; t < t_count; ++t)
    {
      const double* column = table + static_cast<std::ptrdiff_t> (t) * s_count;
      double sum = 0.0;
      for (int s = 0; s < s_count; ++s)
        sum += a[s] * column[s];
      const double* log_column = pairwise + static_cast<std::ptrdiff_t> (t) * s_count;
      next[t] = unary[t] + (sum >= safe ? offset + std::log (sum)
                                        : logSumExpOf (s_count, [&] (int s) { return alpha[s] + log_column[s]; }));
    }
  }
}

void
ChainInference::backtrack ()
{
  const std::size_t n = size ();
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
ChainInference::backward (const PackedChainPotentials& chain)
{
  // β_i(s) = log Σ_t exp(P_i(s, t) + v(t)), v = u_{i+1} + β_{i+1}; β_{n−1} = 0.
  const std::size_t n = size ();
  const auto max_states = static_cast<std::ptrdiff_t> (scratch_.size () / 3);
  std::fill_n (beta_.data () + node_offset_[n - 1], states_[n - 1], 0.0);
  for (std::size_t i = n - 1; i-- > 0;)
  {
    const int s_count = states_[i], t_count = states_[i + 1];
    const double* unary = chain.unary (i + 1).data ();
    const double* beta_next = beta_.data () + node_offset_[i + 1];
    double* beta = beta_.data () + node_offset_[i];
    double *v = scratch_.data (), *e = v + max_states, *sums = e + max_states;
    double maximum = kLogZero;
    for (int t = 0; t < t_count; ++t)
    {
      v[t] = unary[t] + beta_next[t];
      maximum = std::max (maximum, v[t]);
    }
    if (maximum == kLogZero)
    {
      std::fill_n (beta, s_count, kLogZero);
      continue;
    }
    for (int t = 0; t < t_count; ++t)
      e[t] = flushedExp (v[t] - maximum);
    const double* table = edgeTable (chain, i, false);
    std::fill_n (sums, s_count, 0.0);
    for (int t = 0; t < t_count; ++t)
    {
      const double* column = table + static_cast<std::ptrdiff_t> (t) * s_count;
      for (int s = 0; s < s_count; ++s)
        sums[s] += column[s] * e[t];
    }
    const double* pairwise = chain.pairwise (i).data ();
    const double offset = maximum + edge_shift_[i];
    const double safe = kSafeSumPerTerm * t_count;
    for (int s = 0; s < s_count; ++s)
      beta[s] = sums[s] >= safe ? offset + std::log (sums[s]) : logSumExpOf (t_count, [&] (int t) {
        return pairwise[s + static_cast<std::ptrdiff_t> (t) * s_count] + v[t];
      });
  }
  log_partition_ = logSumExp (alphaOf (n - 1));  // log Z = log Σ_s exp(α_{n−1}(s))
  requireFeasible (log_partition_, "sumProduct");
}

void
ChainInference::nodeMarginals ()
{
  for (std::size_t i = 0; i < size (); ++i)  // p(y_i) ∝ exp(α_i + β_i)
  {
    const double* alpha = alpha_.data () + node_offset_[i];
    const double* beta = beta_.data () + node_offset_[i];
    double* p = marginals_.data () + node_offset_[i];
    double maximum = kLogZero;
    for (int s = 0; s < states_[i]; ++s)
    {
      p[s] = alpha[s] + beta[s];
      maximum = std::max (maximum, p[s]);
    }
    double sum = 0.0;
    for (int s = 0; s < states_[i]; ++s)
    {
      p[s] = flushedExp (p[s] - maximum);
      sum += p[s];
    }
    for (int s = 0; s < states_[i]; ++s)
      p[s] /= sum;
  }
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
