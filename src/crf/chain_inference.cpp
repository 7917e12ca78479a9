#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

/** A probability-space message sum below this times its number of terms sends the
 *  message to the log-space path: every factor is at most 1 and every nonzero one
 *  accurate, so each term lost to underflow is below 2.2e-308 and, above this, all
 *  of them are below 2.2e-18 of the sum. */
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
  if (std::isfinite (log_value))
    return;
  const std::string where = std::string ("[pcl_crf::crf::") + method + "] ";
  if (log_value == -std::numeric_limits<double>::infinity ())
    throw std::invalid_argument (where + "every labelling of the chain is forbidden (-inf score), or its "
                                 "log-potentials sum below the range of a double");
  throw std::invalid_argument (where + "the score of the chain overflows (" + std::to_string (log_value) +
                               "): its log-potentials sum beyond the range of a double");
}

/** log Σ_k exp(term (k)) for k < count, by log-sum-exp (the log-space path of a
 *  message whose probability-space sums cannot be trusted). */
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

/** Edge marginal p(y_i = s, y_{i+1} = t) ∝ exp(α_i(s) + P_i(s, t) + u_{i+1}(t) + β_{i+1}(t)),
 *  normalised over the table from its largest log value (the terms, each as large as the
 *  potentials, cancel to log Z only up to their rounding: with potentials of 1e20 the
 *  exponents came out thousands off, and the table NaN). */
