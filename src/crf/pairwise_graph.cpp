#include <pcl_crf/crf/loopy_belief_propagation.h>
#include <pcl_crf/crf/log_space.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::PairwiseGraph::validate] " + what);
}

void
validateEdge (const PairwiseGraph::Edge& edge, std::size_t e, const std::vector<Eigen::VectorXd>& unary)
{
  const std::string name = "edge " + std::to_string (e) + " (" + std::to_string (edge.a) + ", " +
                           std::to_string (edge.b) + ")";
  const int n = static_cast<int> (unary.size ());
  if (edge.a < 0 || edge.a >= n || edge.b < 0 || edge.b >= n)
    fail (name + " names a node outside [0, " + std::to_string (n) + ")");
  if (edge.a == edge.b)
    fail (name + " is a self loop");
  if (edge.log_potential.rows () != unary[edge.a].size () || edge.log_potential.cols () != unary[edge.b].size ())
    fail (name + " has a " + std::to_string (edge.log_potential.rows ()) + "x" +
          std::to_string (edge.log_potential.cols ()) + " potential but its nodes have " +
          std::to_string (unary[edge.a].size ()) + " and " + std::to_string (unary[edge.b].size ()) + " states");
  if (hasNanOrPositiveInfinity (edge.log_potential))
    fail (name + " has a NaN or +inf log-potential");
}

}  // namespace

void
PairwiseGraph::validate () const
{
  for (std::size_t v = 0; v < unary.size (); ++v)
  {
    if (unary[v].size () == 0)
      fail ("node " + std::to_string (v) + " has zero states");
    if (hasNanOrPositiveInfinity (unary[v]))
      fail ("node " + std::to_string (v) + " has a NaN or +inf unary log-potential");
  }
  for (std::size_t e = 0; e < edges.size (); ++e)
    validateEdge (edges[e], e, unary);
}

}  // namespace crf
}  // namespace pcl_crf
