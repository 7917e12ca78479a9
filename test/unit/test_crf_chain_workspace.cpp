// ChainInference (reused buffers, probability-space messages) against the log-space
// definition, and PackedChainPotentials against ChainPotentials.

#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/log_space.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace {

using pcl_crf::crf::ChainInference;
using pcl_crf::crf::ChainPotentials;
using pcl_crf::crf::kLogZero;
using pcl_crf::crf::PackedChainPotentials;

/** Random chain: S_i in [1, max_states], N(0, scale²) potentials, a fraction of them forbidden
 *  (never every state of a node). */
ChainPotentials
randomChain (int n, int max_states, double scale, double forbidden, std::mt19937& rng)
{
  std::uniform_int_distribution<int> states (1, max_states);
  std::normal_distribution<double> value (0.0, scale);
  std::uniform_real_distribution<double> uniform (0.0, 1.0);
  const auto draw = [&] { return uniform (rng) < forbidden ? kLogZero : value (rng); };
  ChainPotentials chain;
  for (int i = 0; i < n; ++i)
  {
    Eigen::VectorXd u (states (rng));
    for (Eigen::Index s = 0; s < u.size (); ++s)
      u (s) = draw ();
    u (std::uniform_int_distribution<Eigen::Index> (0, u.size () - 1) (rng)) = value (rng);
    chain.unary.push_back (u);
  }
  for (int i = 0; i + 1 < n; ++i)
  {
    Eigen::MatrixXd p (chain.unary[i].size (), chain.unary[i + 1].size ());
    for (Eigen::Index k = 0; k < p.size (); ++k)
      p (k) = draw ();
    chain.pairwise.push_back (p);
  }
  return chain;
}

TEST (ChainInference, AgreesWithTheLogSpaceDefinitionAtAnyMagnitude)
{
  std::mt19937 rng (5);
  ChainInference inference;  // one workspace for every chain
  int feasible = 0;
  for (const double scale : {0.5, 30.0, 400.0, 5000.0})
    for (int trial = 0; trial < 20; ++trial)
    {
      const ChainPotentials chain = randomChain (40, 6, scale, trial % 2 ? 0.2 : 0.0, rng);
      const std::vector<Eigen::VectorXd> alpha = pcl_crf::crf::forwardMessages (chain);
      const std::vector<Eigen::VectorXd> beta = pcl_crf::crf::backwardMessages (chain);
      const double log_z = pcl_crf::crf::logSumExp (alpha.back ());
      if (!std::isfinite (log_z))
      {
        EXPECT_THROW (inference.compute (chain), std::invalid_argument);
        continue;
      }
      ++feasible;
      inference.compute (chain, pcl_crf::crf::kMapLabels | pcl_crf::crf::kEdgeMarginals);
      const std::string where = "scale " + std::to_string (scale) + " trial " + std::to_string (trial);
      EXPECT_NEAR (inference.logPartition (), log_z, 1e-12 * (1.0 + std::abs (log_z))) << where;
      for (std::size_t i = 0; i < chain.size (); ++i)
      {
        const Eigen::VectorXd log_p = alpha[i] + beta[i];
        const Eigen::VectorXd expected = pcl_crf::crf::normalizedExp (log_p);
        ASSERT_EQ (inference.nodeMarginal (i).size (), expected.size ()) << where;
        EXPECT_LT ((inference.nodeMarginal (i) - expected).cwiseAbs ().maxCoeff (), 1e-9) << where << " node " << i;
        for (Eigen::Index s = 0; s < log_p.size (); ++s)
          EXPECT_TRUE (log_p (s) != kLogZero || inference.nodeMarginal (i) (s) == 0.0) << where << " node " << i;
        if (i + 1 < chain.size ())
        {
          const Eigen::MatrixXd joint = inference.edgeMarginal (i);
          EXPECT_NEAR (joint.sum (), 1.0, 1e-9) << where;
          EXPECT_LT ((joint.rowwise ().sum () - expected).cwiseAbs ().maxCoeff (), 1e-9) << where << " edge " << i;
        }
      }
      EXPECT_NEAR (inference.mapLogScore (), chain.score (inference.mapLabels ()),
                   1e-12 * (1.0 + std::abs (inference.mapLogScore ())))
          << where;
      EXPECT_GE (inference.logPartition (), inference.mapLogScore () - 1e-9 * std::abs (log_z)) << where;
    }
  EXPECT_GT (feasible, 40);
}

TEST (ChainInference, LongChainsRecomputeTheEdgeTablesWithTheSameResults)
{
  // 2500 nodes of 6 states: ~90000 transitions, beyond what the backward pass keeps.
  std::mt19937 rng (41);
  ChainPotentials chain = randomChain (2500, 6, 2.0, 0.0, rng);
  std::uniform_real_distribution<double> extreme (-900.0, 900.0);
  for (auto& p : chain.pairwise)
  {
    p (0, 0) = extreme (rng);  // beyond exp's range: the log-space path
    if (p.size () > 1)
      p (p.rows () - 1, p.cols () - 1) = kLogZero;  // a forbidden transition
  }
  const std::vector<Eigen::VectorXd> alpha = pcl_crf::crf::forwardMessages (chain);
  const std::vector<Eigen::VectorXd> beta = pcl_crf::crf::backwardMessages (chain);
  const double log_z = pcl_crf::crf::logSumExp (alpha.back ());
  ASSERT_TRUE (std::isfinite (log_z));
  ChainInference inference;
  inference.compute (chain, pcl_crf::crf::kNodeMarginals);
  EXPECT_NEAR (inference.logPartition (), log_z, 1e-12 * (1.0 + std::abs (log_z)));
  double worst = 0.0;
  for (std::size_t i = 0; i < chain.size (); ++i)
    worst = std::max (worst, (inference.nodeMarginal (i) - pcl_crf::crf::normalizedExp (alpha[i] + beta[i]))
                                 .cwiseAbs ()
                                 .maxCoeff ());
  EXPECT_LT (worst, 1e-9);
}

