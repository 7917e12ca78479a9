#pragma once

#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/crf/chain_features.h>
#include <pcl_crf/crf/chain_potentials.h>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Number of local features per (node, cluster): the residual f_dist (Eq. (2))
 *  seen robustly at two scales, the scan's sampling distance at the point and the
 *  beam spacing at its range (see chainFeatures ()). */
constexpr int kUnaryFeatureCount = 2;
/** \brief Number of pairwise features per (edge, cluster pair): neighbour (Eq. (4)),
 *  weighted neighbour (Eq. (5)) and stiffness (Eq. (6)). */
constexpr int kPairwiseFeatureCount = 3;
/** \brief Number of CRF-Clustering weights:
 *  [w_spacing_residual, w_beam_residual, w_neighbour, w_weighted_neighbour, w_stiffness]. */
constexpr int kWeightCount = kUnaryFeatureCount + kPairwiseFeatureCount;

/** \brief Names of the weights in order (used by the model file). */
const std::vector<const char*>&
weightNames ();

/** \brief Settings that define the features (part of a learned model). */
struct FeatureOptions
{
  /** distances between chain neighbours are clamped to at least this in the weighted
   *  neighbour feature (Eq. (5)), so that coincident points give a finite value [m];
   *  default 0.01 m. */
  double min_neighbour_distance = 0.01;
  /** the two scales of the local features (sampling distance, beam spacing) are
   *  clamped to at least this [m]; default 0.01 m. */
  double min_spacing = 0.01;
  /** chain neighbours with more than this many beams between them that hold no pair
   *  (beams without a return, or returns without an association) share no weighted
   *  neighbour feature (Eq. (5)); the neighbour (Eq. (4)) and stiffness (Eq. (6))
   *  features still couple them. Across such a run their distance does not say that
   *  they lie on one surface: the scan segmentation takes a run of more than 10
   *  missing returns for a breakpoint (matching::SegmentMotionParameters::
   *  max_missing_returns), while 1/d rewards two points 0.3 m apart with the same
   *  bonus at 0.6 m range, 30 beams apart, as at 20 m, one beam apart. −1: no bound,
   *  the paper's feature. An inference setting, not part of a model file (every model
   *  is trained without a bound; with it, the shipped CRF-Clustering weights moved by
   *  3 %): the joint model's final clustering sets it. Default −1. */
  int weighted_neighbour_max_gap = -1;
};

/** \brief The inverse squared scales of the local features, kUnaryFeatureCount x n
 *  [1/m²]: column i = (1 / max(h_i, h_min)², 1 / max(r_i Δθ, h_min)²) with h_i the
 *  sampling distance (PointPairs::spacing), r_i = ||s_i||, Δθ the angular resolution
 *  (PointPairs::angular_resolution), h_min = min_spacing. */
Eigen::MatrixXd
unaryScales (const PointPairs& pairs, const FeatureOptions& options);

/** \brief The local features of one residual: log(1 + f_dist · c_k) for every inverse
 *  squared scale c_k (a column of unaryScales ()). */
Eigen::VectorXd
unaryFeatures (double f_dist, const Eigen::Ref<const Eigen::VectorXd>& inverse_scales);

/** \brief Local log-potential of every cluster at every pair, S x n: w_u · f_u(i, l).
 *  \param[in] residuals S x n f_dist (squaredResiduals ())
 *  \param[in] weights all kWeightCount weights (the first kUnaryFeatureCount are used)
 */
Eigen::MatrixXd
localLogPotentials (const PointPairs& pairs, const Eigen::MatrixXd& residuals, const Eigen::VectorXd& weights,
                    const FeatureOptions& options);

