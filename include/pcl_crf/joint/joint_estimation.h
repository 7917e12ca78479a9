#pragma once

#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/crf/chain_potentials.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/pass_geometry.h>
#include <pcl_crf/matching/robust_rigid_fit.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace joint {

/** \brief What the joint model finds for one scan pair (frames as in ScanPair).
 *
 *  \code
 *  const pcl_crf::joint::JointResult r = pcl_crf::joint::estimateJoint (pair.source, pair.target, pair.odometry, model);
 *  const pcl_crf::Rigid2d ego = r.T_source_target;                  // the sensor's motion
 *  for (int i : r.outliers) ...                                      // points no cluster explains
 *  \endcode
 */
struct JointResult
{
  /** per source point: its target point, or kNoMatch (the ladder's MAP decision). A
   *  matched point of one of the ladder's clusters has the target point nearest to
   *  where that cluster's final motion puts it (associateUnderClusterMotions ()). */
  std::vector<int> source_match;
  /** per source point: its cluster (numbered largest first), or kOutlierCluster. */
  std::vector<int> source_cluster;
  /** per cluster: T_target_source, mapping its source points into the target frame. */
  std::vector<Rigid2d> cluster_motions;
  /** per cluster: its number of source points. */
  std::vector<int> cluster_sizes;
  /** the static world (clustering::selectStaticCluster with the cluster sizes), or −1. */
  int static_cluster = -1;
  /** the sensor's motion: its pose at the target time in the source frame
   *  (the inverse of the static world's motion; the odometry without clusters). */
  Rigid2d T_source_target = Rigid2d::Identity ();
  /** source points in the outlier cluster, increasing. */
  std::vector<int> outliers;
  /** the outliers that moved away to where the target did not see them
   *  (markPointsThatMovedAway ()), or whose view in the target is another cluster's
   *  (removeClustersANearerClusterExplains ()), increasing: not the static world, their
   *  motion unknown. */
  std::vector<int> moved_away;
  /** clusters proposed by the initial CRF-Clustering. */
  int initial_clusters = 0;
  /** inference rounds (each followed by the removal of vacuous clusters). */
  int rounds = 0;
  /** belief-propagation iterations over all rounds. */
  int iterations = 0;
  /** true when the last round's inference converged. */
  bool converged = false;
};

/** \brief The association side of the joint CRF for one pair: CRF-Matching's first
 *  pass (its MAP associations and robust motion), then the candidates and boosted
 *  scores of the joint pass under that motion (stage 2 of the matcher's model).
 */
struct AssociationStage
{
  matching::ScanShape source;
  /** pass 1's MAP target of every source point, or kNoMatch. */
  std::vector<int> first_matches;
  /** pass 1's estimate of the static motion T_target_source. */
  Rigid2d T_first = Rigid2d::Identity ();
  /** pass 1's shape neighbours (the joint pass reuses them where provably exact). */
  matching::ShapeNeighbours first_shape_neighbours;
  /** the joint pass: candidates (the association states) and their raw geometry. */
  matching::PassGeometry pass;
  matching::BoostedScores scores;
};

/** \brief The state of the ladder inference starts from: cluster motions, and the
 *  association state and cluster (K = the outlier cluster) of every point. */
struct LadderStart
{
  std::vector<Rigid2d> motions;
  std::vector<int> association;
  std::vector<int> cluster;
};

/** \brief Pass 1 of CRF-Matching from the guess (fills source, first_matches, T_first).
 *  \param[in] matcher a trained CRF-Matching model */
AssociationStage
firstAssociationPass (const Eigen::Matrix2Xd& source, const matching::PreparedTarget& target,
                      const matching::MotionGuess& guess, const matching::CrfMatchingModel& matcher);

/** \brief The initial clusters: CRF-Clustering (the model's initial_clustering) of
 *  pass 1's associations; unassociated points start in the outlier cluster, the
 *  static world's cluster (nearest to the odometry) starts from pass 1's motion
 *  stage.T_first, and start.association is left empty (see jointPass). */
