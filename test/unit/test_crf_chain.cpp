#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pcl_crf::crf::ChainPotentials;

/** Random chain with per-node state counts in [min_states, max_states] and N(0, scale²) potentials. */
ChainPotentials
randomChain (int n, int min_states, int max_states, double scale, std::mt19937& rng)
{
  std::uniform_int_distribution<int> states (min_states, max_states);
  std::normal_distribution<double> value (0.0, scale);
  ChainPotentials chain;
  for (int i = 0; i < n; ++i)
  {
    Eigen::VectorXd u (states (rng));
    for (Eigen::Index s = 0; s < u.size (); ++s)
      u (s) = value (rng);
    chain.unary.push_back (u);
  }
  for (int i = 0; i + 1 < n; ++i)
  {
    Eigen::MatrixXd p (chain.unary[i].size (), chain.unary[i + 1].size ());
    for (Eigen::Index k = 0; k < p.size (); ++k)
      p (k) = value (rng);
    chain.pairwise.push_back (p);
  }
  return chain;
}

/** Calls visit (labels) for every labelling of the chain (mixed-radix counter). */
template <typename Visit> void
enumerate (const ChainPotentials& chain, Visit visit)
{
  std::vector<int> labels (chain.size (), 0);
  while (true)
  {
    visit (labels);
    std::size_t i = 0;
    while (i < labels.size () && ++labels[i] == chain.states (i))
      labels[i++] = 0;
    if (i == labels.size ())
      return;
  }
}

struct BruteForce
{
  std::vector<int> map_labels;
  double map_score = -std::numeric_limits<double>::infinity ();
  double log_partition = 0.0;
  std::vector<Eigen::VectorXd> node;
  std::vector<Eigen::MatrixXd> edge;
};

BruteForce
bruteForce (const ChainPotentials& chain)
{
  BruteForce b;
  double z = 0.0;
  for (std::size_t i = 0; i < chain.size (); ++i)
    b.node.push_back (Eigen::VectorXd::Zero (chain.states (i)));
  for (const auto& p : chain.pairwise)
    b.edge.push_back (Eigen::MatrixXd::Zero (p.rows (), p.cols ()));
  enumerate (chain, [&] (const std::vector<int>& y) {
    const double score = chain.score (y);
    if (score > b.map_score)
      b.map_score = score, b.map_labels = y;
    const double weight = std::exp (score);
    z += weight;
    for (std::size_t i = 0; i < y.size (); ++i)
      b.node[i] (y[i]) += weight;
    for (std::size_t i = 0; i + 1 < y.size (); ++i)
      b.edge[i] (y[i], y[i + 1]) += weight;
  });
  b.log_partition = std::log (z);
  for (auto& m : b.node)
    m /= z;
  for (auto& m : b.edge)
    m /= z;
  return b;
}

TEST (ChainPotentials, ValidateNamesTheProblem)
{
  ChainPotentials chain;
  chain.unary = {Eigen::VectorXd::Zero (2), Eigen::VectorXd::Zero (3)};
  EXPECT_THROW (chain.validate (), std::invalid_argument);  // no pairwise matrix
  chain.pairwise = {Eigen::MatrixXd::Zero (3, 2)};
  try
  {
    chain.validate ();
    FAIL () << "size mismatch not detected";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("edge 0"), std::string::npos) << e.what ();
  }
  chain.pairwise = {Eigen::MatrixXd::Zero (2, 3)};
  EXPECT_NO_THROW (chain.validate ());
  chain.pairwise[0] (1, 2) = pcl_crf::crf::kLogZero;  // forbidden transitions are fine
  EXPECT_NO_THROW (chain.validate ());
  chain.pairwise[0] (0, 0) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (chain.validate (), std::invalid_argument);
  chain.pairwise[0] (0, 0) = std::numeric_limits<double>::infinity ();
  EXPECT_THROW (chain.validate (), std::invalid_argument);
  chain.pairwise[0] (0, 0) = 0.0;
  chain.unary[1] = Eigen::VectorXd ();
  EXPECT_THROW (chain.validate (), std::invalid_argument);  // zero states
}

