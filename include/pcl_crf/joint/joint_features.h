#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/candidates.h>
#include <pcl_crf/matching/matching_chain.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

/** \brief The weights of the joint model (joint paper, Sec. IV-C), in this order.
 *
 *  The association chain x^a keeps CRF-Matching's features (matching::UnaryFeature,
 *  matching::PairwiseFeature: data and outlier boosting; sequence, pairwise outlier,
 *  pairwise distance, pairwise translation). The clustering chain x^c has D = K + 1
 *  states per point, K clusters with motions x^RT = (T_0 … T_{K−1}) and the outlier
 *  cluster K. The rung between x^a_i and x^c_i carries the clustering local
 *  features, which read both chains and the motions:
 *  - cluster distance: for an association to target point t_j and a cluster l < K,
 *    log(1 + ||T_l s_i − t_j||² / h²) at the two scales of CRF-Clustering
 *    (clustering::unaryScales: the scan's sampling distance and beam spacing at s_i);
 *  - cluster inlier: the consistency of the two chains, an indicator for "matched but
 *    in the outlier cluster" (its weight is the outlier threshold) and one for
 *    "unmatched but in a real cluster"; an unmatched point in the outlier cluster is
 *    the reference (0), so that the rung never rewards giving up a match.
 *  The clustering pairwise features between x^c_i and x^c_{i+1} (d = ||s_{i+1} − s_i||):
 *  neighbour [k = l], weighted neighbour [k = l] / max(d, d_min), neighbour stiffness
 *  | ||T_k s_i − T_l s_{i+1}|| − d |, and pairwise outlier (exactly one / both in
 *  the outlier cluster).
 */
enum JointWeight : int
{
  // association chain: matching::kCrfWeightCount weights in matching's order
  kAssociationWeights = 0,
  // rungs x^a_i — x^c_i
  kRungSpacingResidual = matching::kCrfWeightCount,
  kRungBeamResidual,
  kRungMatchedOutlierCluster,
  kRungUnmatchedCluster,
  // clustering chain x^c_i — x^c_{i+1}
  kClusterNeighbour,
  kClusterWeightedNeighbour,
  kClusterStiffness,
  kClusterOutlierSwitch,
  kClusterOutlierRun,
  kJointWeightCount
};

/** \brief Names of the weights in order (the model file's keys). */
const std::vector<const char*>&
jointWeightNames ();

/** \brief The geometry the rung and clustering features read, fixed for one scan pair. */
struct LadderGeometry
{
  /** source points [m, source frame], n columns. */
  Eigen::Matrix2Xd source;
  /** target points [m, target frame]. */
  Eigen::Matrix2Xd target;
  /** association states of every source point: its candidates, then the outlier state. */
  matching::Candidates candidates;
  /** 2 x n inverse squared scales of the cluster-distance features [1/m²]. */
  Eigen::Matrix2Xd inverse_scales;
  /** n − 1 distances ||s_{i+1} − s_i|| [m]. */
  Eigen::VectorXd neighbour_distance;
  /** distances are clamped to at least this in the weighted neighbour feature [m]. */
  double min_neighbour_distance = 0.01;

  int
  size () const { return static_cast<int> (source.cols ()); }

  /** \brief Association states of point i (candidates + outlier). */
  int
  associationStates (int i) const { return candidates.count (i) + 1; }
};

/** \brief What makes \a geometry inconsistent, or "" when nothing does: candidates that
 *  are not compressed rows (offsets from 0, non-decreasing, ending at the number of
 *  targets), not one row per source point, or a candidate that is not a target point;
 *  inverse scales that are not one column per source point, or neighbour distances
 *  that are not one per pair of consecutive source points. makeLadderGeometry () gives
 *  consistent geometries; the functions below that read one check it. */
std::string
ladderGeometryProblem (const LadderGeometry& geometry);

/** \brief Builds the geometry of a pair from its candidates.
 *  \param[in] min_spacing lower bound of the residual scales [m] (clustering::FeatureOptions)
 *  \param[in] min_neighbour_distance lower bound of d in the weighted neighbour feature [m]
 *  \throws std::invalid_argument when the candidates do not fit the scans (ladderGeometryProblem ()).
 */
