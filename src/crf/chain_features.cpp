#include <pcl_crf/crf/chain_features.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& method, const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::" + method + "] " + what);
}

void
validateNode (const ChainFeatures& f, std::size_t i)
{
  const std::string node = "node " + std::to_string (i);
  if (f.unary[i].rows () == 0)
    fail ("ChainFeatures::validate", node + " has zero states");
  if (f.unary[i].cols () != f.unaryDimension ())
    fail ("ChainFeatures::validate", node + " has " + std::to_string (f.unary[i].cols ()) +
                                         " unary features, node 0 has " + std::to_string (f.unaryDimension ()));
  if (!f.unary[i].allFinite ())
    fail ("ChainFeatures::validate", node + " has a non-finite unary feature");
}

void
validateEdge (const ChainFeatures& f, std::size_t i)
{
  const std::string edge = "edge " + std::to_string (i);
  const Eigen::Index rows = f.unary[i].rows () * f.unary[i + 1].rows ();
  if (f.pairwise[i].rows () != rows)
    fail ("ChainFeatures::validate", edge + " has " + std::to_string (f.pairwise[i].rows ()) +
                                         " rows, expected S_i * S_{i+1} = " + std::to_string (rows));
  if (f.pairwise[i].cols () != f.pairwiseDimension ())
    fail ("ChainFeatures::validate", edge + " has " + std::to_string (f.pairwise[i].cols ()) +
                                         " pairwise features, edge 0 has " +
                                         std::to_string (f.pairwiseDimension ()));
  if (!f.pairwise[i].allFinite ())
    fail ("ChainFeatures::validate", edge + " has a non-finite pairwise feature");
}

}  // namespace

void
ChainFeatures::validate () const
{
  const std::size_t n = unary.size ();
  const std::size_t expected_edges = n == 0 ? 0 : n - 1;
  if (pairwise.size () != expected_edges)
    fail ("ChainFeatures::validate", "a chain of " + std::to_string (n) + " nodes needs " +
                                         std::to_string (expected_edges) + " pairwise matrices, got " +
                                         std::to_string (pairwise.size ()));
  for (std::size_t i = 0; i < n; ++i)
    validateNode (*this, i);
  for (std::size_t i = 0; i < expected_edges; ++i)
    validateEdge (*this, i);
}

ChainPotentials
potentials (const ChainFeatures& features, const Eigen::VectorXd& weights)
{
  features.validate ();
  const Eigen::Index d_u = features.unaryDimension ();
  const Eigen::Index d_p = features.pairwise.empty () ? weights.size () - d_u : features.pairwiseDimension ();
  if (d_p < 0 || weights.size () != d_u + d_p)
    fail ("potentials", std::to_string (weights.size ()) + " weights for " + std::to_string (d_u) +
                            " unary + " + std::to_string (d_p) + " pairwise features");
  const auto w_u = weights.head (d_u);
  const auto w_p = weights.tail (d_p);

  ChainPotentials chain;
  chain.unary.reserve (features.size ());
  for (const Eigen::MatrixXd& f_u : features.unary)
    chain.unary.push_back (f_u * w_u);  // unary_i(s) = w_u · f_u(i, s)
  chain.pairwise.reserve (features.pairwise.size ());
  for (std::size_t i = 0; i < features.pairwise.size (); ++i)
  {
    const Eigen::VectorXd flat = features.pairwise[i] * w_p;  // pairwise_i(s, t) = w_p · f_p(i, s, t)
    chain.pairwise.push_back (Eigen::Map<const Eigen::MatrixXd> (flat.data (), features.states (i),
                                                                 features.states (i + 1)));
  }
  return chain;
}

}  // namespace crf
}  // namespace pcl_crf
