#include <pcl_crf/matching/matching_chain.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** What the pairwise features of edge i need from the source side. */
struct SourceStep
{
  Eigen::Vector2d rotated;  // R (s_{i+1} − s_i)
  double length = 0.0;      // ||s_{i+1} − s_i||
};

SourceStep
sourceStep (const ScanShape& source, const PassGeometry& pass, int i)
{
  const Eigen::Vector2d step = source.points.col (i + 1) - source.points.col (i);
  return {pass.T_current.linear () * step, step.norm ()};
}

/** Geman–McClure residual ρ(d) = d² / (d² + σ²) from d². */
inline double
gemanMcClure (double squared_residual, double squared_scale)
{
  return squared_residual / (squared_residual + squared_scale);
}

/** The geometric part of f_p(i, s, t) for two candidate target points j, j'. */
struct EdgeTerms
{
  int shift = 0;               // j' − j
  double distance = 0.0;       // ρ(| ||s_{i+1} − s_i|| − ||t_j' − t_j|| |)
  double translation = 0.0;    // ρ(|| R (s_{i+1} − s_i) − (t_j' − t_j) ||)
};

inline EdgeTerms
edgeTerms (int j, int j_next, const SourceStep& step, const Eigen::Matrix2Xd& target, double squared_scale)
{
  const double dx = target (0, j_next) - target (0, j), dy = target (1, j_next) - target (1, j);
  const double length_error = step.length - std::sqrt (dx * dx + dy * dy);
  const double ex = step.rotated.x () - dx, ey = step.rotated.y () - dy;
  return {j_next - j, gemanMcClure (length_error * length_error, squared_scale),
          gemanMcClure (ex * ex + ey * ey, squared_scale)};
}

/** f_p(i, s, t) for target points j, j_next (kNoMatch for the outlier state). */
inline void
pairwiseFeatures (int j, int j_next, const SourceStep& step, const Eigen::Matrix2Xd& target, double squared_scale,
                  double* f)
{
  for (int k = 0; k < kPairwiseFeatureCount; ++k)
    f[k] = 0.0;
  const bool outlier = j == kNoMatch, outlier_next = j_next == kNoMatch;
  if (outlier || outlier_next) {
    f[outlier && outlier_next ? kOutlierRun : kOutlierSwitch] = 1.0;
    return;
  }
  const EdgeTerms terms = edgeTerms (j, j_next, step, target, squared_scale);
  f[kSequence] = terms.shift == 1 ? 1.0 : 0.0;
  f[kSequenceRepeat] = terms.shift == 0 ? 1.0 : 0.0;
  f[kSequenceSkip] = terms.shift == 2 ? 1.0 : 0.0;
  f[kPairwiseDistance] = terms.distance;
  f[kPairwiseTranslation] = terms.translation;
}

/** w_p · f_p(i, s, t) of two candidate states, without building f_p. */
inline double
inlierPairPotential (int j, int j_next, const SourceStep& step, const Eigen::Matrix2Xd& target, double squared_scale,
                     const double* w_p)
{
  const EdgeTerms terms = edgeTerms (j, j_next, step, target, squared_scale);
  const double sequence = terms.shift == 1   ? w_p[kSequence]
                          : terms.shift == 0 ? w_p[kSequenceRepeat]
                          : terms.shift == 2 ? w_p[kSequenceSkip]
                                             : 0.0;
  return sequence + w_p[kPairwiseDistance] * terms.distance + w_p[kPairwiseTranslation] * terms.translation;
}

/** Target point of state s of node i, kNoMatch for the outlier state. */
inline int
stateTarget (const Candidates& candidates, int i, int s)
{
  return s < candidates.count (i) ? candidates.target (i, s) : kNoMatch;
}

}  // namespace

crf::ChainFeatures
matchingChainFeatures (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                       const BoostedScores& scores, double residual_scale)
{
  const Candidates& candidates = pass.candidates;
  const int n = candidates.size ();
  crf::ChainFeatures features;
  features.unary.resize (n);
  for (int i = 0; i < n; ++i) {
    const int count = candidates.count (i);
    Eigen::MatrixXd& u = features.unary[i];
    u.setZero (count + 1, kUnaryFeatureCount);
    u.col (kDataMargin).head (count) = scores.data_margins.segment (candidates.offsets[i], count);
    u (count, kOutlierMargin) = scores.outlier_margins (i);
    u (count, kOutlierBias) = 1.0;
  }
  const double squared_scale = residual_scale * residual_scale;
  features.pairwise.resize (n > 0 ? n - 1 : 0);
  double f[kPairwiseFeatureCount];
  for (int i = 0; i + 1 < n; ++i) {
    const SourceStep step = sourceStep (source, pass, i);
    const int states = candidates.count (i) + 1, states_next = candidates.count (i + 1) + 1;
    Eigen::MatrixXd& p = features.pairwise[i];
    p.resize (states * states_next, kPairwiseFeatureCount);
    for (int t = 0; t < states_next; ++t)
      for (int s = 0; s < states; ++s) {
        pairwiseFeatures (stateTarget (candidates, i, s), stateTarget (candidates, i + 1, t), step,
                          target.points, squared_scale, f);
        p.row (crf::ChainFeatures::pairRow (s, t, states)) = Eigen::Map<const Eigen::RowVectorXd> (f, kPairwiseFeatureCount);
      }
  }
  return features;
}