TEST (ChainInference, ReusedWorkspaceGivesTheResultsOfAFreshOne)
{
  std::mt19937 rng (17);
  ChainInference reused;
  for (int trial = 0; trial < 12; ++trial)
  {
    const ChainPotentials chain = randomChain (trial % 3 == 0 ? 3 : 60 - 4 * trial, 5, 3.0, 0.1, rng);
    ChainInference fresh;
    try
    {
      fresh.compute (chain);
    }
    catch (const std::invalid_argument&)
    {
      EXPECT_THROW (reused.compute (chain), std::invalid_argument);
      continue;
    }
    reused.compute (chain);
    ASSERT_EQ (reused.size (), chain.size ());
    EXPECT_EQ (reused.mapLabels (), fresh.mapLabels ());
    EXPECT_EQ (reused.mapLogScore (), fresh.mapLogScore ());
    EXPECT_EQ (reused.logPartition (), fresh.logPartition ());
    for (std::size_t i = 0; i < chain.size (); ++i)
      EXPECT_EQ (reused.nodeMarginal (i), fresh.nodeMarginal (i)) << "trial " << trial << " node " << i;
    // The free functions give the same numbers.
    EXPECT_EQ (pcl_crf::crf::maxProduct (chain).labels, fresh.mapLabels ());
    EXPECT_EQ (pcl_crf::crf::sumProduct (chain).node_marginals.back (), fresh.nodeMarginal (chain.size () - 1));
  }
}

TEST (ChainInference, OutputsOnlyWhatIsAsked)
{
  std::mt19937 rng (23);
  const ChainPotentials chain = randomChain (10, 4, 1.0, 0.0, rng);
  ChainInference inference;
  inference.compute (chain, pcl_crf::crf::kNodeMarginals);
  EXPECT_TRUE (inference.mapLabels ().empty ());
  EXPECT_NEAR (inference.nodeMarginal (3).sum (), 1.0, 1e-12);
  inference.compute (chain, pcl_crf::crf::kMapLabels);
  EXPECT_EQ (inference.mapLabels (), pcl_crf::crf::maxProduct (chain).labels);
  inference.compute (ChainPotentials ());
  EXPECT_EQ (inference.size (), 0u);
  EXPECT_EQ (inference.logPartition (), 0.0);
}

TEST (PackedChainPotentials, HoldsWhatChainPotentialsHolds)
{
  std::mt19937 rng (29);
  const ChainPotentials chain = randomChain (7, 4, 2.0, 0.1, rng);
  PackedChainPotentials packed;
  packed.addNode (9);  // replaced by assign
  packed.assign (chain);
  ASSERT_EQ (packed.size (), chain.size ());
  for (std::size_t i = 0; i < chain.size (); ++i)
  {
    EXPECT_EQ (packed.states (i), chain.states (i));
    EXPECT_EQ (packed.unary (i), chain.unary[i]);
    if (i + 1 < chain.size ())
    {
      EXPECT_EQ (packed.pairwise (i), chain.pairwise[i]);
    }
  }
  std::vector<int> labels (chain.size (), 0);
  EXPECT_EQ (packed.score (labels), chain.score (labels));
  EXPECT_THROW (packed.score (std::vector<int> (3, 0)), std::invalid_argument);

  // Built node by node, then solved.
  packed.clear ();
  EXPECT_EQ (packed.size (), 0u);
  packed.addNode (2);
  packed.addNode (3);
  packed.unary (0) << 0.0, 1.0;
  packed.unary (1) << 0.5, 0.0, -1.0;
  packed.pairwise (0) << 0.0, 0.2, -0.3, 0.1, kLogZero, 0.4;
  ChainPotentials same;
  same.unary = {packed.unary (0), packed.unary (1)};
  same.pairwise = {packed.pairwise (0)};
  ChainInference a, b;
  a.compute (packed);
  b.compute (same);
  EXPECT_EQ (a.mapLabels (), b.mapLabels ());
  EXPECT_EQ (a.logPartition (), b.logPartition ());
  EXPECT_THROW (packed.addNode (0), std::invalid_argument);
}

TEST (PackedChainPotentials, ValidateNamesTheProblem)
{
  PackedChainPotentials packed;
  packed.addNode (2);
  packed.addNode (2);
  packed.addNode (2);
  EXPECT_NO_THROW (packed.validate ());
  packed.pairwise (1) (0, 1) = std::numeric_limits<double>::quiet_NaN ();
  try
  {
    packed.validate ();
    FAIL () << "NaN not detected";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE (std::string (e.what ()).find ("edge 1"), std::string::npos) << e.what ();
  }
  packed.pairwise (1) (0, 1) = 0.0;
  packed.unary (2).setConstant (kLogZero);
  EXPECT_THROW (packed.validate (), std::invalid_argument);
  ChainInference inference;
  EXPECT_THROW (inference.compute (packed), std::invalid_argument);
}

}  // namespace