template <typename Alpha, typename Pairwise, typename Unary, typename Beta, typename Joint> void
fillEdgeMarginal (const Alpha& alpha, const Pairwise& pairwise, const Unary& unary_next, const Beta& beta_next,
                  Joint&& joint)
{
  for (Eigen::Index t = 0; t < pairwise.cols (); ++t)
    joint.col (t) = (pairwise.col (t) + alpha).array () + (unary_next (t) + beta_next (t));
  joint = (joint.array () - joint.maxCoeff ()).exp ().matrix ();
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
    unary_exp_.resize (node_total);
    unary_shift_.resize (n);
    forward_.resize (node_total);
    backward_.resize (node_total);
    forward_scale_.resize (n);
    backward_scale_.resize (n);
    alpha_.resize (node_total);
    beta_.resize (node_total);
    exact_forward_.assign (n, 0);
    exact_backward_.assign (n, 0);
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
  {
    Eigen::VectorXd alpha (states_[i]), beta (states_[i + 1]);
    for (int s = 0; s < states_[i]; ++s)
      alpha (s) = logForward (i, s);
    for (int t = 0; t < states_[i + 1]; ++t)
      beta (t) = logBackward (i + 1, t);
    fillEdgeMarginal (alpha, chain.pairwise (i), chain.unary (i + 1), beta,
                      Eigen::Map<Eigen::MatrixXd> (edge_marginals_.data () + edge_offset_[i], states_[i],
                                                   states_[i + 1]));
  }
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

bool
ChainInference::scaleUnary (const PackedChainPotentials& chain, std::size_t i)
{
  const double* unary = chain.unary (i).data ();
  double* scaled = unary_exp_.data () + node_offset_[i];
  const double maximum = *std::max_element (unary, unary + states_[i]);  // finite (validated)
  unary_shift_[i] = maximum;
  bool accurate = true;
  for (int s = 0; s < states_[i]; ++s)
  {
    scaled[s] = flushedExp (unary[s] - maximum);
    accurate = accurate && (scaled[s] > 0.0 || unary[s] == kLogZero);
  }
  return accurate;
}

double
ChainInference::logForward (std::size_t i, int s) const
{
  if (exact_forward_[i])
    return alpha_[node_offset_[i] + static_cast<std::size_t> (s)];
  const double f = forward_[node_offset_[i] + static_cast<std::size_t> (s)];
  return f > 0.0 ? forward_scale_[i] + std::log (f) : kLogZero;
}

double
ChainInference::logBackward (std::size_t i, int s) const
{
  if (exact_backward_[i])
    return beta_[node_offset_[i] + static_cast<std::size_t> (s)];
  const double h = backward_[node_offset_[i] + static_cast<std::size_t> (s)];
  return h > 0.0 ? backward_scale_[i] + std::log (h) : kLogZero;
}

void
ChainInference::forward (const PackedChainPotentials& chain, bool with_map, bool with_marginals)
{
  const std::size_t n = size ();
  const double normal = std::numeric_limits<double>::min ();
  if (with_map)
    std::copy_n (chain.unary (0).data (), states_[0], delta_.data ());
  if (with_marginals)
  {
    // f_0 = exp(u_0 − max u_0), scale max u_0; on the log-space path when an entry underflowed.
    exact_forward_[0] = !scaleUnary (chain, 0);
    std::copy_n (unary_exp_.data (), states_[0], forward_.data ());
    std::copy_n (chain.unary (0).data (), states_[0], alpha_.data ());
    forward_scale_[0] = unary_shift_[0];
  }
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
    // Scaled forward message: α_{i+1}(t) = F_{i+1} + log f_{i+1}(t) with
    // f_{i+1}(t) ∝ exp(u_{i+1}(t) − max u_{i+1}) Σ_s f_i(s) exp(P_i(s, t) − shift_i), max 1.
    const double* table = edgeTable (chain, i, true);
    bool trusted = scaleUnary (chain, i + 1);
    const double* f = forward_.data () + node_offset_[i];
    const double* scaled_unary = unary_exp_.data () + node_offset_[i + 1];
    double* next = forward_.data () + node_offset_[i + 1];
    double* sums = scratch_.data ();
    double maximum = 0.0;
    for (int t = 0; t < t_count; ++t)
    {
      const double* column = table + static_cast<std::ptrdiff_t> (t) * s_count;
      double sum = 0.0;
      for (int s = 0; s < s_count; ++s)
        sum += f[s] * column[s];
      sums[t] = sum;
      next[t] = sum * scaled_unary[t];
      maximum = std::max (maximum, next[t]);
    }
    // Every allowed entry must be a normal number from a sum above the underflow losses.
    const double safe = kSafeSumPerTerm * s_count;
    trusted = trusted && maximum >= normal;
    for (int t = 0; t < t_count && trusted; ++t)
    {
      next[t] /= maximum;
      trusted = unary[t] == kLogZero || (sums[t] >= safe && sums[t] * scaled_unary[t] >= normal && next[t] >= normal);
    }
    if (trusted)
    {
      forward_scale_[i + 1] = forward_scale_[i] + edge_shift_[i] + unary_shift_[i + 1] + std::log (maximum);
      continue;
    }
    // Log-space path: α_{i+1}(t) = u_{i+1}(t) + log Σ_s exp(α_i(s) + P_i(s, t)).
    exact_forward_[i + 1] = 1;
    double* alpha = scratch_.data () + s_count;
    for (int s = 0; s < s_count; ++s)
      alpha[s] = logForward (i, s);
    double* alpha_next = alpha_.data () + node_offset_[i + 1];
    for (int t = 0; t < t_count; ++t)
    {
      const double* column = pairwise + static_cast<std::ptrdiff_t> (t) * s_count;
      alpha_next[t] = unary[t] + logSumExpOf (s_count, [&] (int s) { return alpha[s] + column[s]; });
    }
    rescale (alpha_next, t_count, next, forward_scale_[i + 1]);
  }
}

