#include <pcl_crf/crf/node_pseudo_likelihood.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::learnNodePseudoLikelihood] " + what);
}

void
validate (const std::vector<NodeConditional>& nodes, double prior_sigma)
{
  if (nodes.empty ())
    fail ("no training node");
  if (!(prior_sigma > 0.0))
    fail ("prior_sigma must be > 0 (+inf: no prior)");
  const Eigen::Index dimension = nodes.front ().features.cols ();
  if (dimension < 1)
    fail ("the features have no column");
  for (std::size_t v = 0; v < nodes.size (); ++v) {
    const NodeConditional& node = nodes[v];
    const std::string name = "node " + std::to_string (v);
    if (node.features.cols () != dimension)
      fail (name + " has " + std::to_string (node.features.cols ()) + " features, expected " +
            std::to_string (dimension));
    if (node.label < 0 || node.label >= node.features.rows ())
      fail (name + ": label " + std::to_string (node.label) + " is out of range");
    if (!node.features.allFinite ())
      fail (name + " has non-finite features");
  }
}

/** −log p(y_v | blanket) of one node; adds its gradient F^T p − f(y) to \a gradient. */
double
nodeTerm (const NodeConditional& node, const Eigen::VectorXd& w, Eigen::VectorXd& gradient)
{
  const Eigen::VectorXd scores = node.features * w;
  const double top = scores.maxCoeff ();
  const Eigen::VectorXd p = (scores.array () - top).exp ().matrix ();
  const double sum = p.sum ();
  gradient.noalias () += node.features.transpose () * (p / sum);
  gradient -= node.features.row (node.label).transpose ();
  return top + std::log (sum) - scores (node.label);
}

}  // namespace

double
nodePseudoLikelihoodObjective (const std::vector<NodeConditional>& nodes, double prior_sigma,
                               const Eigen::VectorXd& w, Eigen::VectorXd& gradient)
{
  gradient = Eigen::VectorXd::Zero (w.size ());
  double value = 0.0;
  for (const NodeConditional& node : nodes)
    value += nodeTerm (node, w, gradient);
  if (std::isfinite (prior_sigma)) {
    const double precision = 1.0 / (prior_sigma * prior_sigma);
    value += 0.5 * precision * w.squaredNorm ();
    gradient += precision * w;
  }
  return value;
}

LbfgsResult
learnNodePseudoLikelihood (const std::vector<NodeConditional>& nodes, double prior_sigma, const LbfgsOptions& options)
{
  validate (nodes, prior_sigma);
  const Objective objective = [&nodes, prior_sigma] (const Eigen::VectorXd& w, Eigen::VectorXd& gradient) {
    return nodePseudoLikelihoodObjective (nodes, prior_sigma, w, gradient);
  };
  return minimizeLbfgs (objective, Eigen::VectorXd::Zero (nodes.front ().features.cols ()), options);
}

}  // namespace crf
}  // namespace pcl_crf