TEST (ChainInference, MaxProductMatchesBruteForce)
{
  std::mt19937 rng (42);
  for (int trial = 0; trial < 30; ++trial)
  {
    const ChainPotentials chain = randomChain (5, 2, 4, 2.0, rng);
    const BruteForce truth = bruteForce (chain);
    const pcl_crf::crf::MapResult map = pcl_crf::crf::maxProduct (chain);
    EXPECT_EQ (map.labels, truth.map_labels) << "trial " << trial;
    EXPECT_NEAR (map.log_score, truth.map_score, 1e-10);
  }
}

TEST (ChainInference, SumProductMatchesBruteForce)
{
  std::mt19937 rng (7);
  for (int trial = 0; trial < 30; ++trial)
  {
    const ChainPotentials chain = randomChain (5, 2, 4, 1.5, rng);
    const BruteForce truth = bruteForce (chain);
    const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (chain, true);
    EXPECT_NEAR (m.log_partition, truth.log_partition, 1e-10);
    for (std::size_t i = 0; i < chain.size (); ++i)
      EXPECT_LT ((m.node_marginals[i] - truth.node[i]).cwiseAbs ().maxCoeff (), 1e-10);
    ASSERT_EQ (m.edge_marginals.size (), chain.size () - 1);
    for (std::size_t i = 0; i + 1 < chain.size (); ++i)
      EXPECT_LT ((m.edge_marginals[i] - truth.edge[i]).cwiseAbs ().maxCoeff (), 1e-10);
  }
  EXPECT_TRUE (pcl_crf::crf::sumProduct (randomChain (4, 2, 3, 1.0, rng)).edge_marginals.empty ());
}

TEST (ChainInference, ForbiddenTransitionsAreRespected)
{
  std::mt19937 rng (3);
  ChainPotentials chain = randomChain (5, 3, 3, 1.0, rng);
  // Forbid every transition into state 0 and make state 0 of the last node very attractive.
  for (auto& p : chain.pairwise)
    p.col (0).setConstant (pcl_crf::crf::kLogZero);
  chain.unary[4] (0) = 50.0;
  const BruteForce truth = bruteForce (chain);
  const pcl_crf::crf::MapResult map = pcl_crf::crf::maxProduct (chain);
  EXPECT_EQ (map.labels, truth.map_labels);
  EXPECT_NE (map.labels[4], 0);
  const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (chain, true);
  EXPECT_NEAR (m.log_partition, truth.log_partition, 1e-10);
  for (std::size_t i = 1; i < chain.size (); ++i)
    EXPECT_EQ (m.node_marginals[i] (0), 0.0);
  EXPECT_EQ (m.edge_marginals[0].col (0).sum (), 0.0);
}

TEST (ChainInference, InfeasibleChainThrows)
{
  ChainPotentials chain;
  chain.unary = {Eigen::VectorXd::Zero (2), Eigen::VectorXd::Zero (2)};
  chain.pairwise = {Eigen::MatrixXd::Constant (2, 2, pcl_crf::crf::kLogZero)};
  EXPECT_THROW (pcl_crf::crf::maxProduct (chain), std::invalid_argument);
  EXPECT_THROW (pcl_crf::crf::sumProduct (chain), std::invalid_argument);
}

TEST (ChainInference, AScoreBeyondTheRangeOfADoubleIsNamedAsSuch)
{
  // Two nodes of potential 1e308 each: the score, 2e308, overflows. It was reported as
  // "every labelling of the chain is forbidden".
  ChainPotentials chain;
  chain.unary = {Eigen::VectorXd::Constant (2, 1e308), Eigen::VectorXd::Constant (2, 1e308)};
  chain.pairwise = {Eigen::MatrixXd::Zero (2, 2)};
  for (const auto& infer : std::vector<std::function<void ()>>{[&] { pcl_crf::crf::maxProduct (chain); },
                                                               [&] { pcl_crf::crf::sumProduct (chain); }})
    try {
      infer ();
      ADD_FAILURE () << "no error";
    }
    catch (const std::invalid_argument& e) {
      EXPECT_NE (std::string (e.what ()).find ("overflows"), std::string::npos) << e.what ();
    }
  chain.unary[0].setConstant (-1e308);
  chain.unary[1].setConstant (-1e308);
  try {
    pcl_crf::crf::maxProduct (chain);
    ADD_FAILURE () << "no error";
  }
  catch (const std::invalid_argument& e) {
    EXPECT_NE (std::string (e.what ()).find ("below the range of a double"), std::string::npos) << e.what ();
  }
}

