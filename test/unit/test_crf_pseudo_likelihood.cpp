#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/pseudo_likelihood.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>

namespace {

using pcl_crf::crf::ChainFeatures;
using pcl_crf::crf::LabelledChain;
using pcl_crf::crf::PseudoLikelihood;

constexpr int kUnaryDimension = 3;
constexpr int kPairwiseDimension = 2;

/** Random features: f_u ~ N(0, 1); f_p = ([s == t], N(0, 1)). States per node in [min_s, max_s]. */
ChainFeatures
randomFeatures (int n, int min_s, int max_s, std::mt19937& rng)
{
  std::uniform_int_distribution<int> states (min_s, max_s);
  std::normal_distribution<double> normal;
  ChainFeatures f;
  for (int i = 0; i < n; ++i)
    f.unary.push_back (Eigen::MatrixXd::NullaryExpr (states (rng), kUnaryDimension, [&] () { return normal (rng); }));
  for (int i = 0; i + 1 < n; ++i)
  {
    const int s_i = f.states (i), s_j = f.states (i + 1);
    Eigen::MatrixXd edge (s_i * s_j, kPairwiseDimension);
    for (int s = 0; s < s_i; ++s)
      for (int t = 0; t < s_j; ++t)
      {
        const Eigen::Index row = ChainFeatures::pairRow (s, t, s_i);
        edge (row, 0) = s == t ? 1.0 : 0.0;
        edge (row, 1) = normal (rng);
      }
    f.pairwise.push_back (edge);
  }
  return f;
}

/** Labels drawn exactly from the model (forward filtering, backward sampling). */
LabelledChain
sampledChain (int n, int states, const Eigen::VectorXd& w, std::mt19937& rng)
{
  LabelledChain chain;
  chain.features = randomFeatures (n, states, states, rng);
  chain.labels = pcl_crf::crf::sampleChain (pcl_crf::crf::potentials (chain.features, w), rng);
  return chain;
}

double
mapAccuracy (const std::vector<LabelledChain>& chains, const Eigen::VectorXd& w)
{
  double correct = 0.0, total = 0.0;
  for (const auto& c : chains)
  {
    const std::vector<int> map = pcl_crf::crf::maxProduct (pcl_crf::crf::potentials (c.features, w)).labels;
    for (std::size_t i = 0; i < map.size (); ++i)
      correct += map[i] == c.labels[i] ? 1.0 : 0.0;
    total += static_cast<double> (map.size ());
  }
  return correct / total;
}

TEST (ChainFeatures, PotentialsFollowTheDocumentedLayout)
{
  std::mt19937 rng (1);
  const ChainFeatures f = randomFeatures (3, 2, 4, rng);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced (kUnaryDimension + kPairwiseDimension, -1.0, 2.0);
  const pcl_crf::crf::ChainPotentials chain = pcl_crf::crf::potentials (f, w);
  EXPECT_NO_THROW (chain.validate ());
  for (int s = 0; s < f.states (1); ++s)
    EXPECT_NEAR (chain.unary[1] (s), f.unary[1].row (s).dot (w.head (kUnaryDimension)), 1e-12);
  for (int s = 0; s < f.states (0); ++s)
    for (int t = 0; t < f.states (1); ++t)
      EXPECT_NEAR (chain.pairwise[0] (s, t),
                   f.pairwise[0].row (ChainFeatures::pairRow (s, t, f.states (0))).dot (w.tail (kPairwiseDimension)),
                   1e-12);
  EXPECT_THROW (pcl_crf::crf::potentials (f, Eigen::VectorXd::Zero (4)), std::invalid_argument);
  ChainFeatures bad = f;
  bad.pairwise[1].conservativeResize (bad.pairwise[1].rows () - 1, Eigen::NoChange);
  EXPECT_THROW (bad.validate (), std::invalid_argument);
}

TEST (PseudoLikelihood, ObjectiveMatchesConditionalsOfTheChain)
{
  std::mt19937 rng (2);
  LabelledChain c;
  c.features = randomFeatures (6, 2, 4, rng);
  for (std::size_t i = 0; i < c.features.size (); ++i)
    c.labels.push_back (static_cast<int> (i) % c.features.states (i));
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced (5, 0.7, -1.1);
  // −log PL from scratch: p(y_i | rest) = exp(score(y)) / Σ_s exp(score(y with y_i = s)).
  const pcl_crf::crf::ChainPotentials chain = pcl_crf::crf::potentials (c.features, w);
  double expected = 0.0;
  for (std::size_t i = 0; i < c.labels.size (); ++i)
  {
    double z = 0.0;
    std::vector<int> y = c.labels;
    for (int s = 0; s < c.features.states (i); ++s)
      y[i] = s, z += std::exp (chain.score (y));
    expected -= chain.score (c.labels) - std::log (z);
  }
  const double sigma = 2.0;
  expected += w.squaredNorm () / (2.0 * sigma * sigma);
  const PseudoLikelihood pl ({c}, sigma);
  Eigen::VectorXd grad;
  EXPECT_NEAR (pl.objectiveAndGradient (w, grad), expected, 1e-10);
}

TEST (PseudoLikelihood, GradientMatchesCentralDifferences)
{
  std::mt19937 rng (3);
  std::vector<LabelledChain> chains;
  for (int c = 0; c < 3; ++c)
  {
    LabelledChain chain;
    chain.features = randomFeatures (20, 2, 4, rng);
    for (std::size_t i = 0; i < chain.features.size (); ++i)
      chain.labels.push_back (std::uniform_int_distribution<int> (0, chain.features.states (i) - 1) (rng));
    chains.push_back (chain);
  }
  const PseudoLikelihood pl (chains, 1.5);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial)
  {
    const Eigen::VectorXd w = Eigen::VectorXd::NullaryExpr (pl.getDimension (), [&] () { return normal (rng); });
    Eigen::VectorXd grad, unused;
    pl.objectiveAndGradient (w, grad);
    Eigen::VectorXd numeric (w.size ());
    const double h = 1e-5;
    for (Eigen::Index k = 0; k < w.size (); ++k)
    {
      Eigen::VectorXd plus = w, minus = w;
      plus (k) += h;
      minus (k) -= h;
      numeric (k) = (pl.objectiveAndGradient (plus, unused) - pl.objectiveAndGradient (minus, unused)) / (2 * h);
    }
    EXPECT_LT ((grad - numeric).norm () / grad.norm (), 1e-5) << "analytic " << grad.transpose ()
                                                              << "\nnumeric  " << numeric.transpose ();
  }
}