LadderStart
initialClusters (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const AssociationStage& stage,
                 const JointModel& model, const clustering::CrfClusteringParameters& parameters,
                 const Odometry& odometry);

/** \brief Motion hypotheses the initial clustering missed: an object that moved a little
 *  (a few centimetres near the sensor) gets pass 1's associations under the static
 *  motion, each a beam or two off its true target point, and CRF-Clustering fits them
 *  into the static world's cluster. So every source segment (matching::segmentScan ())
 *  with at least min_segment_points points in the static world's cluster (the one whose
 *  motion is \a T_static) is tested: when the static motion puts fewer than half of those
 *  points within their overlap radius (matching::overlapRadius () of their spacing on
 *  the segment) of a target point, and point-to-point ICP of them from T_static (nearest
 *  target points within overlap_radius, closed-form fits, eq. 6) puts more than half
 *  there, they start the ladder as a new cluster of the ICP's motion. The ladder then
 *  weighs it against the others like any initial cluster.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target_points kd-tree over the target scan [m, target frame]
 *  \param[in] T_static the static world's initial motion (initialClusters () gives it
 *  stage.T_first)
 *  \param[in] parameters the breakpoint angle, range noise, overlap radius and
 *  min_segment_points (the matcher's segment parameters)
 *  \param[in,out] start the initial clusters; the outlier cluster is renumbered after the new ones
 *  \return the number of clusters added
 *  \throws std::invalid_argument when \a start has not one cluster per source point. */
int
addSegmentMotionHypotheses (const Eigen::Matrix2Xd& source, const KnnIndex& target_points, const Rigid2d& T_static,
                            const matching::SegmentMotionParameters& parameters, LadderStart& start);

/** \brief The joint pass (fills stage.pass, stage.scores and start.association): the
 *  candidates under pass 1's motion, where every point of a cluster that moves
 *  relative to it takes that cluster's motion as its motion hypothesis (so its
 *  candidates include the target points near T_l s_i, and the boosted features
 *  measure the residuals under it); pass 1's associations become the initial states.
 */
void
jointPass (AssociationStage& stage, const matching::PreparedTarget& target, const matching::MotionGuess& guess,
           const matching::CrfMatchingModel& matcher, LadderStart& start);

/** \brief The joint CRF's association chain potentials w_a · f_a (CRF-Matching's features). */
crf::ChainPotentials
associationPotentials (const AssociationStage& stage, const matching::PreparedTarget& target, const JointModel& model);