namespace {

/** Gives \a chain one node per source point with its candidates + 1 states. */
void
shapeChain (const Candidates& candidates, crf::ChainPotentials& chain)
{
  const int n = candidates.size ();
  chain.unary.resize (n);
  chain.pairwise.resize (n > 0 ? n - 1 : 0);
  for (int i = 0; i < n; ++i) {
    chain.unary[i].resize (candidates.count (i) + 1);
    if (i + 1 < n)
      chain.pairwise[i].resize (candidates.count (i) + 1, candidates.count (i + 1) + 1);
  }
}

void
shapeChain (const Candidates& candidates, crf::PackedChainPotentials& chain)
{
  const int n = candidates.size ();
  std::size_t unary_entries = 0, pairwise_entries = 0;
  for (int i = 0; i < n; ++i) {
    unary_entries += static_cast<std::size_t> (candidates.count (i) + 1);
    if (i + 1 < n)
      pairwise_entries += static_cast<std::size_t> (candidates.count (i) + 1) * (candidates.count (i + 1) + 1);
  }
  chain.clear ();
  chain.reserve (static_cast<std::size_t> (n), unary_entries, pairwise_entries);
  for (int i = 0; i < n; ++i)
    chain.addNode (candidates.count (i) + 1);
}

Eigen::VectorXd&
unaryOf (crf::ChainPotentials& chain, int i)
{
  return chain.unary[i];
}

Eigen::Map<Eigen::VectorXd>
unaryOf (crf::PackedChainPotentials& chain, int i)
{
  return chain.unary (i);
}

Eigen::MatrixXd&
pairwiseOf (crf::ChainPotentials& chain, int i)
{
  return chain.pairwise[i];
}

Eigen::Map<Eigen::MatrixXd>
pairwiseOf (crf::PackedChainPotentials& chain, int i)
{
  return chain.pairwise (i);
}

/** matchingChainPotentials () into either kind of chain. */
template <typename Chain> void
fillMatchingChain (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                   const BoostedScores& scores, const Eigen::VectorXd& weights, double residual_scale, Chain& chain)
{
  if (weights.size () != kCrfWeightCount)
    throw std::invalid_argument ("[pcl_crf::matching::matchingChainPotentials] expected " +
                                 std::to_string (kCrfWeightCount) + " weights, got " +
                                 std::to_string (weights.size ()));
  const Candidates& candidates = pass.candidates;
  const int n = candidates.size ();
  shapeChain (candidates, chain);
  for (int i = 0; i < n; ++i) {  // unary_i(s) = w_u · f_u(i, s)
    const int count = candidates.count (i);
    auto&& u = unaryOf (chain, i);
    u.head (count) = weights (kDataMargin) * scores.data_margins.segment (candidates.offsets[i], count);
    u (count) = weights (kOutlierMargin) * scores.outlier_margins (i) + weights (kOutlierBias);
  }
  const double* w_p = weights.data () + kUnaryFeatureCount;
  const double squared_scale = residual_scale * residual_scale;
  for (int i = 0; i + 1 < n; ++i) {  // pairwise_i(s, t) = w_p · f_p(i, s, t)
    const SourceStep step = sourceStep (source, pass, i);
    const int count = candidates.count (i), count_next = candidates.count (i + 1);
    const int* j = candidates.targets.data () + candidates.offsets[i];
    const int* j_next = candidates.targets.data () + candidates.offsets[i + 1];
    auto&& p = pairwiseOf (chain, i);
    for (int t = 0; t < count_next; ++t) {
      for (int s = 0; s < count; ++s)
        p (s, t) = inlierPairPotential (j[s], j_next[t], step, target.points, squared_scale, w_p);
      p (count, t) = w_p[kOutlierSwitch];  // outlier → candidate
    }
    p.col (count_next).head (count).setConstant (w_p[kOutlierSwitch]);  // candidate → outlier
    p (count, count_next) = w_p[kOutlierRun];
  }
}

}  // namespace

crf::ChainPotentials
matchingChainPotentials (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                         const BoostedScores& scores, const Eigen::VectorXd& weights, double residual_scale)
{
  crf::ChainPotentials chain;
  fillMatchingChain (source, target, pass, scores, weights, residual_scale, chain);
  return chain;
}

void
matchingChainPotentials (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                         const BoostedScores& scores, const Eigen::VectorXd& weights, double residual_scale,
                         crf::PackedChainPotentials& chain)
{
  fillMatchingChain (source, target, pass, scores, weights, residual_scale, chain);
}

}  // namespace matching
}  // namespace pcl_crf
