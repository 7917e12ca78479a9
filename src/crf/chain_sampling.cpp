#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <cmath>
#include <stdexcept>

namespace pcl_crf {
namespace crf {

namespace {

/** Draws an index k with probability ∝ exp(log_weights(k)). */
int
drawFromLogWeights (const Eigen::VectorXd& log_weights, std::mt19937& rng)
{
  const Eigen::VectorXd p = normalizedExp (log_weights);
  const double u = std::uniform_real_distribution<double> (0.0, 1.0) (rng);
  double cumulative = 0.0;
  for (Eigen::Index k = 0; k < p.size (); ++k)
  {
    cumulative += p (k);
    if (u < cumulative)
      return static_cast<int> (k);
  }
  // Rounding left u above the last cumulative sum: return the last allowed state.
  Eigen::Index last = p.size () - 1;
  while (last > 0 && p (last) == 0.0)
    --last;
  return static_cast<int> (last);
}

}  // namespace

std::vector<int>
sampleChain (const ChainPotentials& chain, std::mt19937& rng)
{
  chain.validate ();
  const std::size_t n = chain.size ();
  std::vector<int> labels (n);
  if (n == 0)
    return labels;
  const std::vector<Eigen::VectorXd> alpha = forwardMessages (chain);
  if (!std::isfinite (logSumExp (alpha[n - 1])))
    throw std::invalid_argument ("[pcl_crf::crf::sampleChain] every labelling of the chain is forbidden");

  // y_{n−1} ~ exp(α_{n−1}); then y_i | y_{i+1} ~ exp(α_i(s) + P_i(s, y_{i+1})).
  labels[n - 1] = drawFromLogWeights (alpha[n - 1], rng);
  for (std::size_t i = n - 1; i > 0; --i)
    labels[i - 1] = drawFromLogWeights (alpha[i - 1] + chain.pairwise[i - 1].col (labels[i]), rng);
  return labels;
}

}  // namespace crf
}  // namespace pcl_crf
