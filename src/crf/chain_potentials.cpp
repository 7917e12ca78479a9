#include <pcl_crf/crf/chain_potentials.h>
#include <pcl_crf/crf/log_space.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::ChainPotentials] " + what);
}

/** NaN or +∞ anywhere? −∞ (forbidden) is allowed. */
// The messages name the node or edge; they are built only on failure (validation runs
// before every inference, on chains of hundreds of nodes).

void
validateNode (const Eigen::VectorXd& unary, std::size_t i)
{
  if (unary.size () == 0)
    fail ("node " + std::to_string (i) + " has zero states");
  if (hasNanOrPositiveInfinity (unary))
    fail ("node " + std::to_string (i) + " has a NaN or +inf unary log-potential");
  if (!std::isfinite (unary.maxCoeff ()))
    fail ("node " + std::to_string (i) + " has every state forbidden (all unary log-potentials are -inf)");
}

void
validateEdge (const Eigen::MatrixXd& pairwise, const ChainPotentials& chain, std::size_t i)
{
  if (pairwise.rows () != chain.unary[i].size () || pairwise.cols () != chain.unary[i + 1].size ())
    fail ("edge " + std::to_string (i) + " is " + std::to_string (pairwise.rows ()) + "x" +
          std::to_string (pairwise.cols ()) + " but nodes " + std::to_string (i) + " and " + std::to_string (i + 1) +
          " have " + std::to_string (chain.unary[i].size ()) + " and " + std::to_string (chain.unary[i + 1].size ()) +
          " states");
  if (hasNanOrPositiveInfinity (pairwise))
    fail ("edge " + std::to_string (i) + " has a NaN or +inf pairwise log-potential");
}

}  // namespace

void
ChainPotentials::validate () const
{
  const std::size_t n = unary.size ();
  const std::size_t expected_edges = n == 0 ? 0 : n - 1;
  if (pairwise.size () != expected_edges)
    fail ("a chain of " + std::to_string (n) + " nodes needs " + std::to_string (expected_edges) +
          " pairwise matrices, got " + std::to_string (pairwise.size ()));
  for (std::size_t i = 0; i < n; ++i)
    validateNode (unary[i], i);
  for (std::size_t i = 0; i < expected_edges; ++i)
    validateEdge (pairwise[i], *this, i);
}

double
ChainPotentials::score (const std::vector<int>& labels) const
{
  if (labels.size () != unary.size ())
    fail ("score: " + std::to_string (labels.size ()) + " labels for " + std::to_string (unary.size ()) +
          " nodes");
  double total = 0.0;
  for (std::size_t i = 0; i < labels.size (); ++i)
  {
    if (labels[i] < 0 || labels[i] >= unary[i].size ())
      fail ("score: label " + std::to_string (labels[i]) + " of node " + std::to_string (i) +
            " is out of range");
    total += unary[i] (labels[i]);
    if (i > 0)
      total += pairwise[i - 1] (labels[i - 1], labels[i]);
  }
  return total;
}

}  // namespace crf
}  // namespace pcl_crf