/** \brief localLogPotentials () of the residuals of \a motions in one pass, written into
 *  \a local (resized to S x n): localLogPotentials (pairs, squaredResiduals (pairs,
 *  motions), weights, options) without the residual matrix, and with log(1 + x) for
 *  log1p (x), 40 % faster here and within 2e-15 in absolute value (the arguments
 *  are ≥ 0): the difference is rounding, far below what the potentials resolve.
 *  \param[in] scales unaryScales (pairs, options)
 */
void
localLogPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const Eigen::MatrixXd& scales,
                    const Eigen::VectorXd& weights, Eigen::MatrixXd& local);

/** \brief The clusters each node may take: \c states[i] lists cluster indices,
 *  increasing. Nodes may have different lists (clusters that cannot explain a
 *  pair are pruned from it).
 */
using CandidateStates = std::vector<std::vector<int>>;

/** \brief Every node may take every one of \a cluster_count clusters. */
CandidateStates
allStates (std::size_t node_count, int cluster_count);

/** \brief The CRF-Clustering features of a chain of point pairs (Sec. IV-A, IV-B):
 *  - unary, state l of node i: log(1 + f_dist(i, l) / h_i²) and
 *    log(1 + f_dist(i, l) / (r_i Δθ)²), with f_dist(i, l) = ||T_l s_i − g_i||² [m²]
 *    (Eq. (2)), h_i the sampling distance of the scan at s_i and r_i Δθ the beam
 *    spacing at its range: associations between scans are only as precise as the
 *    points are dense (far and grazing surfaces are sampled sparsely), so the
 *    residual is measured in those units, and through a logarithm (the negative
 *    log-likelihood of a Cauchy residual) so that a single wrong association costs a
 *    bounded amount instead of Eq. (2)'s unbounded square and cannot claim a cluster
 *    of its own against its neighbours (measured on data/default with 2 % of the
 *    associations moved 3–10 beams, learned on the same kind: V 0.69 with squared
 *    features, 0.95 with these; 0.967 and 0.964 with clean associations);
 *  - pairwise, edge (i, j = i + 1), states (k, l), d = ||s_i − s_j||:
 *    neighbour [k = l] (Eq. (4): its weight is λ1 − λ2, the only part of λ1, λ2 the
 *    distribution depends on), weighted neighbour [k = l] / max(d, d_min) [1/m]
 *    (Eq. (5); 0 across a gap of more than FeatureOptions::weighted_neighbour_max_gap
 *    beams), stiffness | ||T_k s_i − T_l s_j|| − d | [m] (Eq. (6)), how much
 *    the pair's distance changes when each point moves with its cluster.
 *  Rows follow crf::ChainFeatures with the states of \a states.
 *  \param[in] pairs the nodes (2 x n points)
 *  \param[in] motions T_target_source of every cluster
 *  \param[in] states candidate clusters of every node (see allStates ())
 *  \param[in] options feature settings
 *  \param[in] residuals optional S x n matrix of f_dist (squaredResiduals ()) to reuse
 */
crf::ChainFeatures
chainFeatures (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
               const FeatureOptions& options = {}, const Eigen::MatrixXd* residuals = nullptr);

/** \brief The log-potentials w · f of the same chain, computed directly (inference
 *  needs no feature table): equal to crf::potentials (chainFeatures (...), weights).
 *  \param[in] local S x n local log-potentials (localLogPotentials ())
 *  \param[in] weights the kWeightCount weights
 *  \throws std::invalid_argument when the sizes do not fit.
 */
crf::ChainPotentials
chainPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
                 const Eigen::MatrixXd& local, const Eigen::VectorXd& weights, const FeatureOptions& options = {});

/** \brief The same potentials written into \a chain, whose buffers are reused: an
 *  iterative caller builds a chain every round without allocating.
 *  \throws std::invalid_argument when the sizes do not fit or a node has no state.
 */
void
chainPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
                 const Eigen::MatrixXd& local, const Eigen::VectorXd& weights, const FeatureOptions& options,
                 crf::PackedChainPotentials& chain);

}  // namespace clustering
}  // namespace pcl_crf
