#include <pcl_crf/crf/adaboost_stumps.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

namespace {

using pcl_crf::crf::AdaBoostStumps;

double
trainingAccuracy (const AdaBoostStumps& booster, const Eigen::MatrixXd& X, const std::vector<int>& y)
{
  int correct = 0;
  for (Eigen::Index i = 0; i < X.rows (); ++i)
    correct += (booster.margin (X.row (i).transpose ()) > 0.0) == (y[i] == 1);
  return static_cast<double> (correct) / static_cast<double> (X.rows ());
}

/** n samples uniform in [−1, 1]^d. */
Eigen::MatrixXd
uniformSamples (int n, int d, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u (-1.0, 1.0);
  return Eigen::MatrixXd::NullaryExpr (n, d, [&] () { return u (rng); });
}

TEST (AdaBoostStumps, LearnsAOneDimensionalThresholdExactly)
{
  std::mt19937 rng (1);
  const Eigen::MatrixXd X = uniformSamples (500, 1, rng);
  std::vector<int> y (X.rows ());
  double below = -1.0, above = 1.0;  // largest negative and smallest positive sample
  for (Eigen::Index i = 0; i < X.rows (); ++i)
  {
    y[i] = X (i, 0) > 0.3 ? 1 : 0;
    (y[i] ? above : below) = y[i] ? std::min (above, X (i, 0)) : std::max (below, X (i, 0));
  }
  AdaBoostStumps booster;
  booster.train (X, y, 50);
  ASSERT_EQ (booster.getStumps ().size (), 1u);  // perfect first stump ends training
  const AdaBoostStumps::Stump& stump = booster.getStumps ()[0];
  EXPECT_EQ (stump.feature, 0);
  EXPECT_EQ (stump.polarity, 1);
  EXPECT_DOUBLE_EQ (stump.threshold, below + 0.5 * (above - below));
  EXPECT_EQ (trainingAccuracy (booster, X, y), 1.0);
  EXPECT_GT (booster.probability (Eigen::VectorXd::Constant (1, 0.9)), 0.99);
  EXPECT_LT (booster.probability (Eigen::VectorXd::Constant (1, -0.9)), 0.01);
}

TEST (AdaBoostStumps, NonLinearTwoDimensionalProblem)
{
  // A disc inside a square: not linearly separable, but additive in x and y, so
  // sums of stumps can fit it. (Pure XOR is not additive: stumps cannot fit it.)
  std::mt19937 rng (2);
  const Eigen::MatrixXd X = uniformSamples (1000, 2, rng);
  std::vector<int> y (X.rows ());
  for (Eigen::Index i = 0; i < X.rows (); ++i)
    y[i] = X.row (i).squaredNorm () < 0.5 ? 1 : 0;
  AdaBoostStumps booster;
  booster.train (X, y, 50);
  const double accuracy = trainingAccuracy (booster, X, y);
  std::cout << "[ measured ] disc problem training accuracy after " << booster.getStumps ().size ()
            << " stumps: " << accuracy << "\n";
  EXPECT_GT (accuracy, 0.9);
}

TEST (AdaBoostStumps, SingleClassGivesOneConstantStump)
{
  std::mt19937 rng (3);
  const Eigen::MatrixXd X = uniformSamples (50, 3, rng);
  AdaBoostStumps booster;
  booster.train (X, std::vector<int> (50, 0));
  ASSERT_EQ (booster.getStumps ().size (), 1u);
  EXPECT_EQ (booster.getStumps ()[0].feature, -1);
  EXPECT_TRUE (std::isfinite (booster.getStumps ()[0].alpha));
  EXPECT_LT (booster.probability (X.row (0).transpose ()), 1e-6);
}

TEST (AdaBoostStumps, RejectsBadTrainingSets)
{
  AdaBoostStumps booster;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero (4, 2);
  EXPECT_THROW (booster.train (X, {0, 1, 0}), std::invalid_argument);        // size mismatch
  EXPECT_THROW (booster.train (X, {0, 1, 2, 0}), std::invalid_argument);     // label not 0/1
  EXPECT_THROW (booster.train (X, {0, 1, 1, 0}, 0), std::invalid_argument);  // no round
  EXPECT_THROW (booster.train (Eigen::MatrixXd (0, 2), {}), std::invalid_argument);
  X (2, 1) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (booster.train (X, {0, 1, 1, 0}), std::invalid_argument);
  X (2, 1) = 0.5;
  booster.train (X, {0, 1, 1, 0});
  EXPECT_THROW (booster.margin (Eigen::VectorXd::Zero (1)), std::invalid_argument);  // model needs 2 features
}

TEST (AdaBoostStumps, WriteReadRoundTripGivesIdenticalMargins)
{
  std::mt19937 rng (4);
  const Eigen::MatrixXd X = uniformSamples (300, 4, rng);
  std::vector<int> y (X.rows ());
  for (Eigen::Index i = 0; i < X.rows (); ++i)
    y[i] = X (i, 0) * 0.7 + std::sin (3.0 * X (i, 2)) > 0.1 ? 1 : 0;
  AdaBoostStumps booster;
  booster.train (X, y, 30);
  std::stringstream text;
  booster.write (text);
  AdaBoostStumps copy;
  copy.read (text);
  ASSERT_EQ (copy.getStumps ().size (), booster.getStumps ().size ());
  EXPECT_EQ (copy.getDimension (), 4);
  for (Eigen::Index i = 0; i < X.rows (); ++i)
    EXPECT_EQ (copy.margin (X.row (i).transpose ()), booster.margin (X.row (i).transpose ()));
}

TEST (AdaBoostStumps, MalformedTextThrowsAndKeepsTheModel)
{
  const std::string header = "pcl_crf_adaboost_stumps 1\ndimension 2\n";
  const std::vector<std::string> bad = {
      "",                                               // empty
      "something_else 1\ndimension 2\nstumps 0\n",      // wrong magic
      "pcl_crf_adaboost_stumps 9\ndimension 2\nstumps 0\n",  // version
      header + "stumps two\n",                          // count not a number
      header + "stumps 2\n0 0.5 1 0.3\n",               // missing stump
      header + "stumps 1\n5 0.5 1 0.3\n",               // feature out of range
      header + "stumps 1\n0 0.5 0 0.3\n",               // polarity
      header + "stumps 1\n0 0.5 1\n",                   // missing alpha
      header + "stumps 1\n0 0.5 1 0.3 extra\n",         // trailing field
      header + "stumps 1\n0 nan 1 0.3\n",               // not a number
  };
  AdaBoostStumps booster;
  std::istringstream good (header + "stumps 1\n1 0.25 -1 0.5\n");
  booster.read (good);
  for (const std::string& text : bad)
  {
    std::istringstream is (text);
    EXPECT_THROW (booster.read (is), std::runtime_error) << text;
  }
  ASSERT_EQ (booster.getStumps ().size (), 1u);
  EXPECT_EQ (booster.getStumps ()[0].feature, 1);
}

TEST (AdaBoostStumps, TrainsFiftyThousandSamplesQuickly)
{
  std::mt19937 rng (5);
  const Eigen::MatrixXd X = uniformSamples (50000, 15, rng);
  std::vector<int> y (X.rows ());
  for (Eigen::Index i = 0; i < X.rows (); ++i)
    y[i] = X (i, 3) + 0.5 * X (i, 7) * X (i, 7) - 0.3 * X (i, 11) > 0.2 ? 1 : 0;
  AdaBoostStumps booster;
  const auto start = std::chrono::steady_clock::now ();
  booster.train (X, y, 50);
  const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  const double accuracy = trainingAccuracy (booster, X, y);
  std::cout << "[ measured ] 50000 x 15, " << booster.getStumps ().size () << " rounds: " << seconds
            << " s, training accuracy " << accuracy << "\n";
  EXPECT_EQ (booster.getStumps ().size (), 50u);
  EXPECT_LT (seconds, 5.0);
  EXPECT_GT (accuracy, 0.9);
}

}  // namespace