LadderGeometry
makeLadderGeometry (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                    const matching::Candidates& candidates, double min_spacing = 0.01,
                    double min_neighbour_distance = 0.01);

/** \brief The rung log-potentials of every point in one buffer: rung i is
 *  S_a(i) x (K + 1), column-major. One allocation per ladder instead of one matrix
 *  per point (a ladder of a few hundred points otherwise spends hundreds of
 *  allocations on its rungs alone).
 */
class RungPotentials
{
public:
  /** \brief Sizes rung i to associationStates (i) x (clusters + 1) for every point of
   *  \a geometry (the values are left unset; the buffer keeps its capacity). */
  void
  resize (const LadderGeometry& geometry, int clusters);

  /** \brief Number of rungs (points). */
  std::size_t
  size () const { return rows_.size (); }

  bool
  empty () const { return rows_.empty (); }

  /** \brief Columns of every rung: the clusters + 1. */
  int
  columns () const { return columns_; }

  /** \brief Rung i. */
  Eigen::Map<Eigen::MatrixXd>
  operator[] (std::size_t i) { return {values_.data () + offsets_[i], rows_[i], columns_}; }

  Eigen::Map<const Eigen::MatrixXd>
  operator[] (std::size_t i) const { return {values_.data () + offsets_[i], rows_[i], columns_}; }

private:
  std::vector<double> values_;
  std::vector<std::size_t> offsets_;  // rung i's first entry in values_
  std::vector<int> rows_;             // S_a(i)
  int columns_ = 0;                   // K + 1
};

/** \brief Rung log-potentials of every point under the K motions: rungs[i] is
 *  S_a x (K + 1) for point i, entry (s, l) = w · f_rung(s, l) (rungFeatures ()).
 *  \param[in] motions the K cluster motions T_target_source
 *  \throws std::invalid_argument for an inconsistent \a geometry (ladderGeometryProblem ())
 *  or weights that are not kJointWeightCount.
 */
void
rungPotentials (const LadderGeometry& geometry, const std::vector<Rigid2d>& motions, const Eigen::VectorXd& weights,
                RungPotentials& rungs);

/** \brief Column l (a real cluster) of every rung of rungPotentials () under a new
 *  motion T_l, with log(1 + x) for log1p (x): twice as fast here, and within 2e-15 in
 *  absolute value as the arguments are ≥ 0 (as clustering::localLogPotentials ()).
 *  \a rungs must already have their sizes.
 *  \throws std::invalid_argument when \a rungs do not have one rung per point or \a l
 *  is not a real cluster of theirs.
 */
void
updateRungColumn (const LadderGeometry& geometry, const Rigid2d& motion, const Eigen::VectorXd& weights, int l,
                  RungPotentials& rungs);

/** \brief Rung features of point i in states (s, l), kJointWeightCount wide (zeros outside
 *  the rung block). \param[in] motions the K cluster motions T_target_source
 *  \throws std::invalid_argument when i is not a point, s not one of its association
 *  states, l not in [0, K], or the state's candidate not a target point. */
Eigen::VectorXd
rungFeatures (const LadderGeometry& geometry, int i, int s, int l, const std::vector<Rigid2d>& motions);

/** \brief Clustering edge log-potential between points i and i + 1: (K + 1) x (K + 1).
 *  \param[in] moved_here 2 x K, column l = T_l s_i; \param[in] moved_next the same for s_{i+1}
 *  \param[out] potential already (K + 1) x (K + 1) (a reference, so that a ladder can keep
 *  all its edges in one buffer)
 *  \throws std::invalid_argument when i is not an edge of \a geometry, or the potential
 *  or the moved points do not fit K.
 */
void
clusterEdgePotential (const LadderGeometry& geometry, int i, const Eigen::Matrix2Xd& moved_here,
                      const Eigen::Matrix2Xd& moved_next, const Eigen::VectorXd& weights,
                      Eigen::Ref<Eigen::MatrixXd> potential);

/** \brief Clustering edge features in states (k, l), kJointWeightCount wide.
 *  \throws std::invalid_argument when i is not an edge of \a geometry or k, l not in [0, K]. */
Eigen::VectorXd
clusterEdgeFeatures (const LadderGeometry& geometry, int i, int k, int l, const std::vector<Rigid2d>& motions);

}  // namespace joint
}  // namespace pcl_crf