TEST (PseudoLikelihood, RecoversTheWeightsOfASampledModel)
{
  std::mt19937 rng (2010);
  Eigen::VectorXd w_true (kUnaryDimension + kPairwiseDimension);
  w_true << 1.0, -0.8, 0.5, 1.5, 0.7;
  std::vector<LabelledChain> training, held_out;
  for (int c = 0; c < 10; ++c)
    training.push_back (sampledChain (300, 3, w_true, rng));
  for (int c = 0; c < 5; ++c)
    held_out.push_back (sampledChain (300, 3, w_true, rng));

  const PseudoLikelihood pl (training, 10.0);
  const pcl_crf::crf::LbfgsResult fit = pl.train ();
  EXPECT_TRUE (fit.converged) << fit.status;
  const double max_error = (fit.x - w_true).cwiseAbs ().maxCoeff ();
  const double true_accuracy = mapAccuracy (held_out, w_true);
  const double learned_accuracy = mapAccuracy (held_out, fit.x);
  std::cout << "[ measured ] learned w " << fit.x.transpose () << " (true " << w_true.transpose ()
            << "), max |error| " << max_error << ", " << fit.iterations << " iterations; held-out MAP accuracy "
            << learned_accuracy << " (true model " << true_accuracy << ")\n";
  EXPECT_LT (max_error, 0.25);
  EXPECT_GT (learned_accuracy, true_accuracy - 0.02);
}

TEST (PseudoLikelihood, RejectsBadInput)
{
  std::mt19937 rng (4);
  LabelledChain c;
  c.features = randomFeatures (4, 2, 2, rng);
  c.labels = {0, 1, 2, 0};  // 2 is out of range
  EXPECT_THROW (PseudoLikelihood ({c}), std::invalid_argument);
  c.labels = {0, 1};
  EXPECT_THROW (PseudoLikelihood ({c}), std::invalid_argument);
  c.labels = {0, 1, 1, 0};
  EXPECT_THROW (PseudoLikelihood ({c}, 0.0), std::invalid_argument);
  const PseudoLikelihood pl ({c});
  Eigen::VectorXd grad;
  EXPECT_THROW (pl.objectiveAndGradient (Eigen::VectorXd::Zero (3), grad), std::invalid_argument);
  LabelledChain other;
  other.features = randomFeatures (3, 2, 2, rng);
  for (auto& u : other.features.unary)
    u.conservativeResize (Eigen::NoChange, 2);  // valid alone, but D_u = 2 != 3
  other.labels = {0, 0, 0};
  EXPECT_THROW (PseudoLikelihood ({c, other}), std::invalid_argument);
}

}  // namespace
