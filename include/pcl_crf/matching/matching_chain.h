#pragma once

#include <pcl_crf/crf/chain_features.h>
#include <pcl_crf/crf/chain_potentials.h>
#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/pass_geometry.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief Unary features of the CRF-Matching chain (joint paper, Sec. IV-C 2).
 *  Node i has one state per candidate plus a last "outlier" state:
 *  f_u(i, candidate c) = [data margin of (i, c), 0, 0],
 *  f_u(i, outlier)     = [0, outlier margin of i, 1].
 */
enum UnaryFeature : int
{
  kDataMargin = 0,
  kOutlierMargin,
  kOutlierBias,
  kUnaryFeatureCount
};

/** \brief Pairwise features between neighbours i, i+1 in states (s, t)
 *  (joint paper, Sec. IV-C 2; Ramos et al., RSS 2007, Sec. IV-C). With j, j' the
 *  target points of s, t (when both are candidates), ρ(d) = d² / (d² + σ²) the
 *  Geman–McClure residual with σ = MatchingParameters::residual_scale:
 */
enum PairwiseFeature : int
{
  kSequence = 0,           ///< j' = j + 1: the chain keeps its order (the shifted identity)
  kSequenceRepeat,         ///< j' = j: two source points on one target point (sparser target)
  kSequenceSkip,           ///< j' = j + 2: one target point skipped (denser target)
  kOutlierSwitch,          ///< exactly one of s, t is the outlier state
  kOutlierRun,             ///< both are the outlier state
  kPairwiseDistance,       ///< ρ(| ||s_{i+1} − s_i|| − ||t_j' − t_j|| |)
  kPairwiseTranslation,    ///< ρ(|| R (s_{i+1} − s_i) − (t_j' − t_j) ||), R the rotation of T_current
  kPairwiseFeatureCount
};

/** \brief Number of CRF weights: kUnaryFeatureCount + kPairwiseFeatureCount. */
constexpr int kCrfWeightCount = kUnaryFeatureCount + kPairwiseFeatureCount;

/** \brief Features of the whole chain (for learning): unary[i] is S_i x kUnaryFeatureCount,
 *
 *  \code
 *  pcl_crf::crf::LabelledChain example{pcl_crf::matching::matchingChainFeatures (source, target.scan, pass,
 *                                                                             scores, 0.05), labels};
 *  const pcl_crf::crf::ChainPotentials chain = pcl_crf::matching::matchingChainPotentials (
 *      source, target.scan, pass, scores, model.stages[0].crf_weights, 0.05);
 *  const pcl_crf::crf::MapResult map = pcl_crf::crf::maxProduct (chain);
 *  \endcode
 *  pairwise[i] is (S_i S_{i+1}) x kPairwiseFeatureCount, row s + S_i t (crf::ChainFeatures).
 */
crf::ChainFeatures
matchingChainFeatures (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                       const BoostedScores& scores, double residual_scale);

/** \brief Log-potentials w · f of the same chain computed directly (for inference;
 *  equal to crf::potentials (matchingChainFeatures (…), weights) without building
 *  the feature matrices).
 *  \throws std::invalid_argument when weights.size () != kCrfWeightCount.
 */
crf::ChainPotentials
matchingChainPotentials (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                         const BoostedScores& scores, const Eigen::VectorXd& weights, double residual_scale);

/** \brief matchingChainPotentials () into a packed chain: the potentials in one buffer
 *  (\a chain keeps its capacity from call to call) and ready for crf::ChainInference
 *  without a copy.
 *  \param[out] chain the potentials (its previous content is replaced)
 *  \throws std::invalid_argument when weights.size () != kCrfWeightCount.
 */
void
matchingChainPotentials (const ScanShape& source, const ScanShape& target, const PassGeometry& pass,
                         const BoostedScores& scores, const Eigen::VectorXd& weights, double residual_scale,
                         crf::PackedChainPotentials& chain);

}  // namespace matching
}  // namespace pcl_crf
