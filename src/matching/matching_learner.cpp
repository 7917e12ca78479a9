#include <pcl_crf/crf/pseudo_likelihood.h>
#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/core/scan_thinning.h>
#include <pcl_crf/matching/matching_learner.h>
#include <pcl_crf/matching/raw_features.h>
#include <pcl_crf/matching/scan_matching.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** A training pair with what every stage reuses. */
struct TrainingPair
{
  ScanShape source;
  PreparedTarget target;
  MotionGuess guess;
  Rigid2d T_current = Rigid2d::Identity ();
  std::vector<int> truth;
  // this stage's
  PassGeometry pass;
  Eigen::MatrixXd data_features;
  Eigen::VectorXd data_margins;
  std::vector<int> labels;
};

std::vector<TrainingPair>
prepareTrainingPairs (const std::vector<ScanPair>& pairs, const MatchingParameters& parameters)
{
  std::vector<TrainingPair> prepared (pairs.size ());
  for (std::size_t k = 0; k < pairs.size (); ++k) {
    if (!pairs[k].hasTruth ())
      throw std::invalid_argument ("[pcl_crf::matching::trainCrfMatching] pair '" + pairs[k].name +
                                   "' has no ground truth");
    prepared[k].source = describeScan (pairs[k].source);
    prepared[k].target = prepareTarget (pairs[k].target, parameters.candidates);
    prepared[k].guess = MotionGuess::fromOdometry (pairs[k].odometry);
    prepared[k].T_current = prepared[k].guess.T_target_source;
    prepared[k].truth = pairs[k].source_match;
  }
  return prepared;
}

/** Candidates, raw features and labels of every pair under its current motion. */
void
prepareStage (std::vector<TrainingPair>& pairs, const MatchingParameters& parameters, StageTrainingReport& report)
{
  long matched = 0, found = 0;
  for (TrainingPair& pair : pairs) {
    pair.pass = preparePass (pair.source, pair.target, pair.guess.T_target_source, pair.T_current,
                             limitToInterval (parameters, pair.guess.interval).candidates,
                             &pair.pass.shape_neighbours);  // the last stage's, if any
    pair.data_features = dataFeatures (pair.source, pair.target.scan, pair.pass);
    pair.labels = matchStates (pair.pass.candidates, pair.truth);
    for (int i = 0; i < pair.pass.candidates.size (); ++i) {
      matched += pair.truth[i] != kNoMatch;
      found += pair.labels[i] < pair.pass.candidates.count (i);
      report.outlier_points += pair.labels[i] == pair.pass.candidates.count (i);
    }
    report.points += pair.pass.candidates.size ();
    report.data_samples += pair.data_features.cols ();
  }
  report.candidate_recall = matched == 0 ? 1.0 : static_cast<double> (found) / matched;
}

/** 1. data boosting: true candidates against the other candidates. */
crf::AdaBoostStumps
trainDataBoosting (std::vector<TrainingPair>& pairs, int rounds, StageTrainingReport& report)
{
  Eigen::MatrixXd X (report.data_samples, kDataFeatureCount);
  std::vector<int> y;
  y.reserve (report.data_samples);
  Eigen::Index row = 0;
  for (const TrainingPair& pair : pairs) {
    X.middleRows (row, pair.data_features.cols ()) = pair.data_features.transpose ();
    row += pair.data_features.cols ();
    const Candidates& candidates = pair.pass.candidates;
    for (int i = 0; i < candidates.size (); ++i)
      for (int c = 0; c < candidates.count (i); ++c)
        y.push_back (c == pair.labels[i] ? 1 : 0);
  }
  report.data_positives = std::count (y.begin (), y.end (), 1);
  crf::AdaBoostStumps booster;
  booster.train (X, y, rounds);
  for (TrainingPair& pair : pairs)
    pair.data_margins = boostedMargins (booster, pair.data_features);
  return booster;
}

/** 2. outlier boosting: points labelled with the outlier state against the others. */
crf::AdaBoostStumps
trainOutlierBoosting (const std::vector<TrainingPair>& pairs, int rounds, const StageTrainingReport& report)
{
  Eigen::MatrixXd X (report.points, kOutlierFeatureCount);
  std::vector<int> y;
  y.reserve (report.points);
  Eigen::Index row = 0;
  for (const TrainingPair& pair : pairs) {
    const Eigen::MatrixXd features = outlierFeatures (pair.source, pair.pass, pair.data_features, pair.data_margins);
    X.middleRows (row, features.cols ()) = features.transpose ();
    row += features.cols ();
    for (int i = 0; i < pair.pass.candidates.size (); ++i)
      y.push_back (pair.labels[i] == pair.pass.candidates.count (i) ? 1 : 0);
  }
  crf::AdaBoostStumps booster;
  booster.train (X, y, rounds);
  return booster;
}

