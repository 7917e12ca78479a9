#include <pcl_crf/clustering/prior_selection.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_learning.h>
#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/matching/matching_learner.h>
#include <pcl_crf/metrics/pair_scores.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The truth of one pair in the joint CRF's states. */
struct LadderTruth
{
  std::vector<int> association;  // per point: candidate of the true match, or the outlier state
  std::vector<int> cluster;      // per point: cluster index, K for the outlier cluster
  std::vector<Rigid2d> motions;  // true T_target_source of the K clusters
};

LadderTruth
ladderTruth (const ScanPair& pair, const matching::Candidates& candidates)
{
  LadderTruth truth;
  const int n = candidates.size ();
  truth.association = matching::matchStates (candidates, pair.source_match);
  std::map<int, int> cluster_of_object;  // object id → cluster, in order of appearance
  for (int i = 0; i < n; ++i) {
    const bool matched = truth.association[i] < candidates.count (i);
    if (matched && !cluster_of_object.count (pair.source_object[i])) {
      const int k = pair.objectIndex (pair.source_object[i]);
      if (k < 0)
        throw std::invalid_argument ("[pcl_crf::joint::jointNodeConditionals] pair '" + pair.name +
                                     "': object " + std::to_string (pair.source_object[i]) + " is not declared");
      cluster_of_object.emplace (pair.source_object[i], static_cast<int> (truth.motions.size ()));
      truth.motions.push_back (pair.objects[k].T_target_source);
    }
  }
  const int outlier = static_cast<int> (truth.motions.size ());
  truth.cluster.resize (n);
  for (int i = 0; i < n; ++i)
    truth.cluster[i] =
        truth.association[i] < candidates.count (i) ? cluster_of_object.at (pair.source_object[i]) : outlier;
  return truth;
}

/** Association node i: unary and both chain neighbours clamped. Its rung is left out
 *  (a composite likelihood rather than the full pseudo-likelihood): the true cluster
 *  says almost surely whether the point is matched (the outlier cluster holds exactly
 *  the unmatched points), so conditioning on it would explain the association's own
 *  evidence away and leave the outlier features with no weight (measured: trained on
 *  the test split, the full pseudo-likelihood gave 0.71 association accuracy on the
 *  training split, this 0.78); the rung's weights are learned from the clustering
 *  nodes, which see the true association. */
crf::NodeConditional
associationNode (const crf::ChainFeatures& chain, const LadderGeometry& geometry, const LadderTruth& truth, int i)
{
  const int n = geometry.size (), states = geometry.associationStates (i);
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero (states, kJointWeightCount);
  f.leftCols (matching::kUnaryFeatureCount) = chain.unary[i];
  auto pairwise = f.middleCols (matching::kUnaryFeatureCount, matching::kPairwiseFeatureCount);
  for (int s = 0; s < states; ++s) {
    if (i > 0)
      pairwise.row (s) += chain.pairwise[i - 1].row (
          crf::ChainFeatures::pairRow (truth.association[i - 1], s, geometry.associationStates (i - 1)));
    if (i + 1 < n)
      pairwise.row (s) += chain.pairwise[i].row (crf::ChainFeatures::pairRow (s, truth.association[i + 1], states));
  }
  return {f, truth.association[i]};
}

/** Clustering node i: the rung to its true association and both neighbours clamped. */
crf::NodeConditional
clusterNode (const LadderGeometry& geometry, const LadderTruth& truth, int i)
{
  const int n = geometry.size (), states = static_cast<int> (truth.motions.size ()) + 1;
  Eigen::MatrixXd f (states, kJointWeightCount);
  for (int l = 0; l < states; ++l) {
    Eigen::VectorXd row = rungFeatures (geometry, i, truth.association[i], l, truth.motions);
    if (i > 0)
      row += clusterEdgeFeatures (geometry, i - 1, truth.cluster[i - 1], l, truth.motions);
    if (i + 1 < n)
      row += clusterEdgeFeatures (geometry, i, l, truth.cluster[i + 1], truth.motions);
    f.row (l) = row.transpose ();
  }
  return {f, truth.cluster[i]};
}

/** Per pair of \a pairs: \a metric of estimateJoint's result with \a model, run as
 *  pcl_crf_eval runs it. */
std::vector<double>
trainingScores (const std::vector<ScanPair>& pairs, const JointModel& model, double PairScores::*metric)
{
  std::vector<double> scores;
  JointParameters parameters;
  for (const ScanPair& pair : pairs) {
    parameters.sensor = pair.sensor;  // as pcl_crf_eval runs it
    scores.push_back (scorePair (pair, toPrediction (pair.source, estimateJoint (pair.source, pair.target, pair.odometry,
                                                                                 model, parameters))).*metric);
  }
  return scores;
}

double
mean (const std::vector<double>& values)
{
  return std::accumulate (values.begin (), values.end (), 0.0) / static_cast<double> (values.size ());
}

