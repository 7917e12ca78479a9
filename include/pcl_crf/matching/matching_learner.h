#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/matching_model.h>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief What the learner saw and reached in one stage (pass). */
struct StageTrainingReport
{
  /** fraction of training source points with a true match whose match is a candidate. */
  double candidate_recall = 0.0;
  /** (source point, candidate) samples of the data classifier, and how many are true matches. */
  long data_samples = 0;
  long data_positives = 0;
  /** source points, and how many are labelled with the outlier state. */
  long points = 0;
  long outlier_points = 0;
  /** negative log pseudo-likelihood plus prior at the learned weights. */
  double objective = 0.0;
  int lbfgs_iterations = 0;
  bool converged = false;
};

/** \brief Per-stage reports of a training run. */
struct TrainingReport
{
  std::vector<StageTrainingReport> stages;
};

/** \brief Learns a CRF-Matching model from labelled scan pairs.
 *
 *  For every pass k (parameters.passes): the candidates of every training pair
 *  under the pass's motion (the odometry guess in pass 1, the estimate of the
 *  trained pass 1 in pass 2); node labels = the position of the true match among
 *  the candidates, or the outlier state when the point has no true match or the
 *  match is not a candidate. Then
 *  1. data boosting: AdaBoost stumps on the raw pair features, positives = true
 *     candidates, negatives = the other candidates;
 *  2. outlier boosting: AdaBoost stumps on the raw point features, positives =
 *     points labelled outlier;
 *  3. CRF weights: maximum pseudo-likelihood with a Gaussian prior
 *     (crf::PseudoLikelihood, L-BFGS) on the chains of boosted features.
 *
 *  \param[in] pairs labelled pairs (ScanPair::hasTruth)
 *  \param[in] parameters settings, kept in the model
 *  \param[out] report per-stage statistics, when not null
 *  \throws std::invalid_argument for no pair, a pair without truth or bad parameters.
 *
 *  \code
 *  const auto model = pcl_crf::matching::trainCrfMatching (pcl_crf::loadDataset ("data/default/train"), {});
 *  pcl_crf::matching::saveModel (model, "crf-matching.model");
 *  \endcode
 */
CrfMatchingModel
trainCrfMatching (const std::vector<ScanPair>& pairs, const MatchingParameters& parameters,
                  TrainingReport* report = nullptr);

}  // namespace matching
}  // namespace pcl_crf