/** \brief Joint scan matching, moving-object detection and motion estimation
 *  (Tipaldi & Ramos's joint model): CRF-Matching's first pass proposes the static
 *  motion and associations, CRF-Clustering of those proposes the clusters; then
 *  rounds of modified loopy max-product on the joint ladder CRF (inferLadder) with
 *  the motions refitted as messages flow, each followed by the removal of vacuous
 *  clusters (fewer than min_cluster_points points) and ambiguous ones (average
 *  N_eff above max_average_neff), until no cluster is removed. Then the static
 *  world's motion is refitted robustly, and every point the MAP matches and puts in a
 *  real cluster takes the target point nearest to where its cluster's motion puts it
 *  (the correspondence step of ICP under the final motions: the ladder chose among
 *  candidates found under earlier motions). Finally CRF-Clustering (the model's
 *  clustering weights, sum-product marginals, N_eff merging) of those associations
 *  gives the clusters and motions of the result, the static world's motion refitted
 *  robustly again: the ladder's hard refits let clusters whose motions differ by
 *  little collapse into one. On scans thinned to the training resolution the clusters
 *  are lifted to every point and the associations taken under the ladder's motions.
 *  (Before the ladder, source segments the static motion leaves unexplained and ICP
 *  explains join the initial clusters, addSegmentMotionHypotheses (); after the final
 *  clustering, the ladder's moving clusters it merged into the static world where the
 *  data say they moved are kept, keepLadderClustersTheFinalClusteringMerged ().)
 *  Last, clusters whose matches mostly repeat target points the static world explains
 *  are removed (removeClustersTheStaticWorldExplains ()), and so are clusters whose
 *  matches mostly repeat target points a cluster that moved less explains
 *  (removeClustersANearerClusterExplains ()) and clusters with more
 *  points the target saw through under their motion than matched points
 *  (removeClustersTheTargetSeesThrough ()) and clusters the static motion puts on the
 *  target's outline (removeClustersOnTheStaticOutline ()); then objects the static motion puts where
 *  the source saw through get clusters of their own (separateObjectsInFreeSpace ()),
 *  segments the static motion slides along themselves whose end the target saw
 *  through get clusters of their own (separateSegmentsTheTargetSeesThrough ()), and so
 *  do points that moved out of where the static motion puts them, paired with points
 *  that moved in or with the object's other view hidden behind it
 *  (separatePointsTheTargetSeesThrough ()), and segments of the static world that
 *  moved by less than their overlap radius (separateSegmentsThatMovedSlightly ()); then moving clusters that meet on one
 *  surface and move alike become one (mergeAdjacentClustersThatMoveAlike ()), and take
 *  the static points of their surface that their motion explains as well
 *  (extendMovingClustersOverTheirSurfaces ()); last, a
 *  moving cluster whose points lie in parts far apart becomes one cluster per part
 *  (separateDistantParts ()), and the outliers the target saw through where the static
 *  motion puts them are marked as moved away (markPointsThatMovedAway ()).
 *
 *  A point at exactly the coordinates of an earlier point of its scan is no return of
 *  its own (firstOfEqualPoints () in pcl_crf/core/repeated_points.h): the estimate runs
 *  on the first copies, and every copy takes its first copy's match, cluster and
 *  moved-away mark.
 *
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] odometry the sensor motion guess and its covariance (candidates, ego cluster)
 *  \param[in] model a trained model
 *  \param[in] parameters runtime settings
 *  \throws std::invalid_argument for an untrained model, invalid parameters, or
 *  empty or non-finite scans.
 */
JointResult
estimateJoint (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Odometry& odometry,
               const JointModel& model, const JointParameters& parameters = {});

/** \brief Every point of \a points takes the target point nearest to where the motion
 *  of its cluster puts it, with one batched query: the correspondence step of ICP under
 *  per-cluster motions.
 *  \param[in] source source scan [m, source frame]
 *  \param[in] target_points kd-tree over the target scan [m, target frame]
 *  \param[in] points source points to associate
 *  \param[in] cluster per source point: its cluster, an index into \a motions for \a points
 *  \param[in] motions per cluster: T_target_source
 *  \param[in,out] source_match per source point: its target point; only \a points change
 *  \throws std::invalid_argument for sizes that do not match, a point outside the scan
 *  or without a cluster motion, or an empty target. */
void
associateUnderClusterMotions (const Eigen::Matrix2Xd& source, const KnnIndex& target_points,
                              const std::vector<int>& points, const std::vector<int>& cluster,
                              const std::vector<Rigid2d>& motions, std::vector<int>& source_match);

/** \brief Gives back to the ladder's moving clusters the points the final CRF-Clustering
 *  merged into the static world, where the data say they moved. The final clustering
 *  starts from an over-segmentation of the scan, and a small object's points then see
 *  many near copies of the static world's motion, whose summed probability makes the
 *  object's own cluster look ambiguous (N_eff, eq. 8), so that it is merged. For every
 *  source segment (detail::ScanViews::sourceSegments ()) and moving cluster l of
 *  \a ladder: the segment's points in \a result's static world are all in l, they are
 *  more than half of the segment and at least min_segment_points, and of them, among
 *  those both motions place in the target's view (detail::placeInTarget ()), at least
 *  min_segment_points, the static motion explains fewer than half and l's motion more
 *  than half (a target point within their overlap radius). Then they become a cluster
 *  of l's motion, keeping their matches (the final clustering does not change them).
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the segments' and overlap radius' settings (the matcher's segment parameters)
 *  \param[in] ladder the ladder's clusters and motions over \a source
 *  \param[in,out] result the final clusters over \a source (renumbered largest first when one is added)
 *  \return the number of clusters added
 *  \throws std::invalid_argument when the results' sizes disagree with each other or with
 *  the scans, or a match is not a target point. */
