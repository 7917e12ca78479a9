#pragma once

#include <pcl_crf/crf/chain_potentials.h>
#include <pcl_crf/joint/joint_features.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace joint {

/** \brief The order in which the messages of the ladder are updated.
 *
 *  The ladder (association chain, clustering chain, one rung per point) has loops,
 *  so max-product is iterated; the schedule decides how fast evidence travels.
 */
enum class MessageSchedule
{
  /** the joint paper's Algorithm 1: every message of an iteration is computed from
   *  the previous iteration's messages, then the motions are refitted. Evidence moves
   *  one point per iteration, so a chain of n points needs about n iterations (the
   *  paper names this schedule as its bottleneck). */
  Flooding,
  /** a forward then a backward pass along the ladder, each node sending its messages
   *  (rung first, then along both chains) as soon as it is visited and its motions'
   *  refit following at once: exact on each chain alone, and evidence crosses the
   *  whole scan in one iteration. */
  Sweep
};

/** \brief What LadderResult::cluster_evidence measures at a point. */
enum class ClusterEvidence
{
  /** the rung potential at the point's MAP association state. */
  MapAssociation,
  /** the best association under each cluster: max_s unary(s) + rung(s, l), so that a
   *  cluster fitted to a few wrong associations competes with the clusters that
   *  explain the same points through other candidates. */
  BestAssociation
};

/** \brief Settings of the modified loopy max-product belief propagation. */
struct LadderOptions
{
  /** default MessageSchedule::Sweep. */
  MessageSchedule schedule = MessageSchedule::Sweep;
  /** iterations at most (≥ 1); default 10 (Flooding needs about the number of points). */
  int max_iterations = 10;
  /** fraction of the previous message kept, log domain, in [0, 1); default 0. */
  double damping = 0.0;
  /** converged when an iteration changes no MAP state and no log-message entry by
   *  more than this [nats], ≥ 0; default 0.1. */
  double tolerance = 0.1;
  /** what cluster_evidence measures; default ClusterEvidence::BestAssociation. */
  ClusterEvidence evidence = ClusterEvidence::BestAssociation;
  /** a cluster is refitted only while its MAP pairs weigh at least this [pairs], ≥ 2; default 3. */
  int min_fit_points = 3;
};

/** \brief \throws std::invalid_argument naming the settings out of range. */
void
validateLadderOptions (const LadderOptions& options);

/** \brief What the ladder inference returns (MAP states and the refitted motions). */
struct LadderResult
{
  /** MAP association state of every point (LadderGeometry::candidates order; the last is the outlier state). */
  std::vector<int> association;
  /** MAP cluster of every point, K meaning the outlier cluster. */
  std::vector<int> cluster;
  /** T_target_source of the K clusters, refitted from the MAP pairs (eq. 6). */
  std::vector<Rigid2d> motions;
  /** (K + 1) x n: normalised max-marginal beliefs of the clustering chain. */
  Eigen::MatrixXd cluster_beliefs;
  /** (K + 1) x n: how well each cluster alone explains point i under the final
   *  motions, p(l) ∝ exp(evidence), see ClusterEvidence (the local evidence of
   *  CRF-Clustering's merge test: two copies of one motion share it). */
  Eigen::MatrixXd cluster_evidence;
  int iterations = 0;
  /** true when an iteration changed no MAP state and no message (LadderOptions::tolerance). */
  bool converged = false;
  /** true when the iterations stopped because they oscillated: no node reached a MAP
   *  state it had not held in the two iterations before (a few nodes flipping back
   *  and forth with their clusters' refits, see MapHistory). */
  bool oscillating = false;
};

/** \brief Modified loopy max-product belief propagation on the ladder of the joint
 *  model (joint paper, Algorithm 1): the motions x^RT are treated as observed and the
 *  rung and clustering-edge potentials that depend on them are recomputed at every
 *  node visit. Each node's pair (s_i → t_j of its MAP states) moves between its
 *  clusters' running sums (RigidFitAccumulator) as soon as its MAP state changes, in
 *  O(1); the motions are solved from the sums in closed form (eq. 6) after every
 *  iteration. (Solving after every single node, as the paper's Algorithm 1 does, lets
 *  a cluster whose first nodes have just switched pull the following nodes back to
 *  the old motion.) Stops when an iteration changes no MAP state and no message by
 *  more than the tolerance, when it only alternates nodes between states they held
 *  in the two iterations before (LadderResult::oscillating), or at the limit.
 *
 *  \code
 *  const pcl_crf::joint::LadderResult r = pcl_crf::joint::inferLadder (
 *      geometry, association_chain, weights, motions, initial_association, initial_cluster, {});
 *  \endcode
 *  \param[in] geometry points, association states and feature scales
 *  \param[in] association the association chain's log-potentials (w · f of CRF-Matching's features)
 *  \param[in] weights the kJointWeightCount weights
 *  \param[in] motions the K initial cluster motions (K ≥ 1)
 *  \param[in] initial_association initial association state of every point (seeds the refits)
 *  \param[in] initial_cluster initial cluster of every point, in [0, K]
 *  \param[in] options schedule and limits
 *  \throws std::invalid_argument when the sizes do not fit, the geometry is inconsistent
 *  (ladderGeometryProblem ()) or the options are invalid.
 */
LadderResult
inferLadder (const LadderGeometry& geometry, const crf::ChainPotentials& association, const Eigen::VectorXd& weights,
             const std::vector<Rigid2d>& motions, const std::vector<int>& initial_association,
             const std::vector<int>& initial_cluster, const LadderOptions& options = {});

}  // namespace joint
}  // namespace pcl_crf
