#pragma once

#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Which per-point cluster probabilities the N_eff merge test (Eq. (8)) reads. */
enum class MergeEvidence
{
  /** p(x_i = l) ∝ exp(local log-potential): how well each motion alone explains
   *  pair i. Two copies of one motion share every point however the chain couples them. */
  Local,
  /** the chain's sum-product marginals (the paper's wording); on a strongly coupled
   *  chain they follow whole segments, so near-copies of a motion fitted to different
   *  segments look certain and survive. */
  Marginals
};

/** \brief Which pairs a cluster's motion is refitted to between rounds (Eq. (3)). */
enum class MotionFit
{
  /** every pair, weighted by its marginal p(x_i = l) (the paper's Eq. (3)). The
   *  small marginals of a large cluster's pairs pull a small cluster's motion towards
   *  its own: a few pairs of wrong associations are drawn back into the motions around
   *  them, but so is a small object whose motion differs from the world's by a few
   *  beam spacings. */
  Marginals,
  /** between rounds, the pairs whose MAP cluster it is, each weighted by its marginal
   *  (ownPointWeights ()): for associations taken under the clusters' motions, where a
   *  small cluster's pairs agree with it. On a real 1/10-scale car 0.5 m away moving
   *  5 cm against the walls, 130 wall pairs of marginal 0.05–0.1 outweighed the car's
   *  14 in its Marginals fit, the two motions met, and N_eff merged the car away. The
   *  motions returned after the last round are Eq. (3)'s all the same: there the far
   *  pairs' small marginals steady a small cluster's rotation (a 4-point pedestrian's
   *  own pairs turned it by 0.17 rad where it did not turn). */
  OwnPoints
};

/** \brief Settings of CRF-Clustering inference (Tipaldi & Ramos, IROS 2009, Sec. IV-D, IV-E). */
struct CrfClusteringParameters
{
  // ---- initial over-segmentation (Sec. IV-D)
  /** consecutive pairs whose source points are farther apart than this start a new
   *  initial cluster [m]; default 0.5 m. */
  double segment_break_distance = 0.5;
  /** an initial cluster holds at most this many pairs (≤ 0: no cap) [pairs]; default 20. */
  int max_segment_points = 20;
  /** at most this many initial clusters: on a scan of more than max_segment_points times
   *  as many pairs, an initial cluster holds up to ⌈n / max_initial_clusters⌉ pairs
   *  instead, and when the breaks at segment_break_distance still make more, the
   *  segments stay apart only at their max_initial_clusters − 1 widest breaks
   *  (mergeNarrowestBreaks ()). Every round costs clusters × pairs: 100 000 pairs in
   *  5 000 clusters took minutes, 20 000 scattered pairs (one segment each) took over
   *  600 s and 3 GB. ≥ 1, default 256. */
  int max_initial_clusters = 256;

  // ---- iterations
  /** at most this many rounds of refit → features → belief propagation → merge;
   *  ≥ 1, default 20 (the paper reports 3–7). */
  int max_iterations = 20;
  /** a cluster whose points' average N_eff (Eq. (8)) exceeds this is merged into the
   *  others [clusters]; > 1, default 1.7 (paper). */
  double max_average_neff = 1.7;
  /** what N_eff is computed from; default MergeEvidence::Local. */
  MergeEvidence merge_evidence = MergeEvidence::Local;
  /** which pairs refit each cluster's motion after a round; default MotionFit::Marginals. */
  MotionFit motion_fit = MotionFit::Marginals;
  /** a cluster whose local log-potential at a node is more than this below the
   *  node's best is not a state of that node (keeps inference near O(n)) [nats];
   *  > 0, default 30 (its probability is below e⁻³⁰ before neighbours are counted). */
  double pruning_margin = 30.0;
  /** a node takes at most this many clusters, its best by local log-potential
   *  (beam pruning; exact when no node has more plausible clusters) [clusters];
   *  ≥ 1, default 5. */
  int max_states = 5;

  /** the feature definition (must match the weights' model). */
  FeatureOptions features;
};

/** \brief Outcome of CRF-Clustering on one chain of point pairs. */
struct CrfClusteringResult
{
  /** MAP cluster of every pair, clusters numbered by decreasing size. */
  std::vector<int> labels;
  /** S x n, column i = p(x_i = l) from sum-product (after the last merge). */
  Eigen::MatrixXd marginals;
  /** T_target_source of every cluster (Eq. (3), weighted by the marginals). */
  std::vector<Rigid2d> motions;
  /** pairs labelled with each cluster. */
  std::vector<int> sizes;
  /** the static world (selectStaticCluster with the cluster sizes; without odometry the largest cluster), or −1. */
  int static_cluster = -1;
  /** clusters of the initial over-segmentation. */
  int initial_clusters = 0;
  /** rounds performed. */
  int iterations = 0;
  /** true when the MAP labelling stopped changing before max_iterations. */
  bool converged = false;
};

/** \brief \throws std::invalid_argument naming the first invalid setting. */
void
validateParameters (const CrfClusteringParameters& parameters);

/** \brief Whether \a fit is one of MotionFit's values (not an integer cast to it). */
bool
isMotionFit (MotionFit fit);

/** \brief Clusters point pairs by their rigid motion with a chain CRF (Sec. IV).
 *
 *  Initialises one cluster per segment of the distance over-segmentation, then
 *  repeats: motions fitted to the current weights (Eq. (3); first the segments, then
 *  the marginals, see MotionFit) → local and pairwise features (Eqs. (2), (4)–(6)) → exact
 *  sum-product marginals and max-product MAP on the chain → removal of clusters left
 *  without a MAP point and of ambiguous clusters (Eq. (8)), until the MAP labelling
 *  and the set of clusters stop changing. The static cluster is the most probable
 *  under the odometry (Mahalanobis) and a prior proportional to cluster size
 *  (selectStaticCluster).
 *
 *  The inference buffers (candidate states, packed chain, messages: a few hundred KB
 *  for a 361-beam scan) are kept per thread from call to call, so that repeated calls
 *  do not allocate them again.
 *
 *  \code
 *  pcl_crf::clustering::CrfClusteringParameters parameters;
 *  const auto result = pcl_crf::clustering::clusterPointPairs (pairs, weights, parameters, &pair.odometry);
 *  \endcode
 *  \param[in] pairs the associated pairs in scan order
 *  \param[in] weights [w_spacing_residual, w_beam_residual, w_neighbour, w_weighted_neighbour,
 *             w_stiffness] (kWeightCount)
 *  \param[in] parameters inference settings
 *  \param[in] odometry the sensor motion, or null (the largest cluster is then static)
 *  \throws std::invalid_argument for wrong or non-finite weights or invalid parameters.
 */
CrfClusteringResult
clusterPointPairs (const PointPairs& pairs, const Eigen::VectorXd& weights,
                   const CrfClusteringParameters& parameters = {}, const Odometry* odometry = nullptr);

}  // namespace clustering
}  // namespace pcl_crf
