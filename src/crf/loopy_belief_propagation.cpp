#include <pcl_crf/crf/loopy_belief_propagation.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

/** A message arriving at a node: from edge \c edge, stored in to_b (at_b) or to_a. */
struct Incoming
{
  int edge;
  bool at_b;
};

/** node v: the messages arriving at v. */
using Incidence = std::vector<std::vector<Incoming>>;

/** Log-domain messages of every edge in both directions. */
struct Messages
{
  std::vector<Eigen::VectorXd> to_b;  // edge e: message a → b, size S_b
  std::vector<Eigen::VectorXd> to_a;  // edge e: message b → a, size S_a

  const Eigen::VectorXd&
  at (const Incoming& in) const { return in.at_b ? to_b[in.edge] : to_a[in.edge]; }
};

void
validateOptions (const LoopyOptions& options)
{
  const std::string where = "[pcl_crf::crf::loopyBeliefPropagation] ";
  if (options.max_iterations < 1)
    throw std::invalid_argument (where + "max_iterations must be >= 1");
  if (!(options.damping >= 0.0 && options.damping < 1.0))
    throw std::invalid_argument (where + "damping must be in [0, 1)");
  if (!(options.tolerance >= 0.0))
    throw std::invalid_argument (where + "tolerance must be >= 0");
}

Incidence
incidence (const PairwiseGraph& graph)
{
  Incidence incoming (graph.unary.size ());
  for (std::size_t e = 0; e < graph.edges.size (); ++e)
  {
    incoming[graph.edges[e].b].push_back ({static_cast<int> (e), true});
    incoming[graph.edges[e].a].push_back ({static_cast<int> (e), false});
  }
  return incoming;
}

/** Uniform messages (log 1 = 0). */
Messages
initialMessages (const PairwiseGraph& graph)
{
  Messages messages;
  for (const PairwiseGraph::Edge& edge : graph.edges)
  {
    messages.to_b.push_back (Eigen::VectorXd::Zero (graph.unary[edge.b].size ()));
    messages.to_a.push_back (Eigen::VectorXd::Zero (graph.unary[edge.a].size ()));
  }
  return messages;
}

/** u_v + Σ incoming messages, leaving out the one that came along (skip_edge, skip_at_b). */
Eigen::VectorXd
cavity (const PairwiseGraph& graph, const Incidence& incoming, const Messages& messages, int v, int skip_edge,
        bool skip_at_b)
{
  Eigen::VectorXd sum = graph.unary[v];
  for (const Incoming& in : incoming[v])
    if (in.edge != skip_edge || in.at_b != skip_at_b)
      sum += messages.at (in);
  return sum;
}

/** Normalises a log-message to log-sum 0 (sum-product) or max 0 (max-product). */
void
normalize (Eigen::VectorXd& message, LoopyMode mode)
{
  const double norm = mode == LoopyMode::SumProduct ? logSumExp (message) : message.maxCoeff ();
  if (std::isfinite (norm))
    message.array () -= norm;
}

/** m_{a→b}(t) = ⊕_s [cavity_a(s) + P(s, t)] or m_{b→a}(s) = ⊕_t [P(s, t) + cavity_b(t)]. */
Eigen::VectorXd
sendMessage (const Eigen::MatrixXd& potential, const Eigen::VectorXd& cavity_sender, bool to_b, LoopyMode mode)
{
  const bool sum = mode == LoopyMode::SumProduct;
  Eigen::VectorXd message = to_b ? (sum ? logVectorMatrix (cavity_sender, potential)
                                        : maxVectorMatrix (cavity_sender, potential))
                                 : (sum ? logMatrixVector (potential, cavity_sender)
                                        : maxMatrixVector (potential, cavity_sender));
  normalize (message, mode);
  return message;
}

/** Damps the new message against the old one in the probability domain and returns
 *  the largest change of a (normalised) probability-domain entry. A forbidden entry
 *  (−∞, from hard constraints) is not damped: it stays exactly −∞. */
double
dampAndMeasure (Eigen::VectorXd& fresh, const Eigen::VectorXd& old, const LoopyOptions& options)
{
  if (options.damping > 0.0)
  {
    Eigen::ArrayXd mixed =
        (1.0 - options.damping) * safeExp (fresh.array ()) + options.damping * safeExp (old.array ());
    for (Eigen::Index k = 0; k < mixed.size (); ++k)
      mixed (k) = fresh (k) == kLogZero ? 0.0 : mixed (k);
    fresh = mixed.log ().matrix ();
    normalize (fresh, options.mode);
  }
  return (safeExp (fresh.array ()) - safeExp (old.array ())).abs ().maxCoeff ();
}

/** One flooding sweep: every message recomputed from the previous sweep's messages. */
double
floodingSweep (const PairwiseGraph& graph, const Incidence& incoming, Messages& messages,
               const LoopyOptions& options)
{
  Messages next = messages;
  double change = 0.0;
  for (std::size_t e = 0; e < graph.edges.size (); ++e)
  {
    const PairwiseGraph::Edge& edge = graph.edges[e];
    const int id = static_cast<int> (e);
    const Eigen::VectorXd cavity_a = cavity (graph, incoming, messages, edge.a, id, false);
    const Eigen::VectorXd cavity_b = cavity (graph, incoming, messages, edge.b, id, true);
    next.to_b[e] = sendMessage (edge.log_potential, cavity_a, true, options.mode);
    next.to_a[e] = sendMessage (edge.log_potential, cavity_b, false, options.mode);
    change = std::max (change, dampAndMeasure (next.to_b[e], messages.to_b[e], options));
    change = std::max (change, dampAndMeasure (next.to_a[e], messages.to_a[e], options));
  }
  messages = std::move (next);
  return change;
}

/** b_v ∝ exp(u_v + Σ incoming messages); labels = argmax b_v. */
void
fillBeliefs (const PairwiseGraph& graph, const Incidence& incoming, const Messages& messages, LoopyResult& result)
{
  const std::size_t n = graph.unary.size ();
  result.beliefs.resize (n);
  result.labels.resize (n);
  for (std::size_t v = 0; v < n; ++v)
  {
    const Eigen::VectorXd log_belief = cavity (graph, incoming, messages, static_cast<int> (v), -1, false);
    Eigen::Index best = 0;
    if (!std::isfinite (log_belief.maxCoeff (&best)))
      throw std::invalid_argument ("[pcl_crf::crf::loopyBeliefPropagation] every state of node " +
                                   std::to_string (v) + " is forbidden");
    result.beliefs[v] = normalizedExp (log_belief);
    result.labels[v] = static_cast<int> (best);
  }
}

}  // namespace

LoopyResult
loopyBeliefPropagation (const PairwiseGraph& graph, const LoopyOptions& options)
{
  graph.validate ();
  validateOptions (options);
  const Incidence incoming = incidence (graph);
  Messages messages = initialMessages (graph);
  LoopyResult result;
  result.converged = graph.edges.empty ();
  while (!result.converged && result.iterations < options.max_iterations)
  {
    const double change = floodingSweep (graph, incoming, messages, options);
    ++result.iterations;
    result.converged = change <= options.tolerance;
  }
  fillBeliefs (graph, incoming, messages, result);
  return result;
}

}  // namespace crf
}  // namespace pcl_crf