int
keepLadderClustersTheFinalClusteringMerged (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                            const matching::SegmentMotionParameters& parameters,
                                            const JointResult& ladder, JointResult& result);

/** \brief Separates the source segments of the static world that moved by less than
 *  their overlap radius (a few centimetres near the sensor), which the steps that ask
 *  whether a target point lies within that radius cannot tell from the static world.
 *  For every source segment (detail::ScanViews::sourceSegments ()) with at least
 *  \a min_points points in \a result's static world, point-to-point ICP of those points
 *  from the static motion T_s (nearest target points within overlap_radius, eq. 6)
 *  gives its own motion T. The evidence is the deviance of the static motion against T,
 *  D = Σ_i (r_i(T_s)² − r_i(T)²) / σ_i², over the points both motions place in the
 *  target's view (detail::placeInTarget ()) that T_s does not hide behind a target
 *  return and does not place beyond the end of the target surface nearest to it (there
 *  the target does not show the surface, so a residual says nothing of motion).
 *  - r_i is the distance to the target's outline: to the nearer of the two pieces from
 *    the nearest target point to its neighbours on its target segment, capped at
 *    overlap_radius (a point that lands on nothing counts as landing that far).
 *  - σ_i² = σ_r² + (along_beam_steps · ρ_i · Δφ)² + median_j r_j(T_s)² / 0.4549:
 *    range_noise, the outline's uncertainty between beams ρ_i Δφ apart (ρ_i the point's
 *    range, Δφ the target's beam step), and the static motion's own misfit: the median
 *    squared residual under T_s of the points T_s places as above in every segment
 *    tested, scaled to a variance (0.4549 is the median of χ² with 1 degree of freedom),
 *    so that a pair whose static motion fits loosely everywhere needs more evidence.
 *  A segment with at least \a min_points such points, D ≥ test.min_deviance and
 *  D ≥ test.min_mean_deviance times their number, and whose
 *  motion T moves none of its points farther than overlap_radius from where T_s puts them
 *  (the ICP's gate: a farther move is ICP drifting over a few points, not a slight
 *  motion; larger motions are the free-space steps') becomes a cluster of motion T, and
 *  its matched points take the target point nearest to where T puts them
 *  (associateUnderClusterMotions ()). T is fitted only where D could reach the bar, were
 *  T to fit every point exactly. estimateJoint runs this after the
 *  free-space steps, which find larger motions with the target's help; ICP from the
 *  static motion reaches only motions within overlap_radius.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the segments' and overlap radius' settings and range_noise (the matcher's segment parameters)
 *  \param[in] test the least deviance, in all and per point, and the along-beam uncertainty
 *  \param[in] min_points the fewest points of a segment tested and of its evidence (≥ 1)
 *  \param[in,out] result the clusters over \a source (renumbered largest first when one is added)
 *  \return the number of clusters added
 *  \throws std::invalid_argument when the result's sizes disagree with the scans, a match
 *  is not a target point, \a test is out of range or \a min_points < 1. */
int
separateSegmentsThatMovedSlightly (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                   const matching::SegmentMotionParameters& parameters, const SlightMotionTest& test,
                                   int min_points, JointResult& result);

/** \brief Removes every cluster but the static world most of whose matched points (more
 *  than half) landed on target points the static world already explains: each lies
 *  within the overlap radius (matching::overlapRadius () of its spacing on the target
 *  scan) of a target point a static-world point is matched to. Such a cluster mostly
 *  repeats surfaces the static world accounts for (typically a stretch of façade that
 *  left the view, matched to the façade further on under a motion that slides it along
 *  itself, or a piece of a car whose other points the static world holds), so it is no
 *  evidence of a mover of its own: its points become outliers (kNoMatch,
 *  kOutlierCluster), free for separateObjectsInFreeSpace () to take. The other clusters keep their
 *  order; clusters without a matched point, or a result without a static world, stay.
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the overlap radius (the matcher's segment parameters)
 *  \param[in,out] result a joint result whose matches index \a target
 *  \return the number of clusters removed
 *  \throws std::invalid_argument when the result's sizes disagree or a match is not a
 *  target point. */
