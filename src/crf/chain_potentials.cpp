#include <pcl_crf/crf/chain_potentials.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
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

template <typename Vector> void
validateNode (const Vector& unary, std::size_t i)
{
  if (unary.size () == 0)
    fail ("node " + std::to_string (i) + " has zero states");
  if (hasNanOrPositiveInfinity (unary))
    fail ("node " + std::to_string (i) + " has a NaN or +inf unary log-potential");
  if (!std::isfinite (unary.maxCoeff ()))
    fail ("node " + std::to_string (i) + " has every state forbidden (all unary log-potentials are -inf)");
}

template <typename Matrix> void
validateEdgeValues (const Matrix& pairwise, std::size_t i)
{
  if (hasNanOrPositiveInfinity (pairwise))
    fail ("edge " + std::to_string (i) + " has a NaN or +inf pairwise log-potential");
}

void
validateEdge (const Eigen::MatrixXd& pairwise, const ChainPotentials& chain, std::size_t i)
{
  if (pairwise.rows () != chain.unary[i].size () || pairwise.cols () != chain.unary[i + 1].size ())
    fail ("edge " + std::to_string (i) + " is " + std::to_string (pairwise.rows ()) + "x" +
          std::to_string (pairwise.cols ()) + " but nodes " + std::to_string (i) + " and " + std::to_string (i + 1) +
          " have " + std::to_string (chain.unary[i].size ()) + " and " + std::to_string (chain.unary[i + 1].size ()) +
          " states");
  validateEdgeValues (pairwise, i);
}

[[noreturn]] void
failLabels (std::size_t labels, std::size_t nodes)
{
  fail ("score: " + std::to_string (labels) + " labels for " + std::to_string (nodes) + " nodes");
}

[[noreturn]] void
failLabel (int label, std::size_t i)
{
  fail ("score: label " + std::to_string (label) + " of node " + std::to_string (i) + " is out of range");
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
    failLabels (labels.size (), unary.size ());
  double total = 0.0;
  for (std::size_t i = 0; i < labels.size (); ++i)
  {
    if (labels[i] < 0 || labels[i] >= unary[i].size ())
      failLabel (labels[i], i);
    total += unary[i] (labels[i]);
    if (i > 0)
      total += pairwise[i - 1] (labels[i - 1], labels[i]);
  }
  return total;
}

void
PackedChainPotentials::clear ()
{
  states_.clear ();
  unary_offset_.clear ();
  pairwise_offset_.clear ();
  unary_.clear ();
  pairwise_.clear ();
}

void
PackedChainPotentials::reserve (std::size_t nodes, std::size_t unary_entries, std::size_t pairwise_entries)
{
  states_.reserve (nodes);
  unary_offset_.reserve (nodes);
  pairwise_offset_.reserve (nodes);
  unary_.reserve (unary_entries);
  pairwise_.reserve (pairwise_entries);
}

void
PackedChainPotentials::addNode (int states)
{
  if (states < 1)
    fail ("node " + std::to_string (states_.size ()) + " has zero states");
  if (!states_.empty ())
  {
    pairwise_offset_.push_back (pairwise_.size ());
    pairwise_.resize (pairwise_.size () + static_cast<std::size_t> (states_.back ()) * states, 0.0);
  }
  unary_offset_.push_back (unary_.size ());
  unary_.resize (unary_.size () + static_cast<std::size_t> (states), 0.0);
  states_.push_back (states);
}

void
PackedChainPotentials::assign (const ChainPotentials& chain)
{
  clear ();
  std::size_t unary_entries = 0, pairwise_entries = 0;
  for (std::size_t i = 0; i < chain.size (); ++i)
  {
    unary_entries += static_cast<std::size_t> (chain.unary[i].size ());
    if (i + 1 < chain.size ())
      pairwise_entries += static_cast<std::size_t> (chain.unary[i].size () * chain.unary[i + 1].size ());
  }
  reserve (chain.size (), unary_entries, pairwise_entries);
  for (std::size_t i = 0; i < chain.size (); ++i)
  {
    addNode (chain.states (i));
    unary (i) = chain.unary[i];
    if (i > 0)
      pairwise (i - 1) = chain.pairwise[i - 1];
  }
}

void
PackedChainPotentials::validate () const
{
  // One branch-free pass over each buffer; the node or edge at fault is searched only on failure.
  const auto invalid = [] (const std::vector<double>& values) {
    int count = 0;  // !(x <= max): NaN or +∞
    for (const double x : values)
      count += !(x <= std::numeric_limits<double>::max ());
    return count != 0;
  };
  if (invalid (unary_))
    for (std::size_t i = 0; i < size (); ++i)
      validateNode (unary (i), i);
  if (invalid (pairwise_))
    for (std::size_t i = 0; i + 1 < size (); ++i)
      validateEdgeValues (pairwise (i), i);
  for (std::size_t i = 0; i < size (); ++i)
  {
    const double* u = unary_.data () + unary_offset_[i];
    if (std::all_of (u, u + states_[i], [] (double x) { return x == -std::numeric_limits<double>::infinity (); }))
      validateNode (unary (i), i);
  }
}

double
PackedChainPotentials::score (const std::vector<int>& labels) const
{
  if (labels.size () != size ())
    failLabels (labels.size (), size ());
  double total = 0.0;
  for (std::size_t i = 0; i < labels.size (); ++i)
  {
    if (labels[i] < 0 || labels[i] >= states (i))
      failLabel (labels[i], i);
    total += unary (i) (labels[i]);
    if (i > 0)
      total += pairwise (i - 1) (labels[i - 1], labels[i]);
  }
  return total;
}

}  // namespace crf
}  // namespace pcl_crf