/** 3. CRF weights by maximum pseudo-likelihood on the chains of boosted features. */
Eigen::VectorXd
trainCrfWeights (const std::vector<TrainingPair>& pairs, const StageModel& stage, const MatchingParameters& parameters,
                 StageTrainingReport& report)
{
  std::vector<crf::LabelledChain> chains;
  chains.reserve (pairs.size ());
  for (const TrainingPair& pair : pairs) {
    BoostedScores scores;
    scores.data_margins = pair.data_margins;
    scores.outlier_margins = boostedMargins (
        stage.outlier_boosting, outlierFeatures (pair.source, pair.pass, pair.data_features, pair.data_margins));
    chains.push_back ({matchingChainFeatures (pair.source, pair.target.scan, pair.pass, scores, parameters.residual_scale),
                       pair.labels});
  }
  if (!crf::hasAnEdge (chains))
    throw std::invalid_argument ("[pcl_crf::matching::trainCrfMatching] no training pair has two or more source "
                                 "points: the pairwise weights cannot be learned");
  const crf::PseudoLikelihood learner (std::move (chains), parameters.prior_sigma);
  const crf::LbfgsResult fit = learner.train ();
  report.objective = fit.value;
  report.lbfgs_iterations = fit.iterations;
  report.converged = fit.converged;
  return fit.x;
}

/** The median beam spacing of the training scans (MatchingParameters::training_beam_spacing). */
double
trainingBeamSpacing (const std::vector<ScanPair>& pairs)
{
  std::vector<double> spacings;
  for (const ScanPair& pair : pairs)
    for (const Eigen::Matrix2Xd* scan : {&pair.source, &pair.target})
      if (const double spacing = medianBeamSpacing (*scan); spacing > 0.0)
        spacings.push_back (spacing);
  if (spacings.empty ())
    return 0.0;
  const auto middle = spacings.begin () + static_cast<std::ptrdiff_t> (spacings.size () / 2);
  std::nth_element (spacings.begin (), middle, spacings.end ());
  return *middle;
}

}  // namespace

CrfMatchingModel
trainCrfMatching (const std::vector<ScanPair>& pairs, const MatchingParameters& parameters, TrainingReport* report)
{
  validateParameters (parameters);
  if (pairs.empty ())
    throw std::invalid_argument ("[pcl_crf::matching::trainCrfMatching] no training pair");
  std::vector<TrainingPair> training = prepareTrainingPairs (pairs, parameters);
  const bool some_match = std::any_of (pairs.begin (), pairs.end (), [] (const ScanPair& pair) {
    return std::any_of (pair.source_match.begin (), pair.source_match.end (), [] (int j) { return j != kNoMatch; });
  });
  if (!some_match)  // the boosting would learn "every point is an outlier"
    throw std::invalid_argument ("[pcl_crf::matching::trainCrfMatching] the training pairs have no associated point "
                                 "(every match is -1): nothing to learn associations from");
  CrfMatchingModel model;
  model.parameters = parameters;
  model.parameters.training_beam_spacing = trainingBeamSpacing (pairs);
  TrainingReport local_report;
  for (int k = 0; k < parameters.passes; ++k) {
    StageTrainingReport stage_report;
    prepareStage (training, parameters, stage_report);
    StageModel stage;
    stage.data_boosting = trainDataBoosting (training, parameters.boosting_rounds, stage_report);
    stage.outlier_boosting = trainOutlierBoosting (training, parameters.boosting_rounds, stage_report);
    stage.crf_weights = trainCrfWeights (training, stage, parameters, stage_report);
    if (k + 1 < parameters.passes)  // the next stage starts from this stage's estimate
      for (TrainingPair& pair : training)
        pair.T_current =
            runPass (pair.source, pair.target, pair.guess, pair.T_current, stage, parameters).T_estimate;
    model.stages.push_back (std::move (stage));
    local_report.stages.push_back (stage_report);
  }
  if (report)
    *report = std::move (local_report);
  return model;
}

}  // namespace matching
}  // namespace pcl_crf