int
removeClustersTheStaticWorldExplains (const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Of two moving clusters that claim one view in the target, removes the one
 *  that moved farther from the static motion: taking the moving clusters in order of
 *  their mean displacement from the static motion (the points' distance between where
 *  the two motions put them), a cluster is removed when more than half of its matched
 *  points landed within their overlap radius (matching::overlapRadius () of its spacing
 *  on the target scan) of a target point that a cluster earlier in that order, and
 *  kept, is matched to. One surface seen in the target is one object's: in oncoming
 *  traffic a car that drives out of view behind the sensor is matched onto the car
 *  following it, which takes its place in the target. The removed cluster's points
 *  become outliers (kNoMatch, kOutlierCluster); those of a cluster whose points the
 *  static motion mostly (more than half) puts farther than their overlap radius from
 *  every target point are marked as moved away (JointResult::moved_away): not the
 *  static world, their motion unknown.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the overlap radius (the matcher's segment parameters)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters removed (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with each other or
 *  with the scans, a match is not a target point, or a scan holds a NaN point. */
int
removeClustersANearerClusterExplains (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Removes every cluster but the static world that the target scan refutes: more
 *  points of its extent land, under its motion, where the target sensor saw through
 *  (matching::seesThrough () with the breakpoint distance of \a parameters) than it has
 *  matched points. Its extent is its points and the outliers it would label (those
 *  whose nearer closest clustered neighbour along their source segment,
 *  matching::segmentScan (), is one of its points): a rigid object's points under its
 *  true motion are where the target saw them, hidden behind something or out of view,
 *  never in the target's free space. Typically a stretch of wall that left the view,
 *  whose last few points matched surfaces newly seen behind it: the motion that
 *  matches them sweeps the rest of the wall through the target's view; or a mover's
 *  few points fitted with a wrong motion. The removed clusters' points become outliers; the others keep their
 *  order (renumbered largest first).
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle and range noise (the matcher's segment parameters)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters removed
 *  \throws std::invalid_argument when the result's sizes disagree with each other or with
 *  \a source, or a match is not a target point. */
int
removeClustersTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Removes every cluster but the static world that is the static world seen at
 *  other places: more than half of its points, moved by the static motion, lie on the
 *  target's outline (within 3 range_noise of the pieces between a target point and its
 *  neighbours on the same target segment, matching::segmentScan () across missing
 *  returns), and at least as many as its own motion puts there. A surface seen at
 *  grazing incidence is sampled metres apart, so a motion that slides it by a whole
 *  number of samples matches its points to target points as well as the static motion,
 *  which puts them between the samples; and a moving object that slides along itself
 *  alone (the aperture problem) is no evidence against the static world, the simpler
 *  explanation. The removed clusters' points become outliers; the others keep their
 *  order (renumbered largest first).
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle and range noise (the matcher's segment parameters)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters removed
 *  \throws std::invalid_argument when the result's sizes disagree with each other or with
 *  \a source, or a match is not a target point. */
int
removeClustersOnTheStaticOutline (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                  const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Gives the static world's and the unclustered points that moved clusters of their
 *  own: a source point the static motion puts where the target sensor saw through to a
 *  return farther away (matching::seesThroughToAReturn (), the breakpoint distance of
 *  \a parameters) is no longer there, so it moved out; a target point the inverse motion
 *  puts where the source saw through to a return moved in, unless its target segment
 *  holds a point a moving cluster is matched to (that object after it moved). A scan's moved points group by
 *  their segment (matching::segmentScan ()), and a moved-out group pairs with the
 *  moved-in group whose centroid (in the target frame) is nearest to its own when it is
 *  that group's nearest too, within max_displacement: one object seen before and after
 *  it moved, down to a single point (a pedestrian far away). Each pair becomes a new
 *  cluster of the static motion shifted by the centroids' displacement; its points take
 *  the moved-in group's point nearest to where that motion puts them within its overlap
 *  radius (matching::overlapRadius ()), or no match. An object that came nearer along
 *  the line of sight leaves no moved-out group: under the static motion its source
 *  points hide behind it in the target (matching::hiddenBehindAReturn ()). So a
 *  moved-in group without a counterpart pairs, in the same way, with the group (by
 *  source segment) of static or outlier source points hidden from the target when each
 *  is the other's nearest, both groups have at least min_segment_points, most of
 *  its points lie in the moved-in group's shadow (within its bearings as the target
 *  sensor sees them, a step wider on each side): what hides an object's old view is the
 *  object; and no point of it has a neighbour on the next beam, within the breakpoint
 *  distance, that the static motion explains (puts within its overlap radius of its
 *  match): that is a surface hidden in the middle, a wall behind a walker, where an
 *  object's view ends at the object's edges. Likewise an object that went farther: a moved-out group without a
 *  counterpart pairs with the target points hidden from the source behind it. A group
 *  left without a counterpart (it left the view or hid behind something else) stays:
 *  there is no motion to give it. Beams without a return are no evidence here (real
 *  lasers drop returns where the scene is not free).
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle, range noise, overlap radius,
 *  min_segment_points and max_displacement (the matcher's segment parameters,
 *  limitToInterval () for the pair)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters added (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with each other or with
 *  \a source, or a match is not a target point. */
int
separatePointsTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Gives a segment the static motion slides along itself a cluster of its own: a
 *  truck driving alongside maps under the static motion onto its own side in the
 *  target, all but its trailing end, which lands where the target saw through.
 *
 *  For every source segment (matching::segmentScan (), ≥ min_segment_points) wholly in
 *  the static or the outlier cluster, with at least \a min_seen_through points the
 *  static motion puts where the target saw through to a return
 *  (matching::seesThroughToAReturn ()), the shifts that align one of its object ends
 *  with the same end of a target segment (matching::endAlignments ()) are compared
 *  with the static motion on the points both keep in the target's field of view
 *  (matching::inFieldOfView ()). A shift qualifies when it explains (a target point
 *  within the overlap radius, matching::overlapRadius ()) at least as many of them and
 *  leaves fewer seen through; of those, the one gaining most explained minus
 *  seen-through points makes the segment a cluster of the static motion shifted by it,
 *  each point matched to its nearest target point there within its overlap radius, or
 *  to none. When another qualifying shift farther than overlap_radius from that one
 *  gains as much or one point less, the segment's shape does not tell where it went (a
 *  leg or a post of a few points fits the end of many surfaces) and it is left alone. Beams without a
 *  return are no evidence (real lasers drop returns).
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle, range noise, overlap radius,
 *  min_segment_points and max_displacement (the matcher's segment parameters,
 *  limitToInterval () for the pair)
 *  \param[in] min_seen_through the fewest seen-through points that make a segment worth
 *  testing (≥ 1; JointParameters::segment_min_points_seen_through)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters added (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with each other or with
 *  \a source, a match is not a target point, or min_seen_through < 1. */
int
separateSegmentsTheTargetSeesThrough (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                      const matching::SegmentMotionParameters& parameters, int min_seen_through,
                                      JointResult& result);

/** \brief Separates from the static world the objects its motion puts where the source
 *  sensor saw through: a vehicle driving alongside shows a long side that slides along
 *  itself, which the static motion maps onto the same side in the target, so only its
 *  end and the free space around it show that it moved.
 *
 *  For every target segment (matching::segmentScan ()) some of whose points, moved back
 *  by the static motion, lie where the source saw through (matching::seesThrough ()),
 *  the candidate object is every static or outlier source point on the source segments
 *  the static motion puts on that target segment (nearest target point on it, within its
 *  overlap radius); when that object makes no cluster, the same is tried once more on
 *  the segment's surface, the segment and those it continues behind nearer occluders
 *  (matching::occludedSurfaces (): a crossing car that a pedestrian in front splits in
 *  two, its newly seen end one piece, the part the static motion explains the other).
 *  Unless some of those points is seen through firmly
 *  (matching::seesThroughFirmly (): not only beams a surface's edges dropped), nothing
 *  is searched, and the slide found must leave fewer points seen through firmly.
 *  Its motion slides the static motion along the principal axis of
 *  the target points the static motion puts the object on (not of the points of
 *  another surface the segment runs on into) and, when it differs, along that of those
 *  and the segment's points the source saw through (the newly seen side, which steadies
 *  the axis of a long slide that a few overlapped points would tilt); the axis whose run
 *  leaves fewer points seen through is tried first. Along each: on a grid of 2 overlap_radius steps
 *  within ±max_displacement (or less, where the object and the segment no longer
 *  overlap along the axis), then on a grid of the segment's own two overlap radii
 *  (overlapRadius () of its point spacing) around the best of those, the run of shifts
 *  with the fewest points either sensor saw through (target points moved back, object
 *  points moved forward) is found (a run of one or two grid shifts first bisected
 *  towards fewer between them, no finer than the segment's point spacing: a slide
 *  between two grid shifts), its ends refined by bisection, and its middle taken
 *  (the fine grid's run when it ends within the fine grid: a 1/10-scale car slides a
 *  few centimetres, a truck at 10 m a metre or more; slid too little, the target's end
 *  sticks out where the source saw through; too far, the
 *  source's end sticks out where the target saw through). The object becomes a new
 *  cluster when that run ends within reach on both sides (the slide is observed),
 *  resolves at least two and at least half of the static motion's points seen through
 *  (a lone mixed pixel is no evidence) and some shift of the run (its middle, then
 *  outwards at the segment's point spacing: free space does not place the object within
 *  the run) puts at least as many object points on the segment as the static motion:
 *  its points on the segment under the middle's motion take their nearest target point,
 *  the others no match. Clusters are renumbered largest first.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters segmentation, overlap radius and largest displacement (the
 *             matcher's segment parameters)
 *  \param[in,out] result a joint result for these scans
 *  \param[in] static_fit when given, a slide is dropped when the static motion fits the
 *             object to the target's outline better than the slid motion by this test's
 *             deviance, the roles of separateSegmentsThatMovedSlightly ()'s motions
 *             swapped: the points a rough surface's range noise put where the other
 *             sensor saw through are no evidence against a motion that fits it
 *             (JointParameters::check_free_space_motions_against_the_static_fit)
 *  \return the number of clusters added
 *  \throws std::invalid_argument when the result's sizes disagree with the scans, a
 *          match or cluster is out of range or \a static_fit is out of range. */
int
separateObjectsInFreeSpace (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                            const matching::SegmentMotionParameters& parameters, JointResult& result,
                            const SlightMotionTest* static_fit = nullptr);

/** \brief Marks the outliers that moved away (JointResult::moved_away): every run of at
 *  least min_segment_points consecutive outlier points of one source segment
 *  (matching::segmentScan ()) that the static motion puts where the target saw through
 *  to a return beyond them (matching::seesThroughToAReturn (); a direction without a
 *  return may be one the laser dropped), no point's target beam grazing the segment
 *  (meeting its direction at less than the breakpoint angle, where a few centimetres
 *  move the surface by whole beams). The static world does not explain them: an object
 *  that left the target's view, or went where the target did not see it, so its motion
 *  is unknown. Points stay in the outlier cluster; toPrediction () keeps them (and the
 *  outliers nearest them) there rather than giving them the static world's label.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters segmentation and breakpoint distance (the matcher's segment
 *             parameters)
 *  \param[in,out] result a joint result for these scans; the runs found join those of
 *  its moved_away that are still outliers
 *  \return the number of points marked (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with the scans or a
 *          match or cluster is out of range. */
int
markPointsThatMovedAway (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                         const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief A joint result as a Prediction for the metrics: the associations, the
 *  clusters with the outlier cluster's points given the cluster of their nearest
 *  labelled neighbour in the same distance segment (as CRF-M labels points without
 *  an association, so that both are scored alike; the points that moved away are
 *  labelled kOutlierCluster, so an outlier nearest them stays one too), the motions,
 *  the static cluster and the sensor's motion.
 *  \throws std::invalid_argument when the result's clusters or static cluster are not
 *  those of its motions, or it holds no entry per source point. */
Prediction
toPrediction (const Eigen::Matrix2Xd& source, const JointResult& result);

/** \brief Merges moving clusters that meet on one surface and move alike: two clusters
 *  holding consecutive points of one source segment (matching::segmentScan (), no
 *  breakpoint between them: one continuous surface) become one when the larger one's
 *  motion
 *  - places every point of the smaller within its overlap radius
 *    (matching::overlapRadius () of its spacing on its segment) of where the smaller
 *    one's own motion does, or
 *  - explains the smaller one's points as well as their own motion does: of the points
 *    both motions place in the target's field of view (and not at grazing incidence),
 *    at least as many lie within their overlap radius of a target point. A car's side
 *    seen alongside slides along itself; the target shows only its ends, so motions
 *    farther apart along it than the overlap radius are still alike to the data.
 *
 *  The merged cluster keeps the larger one's motion; matches are untouched. Steps that
 *  each separate part of one vehicle (the free space at its ends, the ladder's clusters
 *  in the middle) leave such neighbours. Runs until no pair is left; clusters are
 *  renumbered largest first.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle and range noise (segmentation) and the
 *             overlap radius (the matcher's segment parameters)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of clusters merged away (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with each other or
 *  with \a source, or a match is not a target point. */
int
mergeAdjacentClustersThatMoveAlike (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                    const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Extends moving clusters over the static world's points of their own surfaces:
 *  each run of consecutive static-world points on a source segment (matching::segmentScan (),
 *  no breakpoint: one continuous surface, one rigid object) joins a moving cluster holding
 *  the point just before or after it when that cluster's motion explains at least one of
 *  them and as many as the static motion does: of the points both motions place in the
 *  target's field of view (and not at grazing incidence), as many lie within their overlap
 *  radius of a target point. Of two such neighbours the one explaining more wins. The
 *  joined points take their nearest target point under the cluster's motion when within
 *  their overlap radius, or no match. A car's side seen alongside slides along itself:
 *  the static motion explains its middle as well as the car's does, and only its ends
 *  gave the car its cluster. Clusters are renumbered largest first.
 *  \param[in] source source scan in beam order [m, source frame]
 *  \param[in] target target scan in beam order [m, target frame]
 *  \param[in] parameters the breakpoint angle and range noise (segmentation) and the
 *             overlap radius (the matcher's segment parameters)
 *  \param[in,out] result a joint result over \a source whose matches index \a target
 *  \return the number of runs that joined a moving cluster (0 without a static world)
 *  \throws std::invalid_argument when the result's sizes disagree with each other or
 *  with \a source, or a match is not a target point. */
int
extendMovingClustersOverTheirSurfaces (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                       const matching::SegmentMotionParameters& parameters, JointResult& result);

/** \brief Splits every moving cluster whose points lie in parts more than \a gap apart
 *  into one cluster per part, each with the cluster's motion: objects that happen to
 *  move alike (cars in one lane at one speed, a cyclist beside a bus) are still
 *  separate objects, and a rigid motion alone cannot tell them apart.
 *
 *  The parts are the connected components of the cluster's source points, two points
 *  joined when they lie no farther apart than \a gap (single linkage, as
 *  pcl::EuclideanClusterExtraction). The static world stays whole, however far apart its
 *  surfaces; outliers and matches are untouched. Clusters are renumbered largest first.
 *  \param[in] source source scan [m, source frame]
 *  \param[in] gap the largest distance between neighbouring points of one object [m]
 *  (JointParameters::part_gap)
 *  \param[in,out] result a joint result over \a source
 *  \return the number of clusters added (0 without a static world)
 *  \throws std::invalid_argument for a gap that is not a distance > 0, or when the
 *  result's sizes disagree with each other or with \a source. */
int
separateDistantParts (const Eigen::Matrix2Xd& source, double gap, JointResult& result);

}  // namespace joint
}  // namespace pcl_crf
