#pragma once

#include <pcl_crf/clustering/clustering_learning.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Outcome of choosing the prior of pseudo-likelihood learning by cross-validation. */
struct PriorSelection
{
  /** the chosen σ and the weights learned with it on every training pair. */
  double prior_sigma = 0.0;
  Eigen::VectorXd weights;
  /** the candidates and their mean held-out V-measure. */
  std::vector<double> grid;
  std::vector<double> scores;
};

/** \brief Learns the CRF-Clustering weights with the prior σ chosen by k-fold
 *  cross-validation on the training pairs.
 *
 *  With the true motions and the neighbours clamped to their true labels the training
 *  chains are (nearly) separable, so pseudo-likelihood fixes the direction of the
 *  weights but not their scale: σ sets it, and with it how sharply inference tells
 *  motions apart and how readily clusters merge (Eq. (8)). Each candidate σ is scored
 *  by the mean V-measure of clusterScan () on held-out pairs (pair k is in fold
 *  k mod \a folds); the best (ties: the smaller σ) is then used on all pairs.
 *
 *  \code
 *  const auto selection = pcl_crf::clustering::learnWithCrossValidation (pcl_crf::loadDataset ("data/default/train"), {});
 *  \endcode
 *  \param[in] training labelled pairs (their true associations and objects are used)
 *  \param[in] parameters inference settings used to score the held-out pairs
 *  \param[in] grid candidate σ, each > 0; default 10, 30, 100, 300, 1000
 *  \param[in] folds number of folds, ≥ 2 (fewer pairs than folds: no cross-validation,
 *             the middle candidate is used)
 *  \param[in] options L-BFGS settings (prior_sigma is ignored)
 *  \throws std::invalid_argument for an empty grid, σ ≤ 0, folds < 2 or pairs without truth.
 */
PriorSelection
learnWithCrossValidation (const std::vector<ScanPair>& training, const CrfClusteringParameters& parameters,
                          const std::vector<double>& grid = {10.0, 30.0, 100.0, 300.0, 1000.0}, int folds = 3,
                          const LearningOptions& options = {});

/** \brief The same over other associations: \a associations[k] are those of training
 *  pair k (per source point a target index or kNoMatch), used both to learn and to
 *  score the held-out pairs. */
PriorSelection
learnWithCrossValidation (const std::vector<ScanPair>& training, const std::vector<std::vector<int>>& associations,
                          const CrfClusteringParameters& parameters,
                          const std::vector<double>& grid = {10.0, 30.0, 100.0, 300.0, 1000.0}, int folds = 3,
                          const LearningOptions& options = {});

}  // namespace clustering
}  // namespace pcl_crf