/** The standard error of the mean of the differences a[k] − b[k] (0 for one pair). */
double
pairedStandardError (const std::vector<double>& a, const std::vector<double>& b)
{
  const std::size_t n = a.size ();
  if (n < 2)
    return 0.0;
  std::vector<double> differences (n);
  for (std::size_t k = 0; k < n; ++k)
    differences[k] = a[k] - b[k];
  const double average = mean (differences);
  double squares = 0.0;
  for (double d : differences)
    squares += (d - average) * (d - average);
  return std::sqrt (squares / static_cast<double> (n - 1) / static_cast<double> (n));
}

/** The indices of \a values ordered by \a before on their values (stable: ties keep their order). */
template <typename T, typename Before>
std::vector<std::size_t>
indicesInOrder (const std::vector<T>& values, Before before)
{
  std::vector<std::size_t> order (values.size ());
  std::iota (order.begin (), order.end (), std::size_t (0));
  std::stable_sort (order.begin (), order.end (),
                    [&values, &before] (std::size_t a, std::size_t b) { return before (values[a], values[b]); });
  return order;
}

/** The outlier bias offset chosen and the per-pair training association accuracy it gives. */
struct OutlierBiasCalibration
{
  double offset = 0.0;
  std::vector<double> association;
};

/** selectOutlierBiasOffset () with the scores of its choice. */
OutlierBiasCalibration
calibrateOutlierBias (const std::vector<ScanPair>& pairs, JointModel model, const std::vector<double>& grid)
{
  if (grid.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::selectOutlierBiasOffset] the grid is empty");
  if (pairs.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::selectOutlierBiasOffset] no pairs to score");
  const double learned = model.weights (matching::kOutlierBias);
  OutlierBiasCalibration best;
  double best_score = -1.0;
  for (double offset : grid) {
    model.weights (matching::kOutlierBias) = learned + offset;
    std::vector<double> association = trainingScores (pairs, model, &PairScores::association_accuracy);
    const double score = mean (association);
    if (score > best_score + 1e-9) {  // ties: the earlier value
      best_score = score;
      best.offset = offset;
      best.association = std::move (association);
    }
  }
  return best;
}

/** The node conditionals of every pair of \a pairs (jointNodeConditionals ()). */
std::vector<crf::NodeConditional>
jointTrainingNodes (const std::vector<ScanPair>& pairs, const JointModel& model)
{
  std::vector<crf::NodeConditional> nodes;
  for (const ScanPair& pair : pairs) {
    std::vector<crf::NodeConditional> more = jointNodeConditionals (pair, model);
    nodes.insert (nodes.end (), std::make_move_iterator (more.begin ()), std::make_move_iterator (more.end ()));
  }
  return nodes;
}

}  // namespace

std::size_t
selectWithinOneStandardError (const std::vector<std::vector<double>>& scores, const std::vector<std::size_t>& preference)
{
  if (scores.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::selectWithinOneStandardError] no candidates");
  if (preference.size () != scores.size ())
    throw std::invalid_argument ("[pcl_crf::joint::selectWithinOneStandardError] " +
                                 std::to_string (scores.size ()) + " candidates but a preference order of " +
                                 std::to_string (preference.size ()));
  std::vector<bool> ranked (scores.size (), false);
  for (std::size_t c : preference) {
    if (c >= scores.size () || ranked[c])
      throw std::invalid_argument ("[pcl_crf::joint::selectWithinOneStandardError] the preference order must list "
                                   "every candidate once");
    ranked[c] = true;
  }
  for (const std::vector<double>& s : scores)
    if (s.empty () || s.size () != scores.front ().size ())
      throw std::invalid_argument ("[pcl_crf::joint::selectWithinOneStandardError] every candidate needs a score "
                                   "on the same, non-empty set of pairs");
  std::vector<double> means;
  std::size_t best = 0;
  for (std::size_t c = 0; c < scores.size (); ++c) {
    means.push_back (mean (scores[c]));
    if (means[c] > means[best] + 1e-9)
      best = c;
  }
  for (std::size_t c : preference)  // the first in the preference order within one standard error
    if (means[best] - means[c] <= pairedStandardError (scores[best], scores[c]) + 1e-9)
      return c;
  return best;  // not reached: best itself is within
}

int
selectMinClusterPoints (const std::vector<ScanPair>& pairs, JointModel model, const std::vector<int>& grid)
{
  if (grid.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::selectMinClusterPoints] the grid is empty");
  if (pairs.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::selectMinClusterPoints] no pairs to score");
  for (const int value : grid)
    if (value < 1)
      throw std::invalid_argument ("[pcl_crf::joint::selectMinClusterPoints] grid values must be >= 1");
  if (grid.size () == 1)  // nothing to choose between
    return grid.front ();
  std::vector<std::vector<double>> scores;
  for (const int value : grid) {
    model.min_cluster_points = value;
    scores.push_back (trainingScores (pairs, model, &PairScores::v_measure));
  }
  // The least pruning within one standard error of the best (V of a pair jumps with one small object).
  return grid[selectWithinOneStandardError (scores, indicesInOrder (grid, std::less<int> ()))];
}

