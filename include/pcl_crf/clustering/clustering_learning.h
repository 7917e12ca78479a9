#pragma once

#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/crf/chain_features.h>
#include <pcl_crf/crf/lbfgs_minimizer.h>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Settings of maximum pseudo-likelihood learning (Sec. IV-C). */
struct LearningOptions
{
  /** standard deviation of the Gaussian prior on every weight (> 0); default 1000:
   *  nearly maximum pseudo-likelihood. The distance weights are precisions in 1/m²
   *  and reach tens, so a tight prior (crf::PseudoLikelihood's default 10) would
   *  bias them towards 0 and blur small motions. */
  double prior_sigma = 1000.0;
  /** stopping rules of L-BFGS. */
  crf::LbfgsOptions lbfgs;
};

/** \brief A training chain from labelled pairs: the clusters are the distinct
 *  labels (renumbered 0, 1, ... in order of first appearance), their motions the
 *  least-squares fits of their true pairs (Eq. (3)), every node may take every cluster.
 *
 *  \code
 *  std::vector<pcl_crf::crf::LabelledChain> chains;
 *  chains.push_back (pcl_crf::clustering::makeTrainingChain (pairs, object_of_each_pair));
 *  const Eigen::VectorXd weights = pcl_crf::clustering::learnWeights (chains).x;
 *  \endcode
 *  \param[in] pairs the associated pairs in scan order
 *  \param[in] labels the true object (any integer id) of every pair
 *  \param[in] options the feature definition
 *  \throws std::invalid_argument when the label count differs from the pair count.
 */
crf::LabelledChain
makeTrainingChain (const PointPairs& pairs, const std::vector<int>& labels, const FeatureOptions& options = {});

/** \brief Learns [w_spacing_residual, w_beam_residual, w_neighbour, w_weighted_neighbour, w_stiffness] by
 *  maximum pseudo-likelihood with L-BFGS (crf::PseudoLikelihood), from w = 0.
 *  \throws std::invalid_argument when no chain has a node, or for invalid chains.
 */
crf::LbfgsResult
learnWeights (const std::vector<crf::LabelledChain>& chains, const LearningOptions& options = {});

}  // namespace clustering
}  // namespace pcl_crf
