// Joint learning's choices: the one-standard-error rule and the prior on the joint
// weights, chosen by the training pairs' own association accuracy.

#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_learning.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pcl_crf::ScanPair;
using pcl_crf::joint::JointLearningOptions;
using pcl_crf::joint::JointModel;
using pcl_crf::joint::learnJointWeightsAndPrior;
using pcl_crf::joint::selectMinClusterPoints;
using pcl_crf::joint::selectWithinOneStandardError;

const JointModel&
shippedModel ()
{
  static const JointModel model =
      pcl_crf::joint::loadJointModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/joint.model");
  return model;
}

/** \a count consecutive-scan pairs at 20 Hz (0.5 m of travel at 10 m/s): not the
 *  2–4 m the shipped model was trained on. */
std::vector<ScanPair>
consecutivePairs (std::size_t count)
{
  pcl_crf::simulation::SimulatorConfig config;
  config.seed = 888;
  config.spacing = pcl_crf::simulation::ScanSpacing::Consecutive;
  config.scan_rate = 20.0;
  return pcl_crf::simulation::ScanPairSimulator (config).simulateDataset (0, count);
}

/** Mean association accuracy of estimateJoint with \a model on \a pairs, as pcl_crf_eval runs it. */
double
meanAssociation (const std::vector<ScanPair>& pairs, const JointModel& model)
{
  double sum = 0.0;
  for (const ScanPair& pair : pairs) {
    pcl_crf::joint::JointParameters parameters;
    parameters.sensor = pair.sensor;
    const pcl_crf::joint::JointResult result =
        pcl_crf::joint::estimateJoint (pair.source, pair.target, pair.odometry, model, parameters);
    sum += pcl_crf::scorePair (pair, pcl_crf::joint::toPrediction (pair.source, result)).association_accuracy;
  }
  return sum / static_cast<double> (pairs.size ());
}

// Candidate A = {1.0, 1.0, 0.5, 0.5} (mean 0.75) is the best.
// B = {0.9, 0.8, 0.5, 0.5}: differences from A 0.1, 0.2, 0, 0, mean 0.075, sample
//   standard deviation sqrt (0.0275 / 3) = 0.0957, standard error 0.0479 < 0.075: out.
// C = {0.95, 0.9, 0.5, 0.55}: differences 0.05, 0.1, 0, −0.05, mean 0.025, standard
//   deviation sqrt (0.0125 / 3) = 0.0645, standard error 0.0323 ≥ 0.025: within.
const std::vector<std::vector<double>> kScores{
    {1.0, 1.0, 0.5, 0.5}, {0.9, 0.8, 0.5, 0.5}, {0.95, 0.9, 0.5, 0.55}};

TEST (JointLearning, OneStandardErrorRuleTakesThePreferredCandidateWithinOneErrorOfTheBest)
{
  EXPECT_EQ (selectWithinOneStandardError (kScores, {1, 2, 0}), 2u);  // B is too far below A
  EXPECT_EQ (selectWithinOneStandardError (kScores, {2, 1, 0}), 2u);
  EXPECT_EQ (selectWithinOneStandardError (kScores, {0, 1, 2}), 0u);
  EXPECT_EQ (selectWithinOneStandardError (kScores, {1, 0, 2}), 0u);
  // One pair has no standard error: only a tie with the best is within.
  EXPECT_EQ (selectWithinOneStandardError ({{0.5}, {0.4}}, {1, 0}), 0u);
  EXPECT_EQ (selectWithinOneStandardError ({{0.5}, {0.5}}, {1, 0}), 1u);
}

TEST (JointLearning, OneStandardErrorRuleRejectsBadInput)
{
  EXPECT_THROW (selectWithinOneStandardError ({}, {}), std::invalid_argument);
  EXPECT_THROW (selectWithinOneStandardError (kScores, {0, 1}), std::invalid_argument);     // C not ranked
  EXPECT_THROW (selectWithinOneStandardError (kScores, {0, 1, 1}), std::invalid_argument);  // B twice
  EXPECT_THROW (selectWithinOneStandardError (kScores, {0, 1, 3}), std::invalid_argument);  // no candidate 3
  EXPECT_THROW (selectWithinOneStandardError ({{0.5, 0.4}, {0.5}}, {0, 1}), std::invalid_argument);
  EXPECT_THROW (selectWithinOneStandardError ({{}, {}}, {0, 1}), std::invalid_argument);
}

TEST (JointLearning, TheSmallestClusterIsThreePointsUnlessAGridOffersSeveral)
{
  EXPECT_EQ (JointLearningOptions ().min_cluster_points_grid, std::vector<int> ({3}));
  // One value is taken without scoring a pair: an untrained model would throw if run.
  const std::vector<ScanPair> pairs = consecutivePairs (1);
  const JointModel untrained;
  EXPECT_EQ (selectMinClusterPoints (pairs, untrained, {7}), 7);
  EXPECT_THROW (selectMinClusterPoints (pairs, untrained, {7, 9}), std::invalid_argument);  // scored: not trained
}

TEST (JointLearning, ClusterSizeSelectionRejectsBadInput)
{
  const std::vector<ScanPair> pairs = consecutivePairs (1);
  EXPECT_THROW (selectMinClusterPoints (pairs, shippedModel (), {}), std::invalid_argument);
  EXPECT_THROW (selectMinClusterPoints (pairs, shippedModel (), {0}), std::invalid_argument);
  EXPECT_THROW (selectMinClusterPoints (pairs, shippedModel (), {3, -1}), std::invalid_argument);
  EXPECT_THROW (selectMinClusterPoints ({}, shippedModel (), {3}), std::invalid_argument);
}

TEST (JointLearning, ConsecutiveScansTakeATighterPriorThanTheLooseOneTheyDefeat)
{
  // With σ = 10 alone, pseudo-likelihood gives the outlier-cluster switch a weight of
  // about 6 on these pairs and full inference on them associates 0.708 of the points;
  // the grid keeps σ = 3 (0.750). Measured with the shipped matcher and initial
  // clustering, which stand in for trainJointModel's first steps.
  const std::vector<ScanPair> pairs = consecutivePairs (16);
  JointModel loose = shippedModel ();
  JointLearningOptions only_loose;
  only_loose.prior_sigma_grid = {10.0};
  const double loose_association = learnJointWeightsAndPrior (pairs, only_loose, loose);
  EXPECT_EQ (loose.prior_sigma, 10.0);

  JointModel chosen = shippedModel ();
  const double chosen_association = learnJointWeightsAndPrior (pairs, JointLearningOptions (), chosen);
  EXPECT_LT (chosen.prior_sigma, 10.0);
  EXPECT_GT (chosen_association, loose_association + 0.03);
  EXPECT_NEAR (chosen_association, meanAssociation (pairs, chosen), 1e-12);  // what the model really does
}

TEST (JointLearning, PriorSelectionRejectsBadInput)
{
  const std::vector<ScanPair> pairs = consecutivePairs (1);
  JointModel model = shippedModel ();
  JointLearningOptions options;
  EXPECT_THROW (learnJointWeightsAndPrior ({}, options, model), std::invalid_argument);
  options.prior_sigma_grid = {};
  EXPECT_THROW (learnJointWeightsAndPrior (pairs, options, model), std::invalid_argument);
  options.prior_sigma_grid = {1.0, 0.0};
  EXPECT_THROW (learnJointWeightsAndPrior (pairs, options, model), std::invalid_argument);
  options.prior_sigma_grid = {-1.0};
  EXPECT_THROW (learnJointWeightsAndPrior (pairs, options, model), std::invalid_argument);
}

}  // namespace