double
selectOutlierBiasOffset (const std::vector<ScanPair>& pairs, JointModel model, const std::vector<double>& grid)
{
  return calibrateOutlierBias (pairs, std::move (model), grid).offset;
}

std::vector<crf::NodeConditional>
jointNodeConditionals (const ScanPair& pair, const JointModel& model)
{
  if (!pair.hasTruth ())
    throw std::invalid_argument ("[pcl_crf::joint::jointNodeConditionals] pair '" + pair.name + "' has no ground truth");
  const matching::PreparedTarget target = matching::prepareTarget (pair.target, model.matcher.parameters.candidates);
  const matching::MotionGuess guess = matching::MotionGuess::fromOdometry (pair.odometry);
  AssociationStage stage = firstAssociationPass (pair.source, target, guess, model.matcher);
  LadderStart start = initialClusters (pair.source, pair.target, stage, model, {}, pair.odometry);
  jointPass (stage, target, guess, model.matcher, start);  // the association states inference will see
  const crf::ChainFeatures chain = matching::matchingChainFeatures (stage.source, target.scan, stage.pass, stage.scores,
                                                                    model.matcher.parameters.residual_scale);
  const LadderGeometry geometry =
      makeLadderGeometry (pair.source, pair.target, stage.pass.candidates, model.initial_clustering.features.min_spacing,
                          model.initial_clustering.features.min_neighbour_distance);
  const LadderTruth truth = ladderTruth (pair, stage.pass.candidates);
  std::vector<crf::NodeConditional> nodes;
  nodes.reserve (2 * static_cast<std::size_t> (geometry.size ()));
  for (int i = 0; i < geometry.size (); ++i) {
    nodes.push_back (associationNode (chain, geometry, truth, i));
    nodes.push_back (clusterNode (geometry, truth, i));
  }
  return nodes;
}

Eigen::VectorXd
learnJointWeights (const std::vector<ScanPair>& pairs, const JointModel& model, double prior_sigma,
                   const crf::LbfgsOptions& lbfgs)
{
  return crf::learnNodePseudoLikelihood (jointTrainingNodes (pairs, model), prior_sigma, lbfgs).x;
}

double
learnJointWeightsAndPrior (const std::vector<ScanPair>& pairs, const JointLearningOptions& options, JointModel& model)
{
  if (pairs.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::learnJointWeightsAndPrior] no training pair");
  if (options.prior_sigma_grid.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::learnJointWeightsAndPrior] the prior_sigma grid is empty");
  for (double sigma : options.prior_sigma_grid)
    if (!(sigma > 0.0))
      throw std::invalid_argument ("[pcl_crf::joint::learnJointWeightsAndPrior] every prior sigma must be > 0, got " +
                                   std::to_string (sigma));
  const std::vector<crf::NodeConditional> nodes = jointTrainingNodes (pairs, model);  // the same under every prior
  const std::vector<double>& grid = options.prior_sigma_grid;
  JointModel candidate = model;  // \a model changes only once every prior is learned
  std::vector<Eigen::VectorXd> weights;
  std::vector<std::vector<double>> association;
  for (double sigma : grid) {
    candidate.weights = crf::learnNodePseudoLikelihood (nodes, sigma, options.lbfgs).x;
    OutlierBiasCalibration bias = calibrateOutlierBias (pairs, candidate, options.outlier_bias_offset_grid);
    candidate.weights (matching::kOutlierBias) += bias.offset;
    weights.push_back (candidate.weights);
    association.push_back (std::move (bias.association));
  }
  const std::size_t chosen =
      selectWithinOneStandardError (association, indicesInOrder (grid, std::greater<double> ()));  // weakest first
  model.weights = weights[chosen];
  model.prior_sigma = grid[chosen];
  return mean (association[chosen]);
}

JointModel
trainJointModel (const std::vector<ScanPair>& pairs, const JointLearningOptions& options)
{
  if (pairs.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::trainJointModel] no training pair");
  JointModel model;
  model.matcher = matching::trainCrfMatching (pairs, options.matching);
  std::vector<std::vector<int>> associations;  // what the initial clustering will see: pass 1's
  for (const ScanPair& pair : pairs)
    associations.push_back (
        firstAssociationPass (pair.source, matching::prepareTarget (pair.target, options.matching.candidates),
                              matching::MotionGuess::fromOdometry (pair.odometry), model.matcher)
            .first_matches);
  const clustering::PriorSelection selection =
      clustering::learnWithCrossValidation (pairs, associations, options.clustering);
  model.initial_clustering.weights = selection.weights;
  model.initial_clustering.prior_sigma = selection.prior_sigma;
  model.initial_clustering.features = options.clustering.features;
  learnJointWeightsAndPrior (pairs, options, model);
  model.min_cluster_points = selectMinClusterPoints (pairs, model, options.min_cluster_points_grid);
  return model;
}

}  // namespace joint
}  // namespace pcl_crf