TEST (ChainInference, EmptyAndSingleNodeChains)
{
  const ChainPotentials empty;
  EXPECT_TRUE (pcl_crf::crf::maxProduct (empty).labels.empty ());
  EXPECT_EQ (pcl_crf::crf::sumProduct (empty).log_partition, 0.0);
  ChainPotentials one;
  one.unary = {Eigen::Vector3d (0.0, 2.0, 1.0)};
  EXPECT_EQ (pcl_crf::crf::maxProduct (one).labels, std::vector<int> ({1}));
  const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (one, true);
  EXPECT_NEAR (m.log_partition, std::log (1.0 + std::exp (2.0) + std::exp (1.0)), 1e-12);
  EXPECT_NEAR (m.node_marginals[0].sum (), 1.0, 1e-12);
}

TEST (ChainInference, LongChainWithLargePotentialsStaysFinite)
{
  std::mt19937 rng (2000);
  std::uniform_real_distribution<double> big (-500.0, 500.0);
  ChainPotentials chain = randomChain (2000, 2, 5, 1.0, rng);
  for (auto& u : chain.unary)
    u = u.unaryExpr ([&] (double) { return big (rng); });
  for (auto& p : chain.pairwise)
    p = p.unaryExpr ([&] (double) { return big (rng); });

  const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (chain, true);
  ASSERT_TRUE (std::isfinite (m.log_partition));
  for (const auto& p : m.node_marginals)
  {
    ASSERT_TRUE (p.allFinite ());
    EXPECT_NEAR (p.sum (), 1.0, 1e-9);
  }
  for (const auto& p : m.edge_marginals)
  {
    ASSERT_TRUE (p.allFinite ());
    EXPECT_NEAR (p.sum (), 1.0, 1e-9);
  }
  const pcl_crf::crf::MapResult map = pcl_crf::crf::maxProduct (chain);
  EXPECT_NEAR (map.log_score, chain.score (map.labels), 1e-6 * std::abs (map.log_score));
  EXPECT_GE (m.log_partition, map.log_score);
}

TEST (ChainSumProduct, EdgeMarginalsOfHugePotentialsAreTheNodeMarginalsJoint)
{
  // Potentials of 1e20 (an audit): the edge marginals came out NaN while the node
  // marginals were right. Each edge table sums to 1 and its rows and columns to the
  // node marginals.
  std::mt19937 rng (5);
  ChainPotentials chain = randomChain (5, 3, 3, 1.0, rng);
  for (auto& u : chain.unary)
    u *= 1e20;
  for (auto& p : chain.pairwise)
    p *= 1e20;
  const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (chain, true);
  ASSERT_EQ (m.edge_marginals.size (), 4u);
  for (std::size_t i = 0; i < m.edge_marginals.size (); ++i) {
    const Eigen::MatrixXd& p = m.edge_marginals[i];
    ASSERT_TRUE (p.allFinite ()) << i;
    EXPECT_NEAR (p.sum (), 1.0, 1e-12);
    EXPECT_LT ((p.rowwise ().sum () - m.node_marginals[i]).cwiseAbs ().maxCoeff (), 1e-12) << i;
    EXPECT_LT ((p.colwise ().sum ().transpose () - m.node_marginals[i + 1]).cwiseAbs ().maxCoeff (), 1e-12) << i;
  }
}

TEST (ChainSampling, EmpiricalFrequenciesMatchMarginals)
{
  std::mt19937 rng (11);
  const ChainPotentials chain = randomChain (4, 2, 3, 1.0, rng);
  const pcl_crf::crf::MarginalResult m = pcl_crf::crf::sumProduct (chain);
  std::vector<Eigen::VectorXd> counts;
  for (const auto& p : m.node_marginals)
    counts.push_back (Eigen::VectorXd::Zero (p.size ()));
  const int samples = 20000;
  for (int k = 0; k < samples; ++k)
  {
    const std::vector<int> y = pcl_crf::crf::sampleChain (chain, rng);
    for (std::size_t i = 0; i < y.size (); ++i)
      counts[i] (y[i]) += 1.0 / samples;
  }
  for (std::size_t i = 0; i < counts.size (); ++i)
    EXPECT_LT ((counts[i] - m.node_marginals[i]).cwiseAbs ().maxCoeff (), 0.015);  // ~4 standard errors
}

}  // namespace
