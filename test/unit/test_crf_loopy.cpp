#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/loopy_belief_propagation.h>

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>

namespace {

using pcl_crf::crf::LoopyMode;
using pcl_crf::crf::LoopyOptions;
using pcl_crf::crf::PairwiseGraph;

Eigen::MatrixXd
randomMatrix (Eigen::Index rows, Eigen::Index cols, double scale, std::mt19937& rng)
{
  std::normal_distribution<double> value (0.0, scale);
  return Eigen::MatrixXd::NullaryExpr (rows, cols, [&] () { return value (rng); });
}

/** The same chain as a ChainPotentials and as a PairwiseGraph. */
void
randomChainBothWays (int n, std::mt19937& rng, pcl_crf::crf::ChainPotentials& chain, PairwiseGraph& graph)
{
  std::uniform_int_distribution<int> states (2, 4);
  for (int i = 0; i < n; ++i)
    chain.unary.push_back (randomMatrix (states (rng), 1, 1.5, rng));
  for (int i = 0; i + 1 < n; ++i)
    chain.pairwise.push_back (randomMatrix (chain.unary[i].size (), chain.unary[i + 1].size (), 1.5, rng));
  graph.unary = chain.unary;
  for (int i = 0; i + 1 < n; ++i)
  {
    // Write every other edge reversed (b, a) to exercise both message directions.
    if (i % 2 == 0)
      graph.edges.push_back ({i, i + 1, chain.pairwise[i]});
    else
      graph.edges.push_back ({i + 1, i, chain.pairwise[i].transpose ()});
  }
}

/** Brute-force MAP of a small graph. */
std::vector<int>
bruteForceMap (const PairwiseGraph& graph)
{
  std::vector<int> labels (graph.unary.size (), 0), best;
  double best_score = -std::numeric_limits<double>::infinity ();
  while (true)
  {
    double score = 0.0;
    for (std::size_t v = 0; v < labels.size (); ++v)
      score += graph.unary[v] (labels[v]);
    for (const auto& e : graph.edges)
      score += e.log_potential (labels[e.a], labels[e.b]);
    if (score > best_score)
      best_score = score, best = labels;
    std::size_t v = 0;
    while (v < labels.size () && ++labels[v] == graph.unary[v].size ())
      labels[v++] = 0;
    if (v == labels.size ())
      return best;
  }
}

TEST (LoopyBeliefPropagation, SumProductOnChainIsExact)
{
  std::mt19937 rng (5);
  pcl_crf::crf::ChainPotentials chain;
  PairwiseGraph graph;
  randomChainBothWays (12, rng, chain, graph);
  const auto exact = pcl_crf::crf::sumProduct (chain);
  const auto loopy = pcl_crf::crf::loopyBeliefPropagation (graph, LoopyOptions ());
  EXPECT_TRUE (loopy.converged);
  EXPECT_LE (loopy.iterations, 13);  // a tree converges in diameter + 1 sweeps
  for (std::size_t i = 0; i < chain.size (); ++i)
    EXPECT_LT ((loopy.beliefs[i] - exact.node_marginals[i]).cwiseAbs ().maxCoeff (), 1e-8);
}

TEST (LoopyBeliefPropagation, ForbiddenTransitionsWithDampingOnChainAreExact)
{
  std::mt19937 rng (15);
  pcl_crf::crf::ChainPotentials chain;
  PairwiseGraph graph;
  randomChainBothWays (8, rng, chain, graph);
  const double forbidden = -std::numeric_limits<double>::infinity ();
  chain.pairwise[3].col (0).setConstant (forbidden);  // node 4 can never take state 0
  graph.edges[3].log_potential = chain.pairwise[3].transpose ();  // edge 3 is stored reversed
  LoopyOptions options;
  options.damping = 0.3;
  options.tolerance = 1e-12;
  options.max_iterations = 500;
  const auto exact = pcl_crf::crf::sumProduct (chain);
  const auto loopy = pcl_crf::crf::loopyBeliefPropagation (graph, options);
  EXPECT_TRUE (loopy.converged);
  EXPECT_EQ (loopy.beliefs[4] (0), 0.0);
  for (std::size_t i = 0; i < chain.size (); ++i)
    EXPECT_LT ((loopy.beliefs[i] - exact.node_marginals[i]).cwiseAbs ().maxCoeff (), 1e-9);
}

TEST (LoopyBeliefPropagation, MaxProductOnChainMatchesViterbi)
{
  std::mt19937 rng (6);
  for (int trial = 0; trial < 10; ++trial)
  {
    pcl_crf::crf::ChainPotentials chain;
    PairwiseGraph graph;
    randomChainBothWays (10, rng, chain, graph);
    LoopyOptions options;
    options.mode = LoopyMode::MaxProduct;
    const auto loopy = pcl_crf::crf::loopyBeliefPropagation (graph, options);
    EXPECT_TRUE (loopy.converged);
    EXPECT_EQ (loopy.labels, pcl_crf::crf::maxProduct (chain).labels) << "trial " << trial;
  }
}

TEST (LoopyBeliefPropagation, SmallLoopMatchesBruteForceMap)
{
  // A 3x3 grid (4 loops), 3 states: informative unaries plus attractive Potts edges.
  std::mt19937 rng (9);
  PairwiseGraph graph;
  for (int v = 0; v < 9; ++v)
    graph.unary.push_back (randomMatrix (3, 1, 2.0, rng));
  const Eigen::MatrixXd potts = Eigen::MatrixXd::Identity (3, 3) * 1.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
    {
      if (c < 2)
        graph.edges.push_back ({3 * r + c, 3 * r + c + 1, potts});
      if (r < 2)
        graph.edges.push_back ({3 * r + c, 3 * (r + 1) + c, potts});
    }
  LoopyOptions options;
  options.mode = LoopyMode::MaxProduct;
  options.damping = 0.5;
  options.max_iterations = 200;
  const auto loopy = pcl_crf::crf::loopyBeliefPropagation (graph, options);
  EXPECT_TRUE (loopy.converged);
  EXPECT_EQ (loopy.labels, bruteForceMap (graph));
  for (const auto& b : loopy.beliefs)
    EXPECT_NEAR (b.sum (), 1.0, 1e-12);

  options.mode = LoopyMode::SumProduct;
  const auto marginals = pcl_crf::crf::loopyBeliefPropagation (graph, options);
  EXPECT_TRUE (marginals.converged);
}

TEST (LoopyBeliefPropagation, GraphWithoutEdgesGivesNormalisedUnaries)
{
  PairwiseGraph graph;
  graph.unary = {Eigen::Vector2d (0.0, std::log (3.0))};
  const auto r = pcl_crf::crf::loopyBeliefPropagation (graph);
  EXPECT_TRUE (r.converged);
  EXPECT_EQ (r.iterations, 0);
  EXPECT_NEAR (r.beliefs[0] (1), 0.75, 1e-12);
  EXPECT_EQ (r.labels[0], 1);
}

TEST (LoopyBeliefPropagation, RejectsInvalidGraphsAndOptions)
{
  PairwiseGraph graph;
  graph.unary = {Eigen::VectorXd::Zero (2), Eigen::VectorXd::Zero (3)};
  graph.edges = {{0, 1, Eigen::MatrixXd::Zero (2, 3)}};
  EXPECT_NO_THROW (pcl_crf::crf::loopyBeliefPropagation (graph));
  auto bad = graph;
  bad.edges[0].b = 2;  // out of range
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (bad), std::invalid_argument);
  bad = graph;
  bad.edges[0].b = 0;  // self loop
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (bad), std::invalid_argument);
  bad = graph;
  bad.edges[0].log_potential = Eigen::MatrixXd::Zero (3, 2);  // size mismatch
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (bad), std::invalid_argument);
  bad = graph;
  bad.unary[1] (2) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (bad), std::invalid_argument);
  LoopyOptions options;
  options.damping = 1.0;
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (graph, options), std::invalid_argument);
  options = LoopyOptions ();
  options.max_iterations = 0;
  EXPECT_THROW (pcl_crf::crf::loopyBeliefPropagation (graph, options), std::invalid_argument);
}

}  // namespace