void
ChainInference::rescale (const double* log_values, int count, double* scaled, double& scale)
{
  scale = *std::max_element (log_values, log_values + count);
  for (int k = 0; k < count; ++k)
    scaled[k] = scale == kLogZero ? 0.0 : flushedExp (log_values[k] - scale);
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
  const std::size_t n = size ();
  // log Z = log Σ_s exp(α_{n−1}(s)) = F_{n−1} + log Σ_s f_{n−1}(s)
  const double* last = forward_.data () + node_offset_[n - 1];
  log_partition_ = forward_scale_[n - 1] + std::log (std::accumulate (last, last + states_[n - 1], 0.0));
  requireFeasible (log_partition_, "sumProduct");

  // Scaled backward message: β_i(s) = B_i + log h_i(s) with
  // h_i(s) ∝ Σ_t exp(P_i(s, t) − shift_i) exp(u_{i+1}(t) − max u_{i+1}) h_{i+1}(t), max 1; β_{n−1} = 0.
  std::fill_n (backward_.data () + node_offset_[n - 1], states_[n - 1], 1.0);
  backward_scale_[n - 1] = 0.0;
  for (std::size_t i = n - 1; i-- > 0;)
  {
    const int s_count = states_[i], t_count = states_[i + 1];
    const double* table = edgeTable (chain, i, false);
    const double* scaled_unary = unary_exp_.data () + node_offset_[i + 1];
    const double* h_next = backward_.data () + node_offset_[i + 1];
    double* h = backward_.data () + node_offset_[i];
    double* v = scratch_.data ();
    for (int t = 0; t < t_count; ++t)
      v[t] = scaled_unary[t] * h_next[t];
    std::fill_n (h, s_count, 0.0);
    for (int t = 0; t < t_count; ++t)
    {
      const double* column = table + static_cast<std::ptrdiff_t> (t) * s_count;
      for (int s = 0; s < s_count; ++s)
        h[s] += column[s] * v[t];
    }
    const double maximum = *std::max_element (h, h + s_count);
    const double safe = kSafeSumPerTerm * t_count;
    if (std::all_of (h, h + s_count, [safe] (double sum) { return sum >= safe; }))
    {
      for (int s = 0; s < s_count; ++s)
        h[s] /= maximum;
      backward_scale_[i] = backward_scale_[i + 1] + unary_shift_[i + 1] + edge_shift_[i] + std::log (maximum);
      continue;
    }
    // Log-space path: β_i(s) = log Σ_t exp(P_i(s, t) + u_{i+1}(t) + β_{i+1}(t)).
    exact_backward_[i] = 1;
    const double* unary = chain.unary (i + 1).data ();
    for (int t = 0; t < t_count; ++t)
      v[t] = unary[t] + logBackward (i + 1, t);
    const double* pairwise = chain.pairwise (i).data ();
    double* beta = beta_.data () + node_offset_[i];
    for (int s = 0; s < s_count; ++s)
      beta[s] = logSumExpOf (t_count, [&] (int t) { return pairwise[s + static_cast<std::ptrdiff_t> (t) * s_count] + v[t]; });
    rescale (beta, s_count, h, backward_scale_[i]);
  }
}

void
ChainInference::nodeMarginals ()
{
  for (std::size_t i = 0; i < size (); ++i)  // p(y_i) ∝ exp(α_i + β_i) ∝ f_i h_i
  {
    const int count = states_[i];
    const double* f = forward_.data () + node_offset_[i];
    const double* h = backward_.data () + node_offset_[i];
    double* p = marginals_.data () + node_offset_[i];
    if (!exact_forward_[i] && !exact_backward_[i])
    {
      double sum = 0.0;
      for (int s = 0; s < count; ++s)
      {
        p[s] = f[s] * h[s];
        sum += p[s];
      }
      if (sum >= kSafeSumPerTerm * count)
      {
        for (int s = 0; s < count; ++s)
          p[s] /= sum;
        continue;
      }
    }
    for (int s = 0; s < count; ++s)
      p[s] = logForward (i, s) + logBackward (i, s);
    double scale = 0.0;
    rescale (p, count, p, scale);
    const double sum = std::accumulate (p, p + count, 0.0);
    for (int s = 0; s < count; ++s)
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

namespace {

/** The MAP result of the last compute () of \a workspace. */
MapResult
mapResultOf (const ChainInference& workspace)
{
  MapResult result;
  result.labels = workspace.mapLabels ();
  result.log_score = workspace.mapLogScore ();
  return result;
}

/** The marginals of the last compute () of \a workspace (the edge marginals when it computed them). */
MarginalResult
marginalResultOf (const ChainInference& workspace, bool with_edge_marginals)
{
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

}  // namespace

MapResult
maxProduct (const ChainPotentials& chain, ChainInference& workspace)
{
  workspace.compute (chain, kMapLabels);
  return mapResultOf (workspace);
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
  return marginalResultOf (workspace, with_edge_marginals);
}

void
maxAndSumProduct (const PackedChainPotentials& chain, ChainInference& workspace, MapResult& map,
                  MarginalResult& marginals)
{
  workspace.compute (chain, kMapAndMarginals);
  map = mapResultOf (workspace);
  marginals = marginalResultOf (workspace, false);
}

MarginalResult
sumProduct (const ChainPotentials& chain, bool with_edge_marginals)
{
  ChainInference workspace;
  return sumProduct (chain, workspace, with_edge_marginals);
}

}  // namespace crf
}  // namespace pcl_crf
