#pragma once

#include <pcl_crf/clustering/clustering_model.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/joint/joint_features.h>
#include <pcl_crf/joint/ladder_inference.h>
#include <pcl_crf/matching/matching_model.h>

#include <Eigen/Core>

#include <iosfwd>
#include <string>

namespace pcl_crf {
namespace joint {

/** \brief How separateSegmentsThatMovedSlightly () weighs the evidence that a source
 *  segment moved by a few centimetres, less than its overlap radius. */
struct SlightMotionTest
{
  /** the least deviance, Σ (r_static² − r_own²) / σ² over the segment's points in view,
   *  that separates it (> 0). Under the static world's motion the deviance of a segment
   *  whose own motion (3 parameters) was fitted to it follows χ² with 3 degrees of
   *  freedom; default 32, which it exceeds with probability below 10⁻⁶, so that among
   *  the tens of segments of thousands of pairs a static one is hardly ever separated. */
  double min_deviance = 32.0;
  /** the least deviance per point counted (≥ 0): on average each point must favour the
   *  segment's own motion by this many variances. Along one surface the residuals are
   *  correlated (the static motion's error and the surface's shape are shared by
   *  neighbouring points), so a long segment can sum to min_deviance an effect no point
   *  shows. Default 1: one variance. */
  double min_mean_deviance = 1.0;
  /** the uncertainty of a residual along the surface, in beam steps of the target scan
   *  (≥ 0): where neighbouring beams land ρ Δφ apart on a surface ρ away, its outline
   *  between them is not known to better than a fraction of that, and the static
   *  motion's rotation moves far points more; σ² grows by (along_beam_steps ρ Δφ)².
   *  Default 0.5: half a beam spacing. */
  double along_beam_steps = 0.5;
};

/** \brief Settings of joint estimation (the runtime ones; a model brings its learned parts). */
struct JointParameters
{
  /** the modified loopy max-product belief propagation. */
  LadderOptions inference;
  /** the initial clusters: CRF-Clustering of the first association pass (its
   *  over-segmentation, merging and iteration settings). */
  clustering::CrfClusteringParameters initial_clustering;
  /** how the final CRF-Clustering, of the associations taken under the ladder's cluster
   *  motions, refits its clusters (its other settings are initial_clustering's). Default
   *  clustering::MotionFit::OwnPoints: there a small cluster's pairs follow its motion,
   *  and a large cluster's must not pull it away (on the real overtakes bag V 0.712 →
   *  0.743). The initial clustering keeps its own setting (Marginals by default): pass 1's
   *  associations are not yet taken under any cluster's motion, and OwnPoints there
   *  keeps small clusters of wrong associations as starts for the ladder. */
  clustering::MotionFit final_motion_fit = clustering::MotionFit::OwnPoints;
  /** true (default): in the final CRF-Clustering, chain neighbours with more beams
   *  without an associated return between them than the model's
   *  segment_max_missing_returns (10) share no weighted neighbour feature
   *  (clustering::FeatureOptions::weighted_neighbour_max_gap; the neighbour and
   *  stiffness features still couple them). On the real overtakes bag the final
   *  clustering joined world points across such a gap to a car 0.6 m from the sensor,
   *  rewarded by 1/d of a 0.3 m gap (V 0.837 → 0.854 without). The initial clustering
   *  keeps the paper's feature: the ladder's start is part of training, and the joint
   *  weights learned with the bound there moved to another plateau (docs/EXPERIMENTS.md). */
  bool bound_weighted_neighbours_by_missing_returns = true;
  /** rounds of inference → removal of vacuous and ambiguous clusters → inference (≥ 1); default 3. */
  int max_rounds = 3;
  /** a cluster with fewer MAP points than this is vacuous and removed [points];
   *  0 (default): the model's JointModel::min_cluster_points, chosen in training. */
  int min_cluster_points = 0;
  /** a cluster whose points' average effective number of clusters (Tipaldi & Ramos,
   *  eq. 8, on the clustering chain's beliefs) exceeds this is merged into the others;
   *  > 1, default 1.7. */
  double max_average_neff = 1.7;
  /** true (default): every source segment of the static world's initial cluster that the
   *  static motion leaves mostly unexplained, and that ICP on its nearest target points
   *  explains mostly, starts the ladder as a cluster of that motion
   *  (addSegmentMotionHypotheses ()). */
  bool add_segment_motion_hypotheses = true;
  /** true (default): a moving cluster of the ladder that the final CRF-Clustering put into
   *  the static world, holding every static point of its source segment, stays a cluster
   *  where the static motion explains fewer than half of its points in the target's view
   *  and its own motion more than half (keepLadderClustersTheFinalClusteringMerged ()). */
  bool keep_ladder_clusters_the_final_clustering_merges = true;
  /** true (default): a segment of the static world that ICP of its points explains
   *  better than the static motion, by more than the pair's residuals and the beams'
   *  spacing account for (slight_motion), becomes a cluster of its own
   *  (separateSegmentsThatMovedSlightly ()). */
  bool separate_segments_that_moved_slightly = true;
  /** how separateSegmentsThatMovedSlightly () weighs a segment's evidence, and
   *  check_free_space_motions_against_the_static_fit the static world's. */
  SlightMotionTest slight_motion;
  /** true (default): clusters whose matches mostly repeat target points the static world
   *  explains become outliers (removeClustersTheStaticWorldExplains ()). */
  bool remove_clusters_the_static_world_explains = true;
  /** true (default): of two moving clusters whose matches claim one target view, the one
   *  that moved farther from the static motion becomes outliers
   *  (removeClustersANearerClusterExplains ()). */
  bool remove_clusters_a_nearer_cluster_explains = true;
  /** true (default): clusters with more points the target saw through under their
   *  motion than matched points become outliers (removeClustersTheTargetSeesThrough ()). */
  bool remove_clusters_the_target_sees_through = true;
  /** true (default): clusters whose points the static motion puts on the target's
   *  outline, for more than half of them and at least as many as their own motion does,
   *  become outliers (removeClustersOnTheStaticOutline ()). */
  bool remove_clusters_on_the_static_outline = true;
  /** true (default): objects the static motion puts where the source saw through get a
   *  cluster of their own (separateObjectsInFreeSpace ()). */
  bool separate_objects_in_free_space = true;
  /** true (default): points that moved out of where the static motion puts them, paired
   *  with points that moved in (or with the object's other view hidden behind it), get
   *  clusters of their own (separatePointsTheTargetSeesThrough ()). */
  bool separate_points_the_target_sees_through = true;
  /** true (default): a static or unclustered segment the target saw through under the
   *  static motion gets a cluster of its own when sliding it to align its object end
   *  with a target segment's explains it better (separateSegmentsTheTargetSeesThrough ()). */
  bool separate_segments_the_target_sees_through = true;
  /** true (default): a slide separateObjectsInFreeSpace () finds for static points is
   *  dropped when the static motion fits the points to the target's outline better by
   *  slight_motion's deviance (at least min_deviance and min_mean_deviance per point, the
   *  roles of the motions swapped): on a rough real surface range noise puts a few
   *  points where the other sensor saw through. */
  bool check_free_space_motions_against_the_static_fit = true;
  /** the fewest points of a segment the target must see through under the static
   *  motion before a shift of it is sought (one point alone may be range noise), at the
   *  model's resolution: on scans thinned by k for the model (thinningFactor ()),
   *  estimateJoint asks k times as many, the same bearings. */
  int segment_min_points_seen_through = 2;
  /** true (default): moving clusters that hold consecutive points of one source segment
   *  and whose motions place the smaller one's points alike become one
   *  (mergeAdjacentClustersThatMoveAlike ()). */
  bool merge_adjacent_clusters_that_move_alike = true;
  /** true (default): the static world's points of a moving cluster's own source segment
   *  that its motion explains as well as the static motion join it
   *  (extendMovingClustersOverTheirSurfaces ()). */
  bool extend_moving_clusters_over_their_surfaces = true;
  /** true (default): a moving cluster whose points lie in parts more than part_gap
   *  apart becomes one cluster per part, each with its motion (separateDistantParts ()). */
  bool separate_distant_parts = true;
  /** true (default): outliers the target saw through where the static motion puts them
   *  are marked as moved away (markPointsThatMovedAway ()). */
  bool mark_points_that_moved_away = true;
  /** the largest distance between neighbouring points of one object [m], > 0; default 2:
   *  wider than the gaps a thin occluder or grazing incidence leaves in a vehicle's
   *  outline at these resolutions (about 1 m at 15 m, 1° per beam, 10° incidence),
   *  narrower than the space between vehicles in traffic. */
  double part_gap = 2.0;
  /** the laser that took both scans (SensorInfo: its beams), when known. When its beams
   *  go all round, the free-space steps above take the whole circle for its field of
   *  view, so that a sector of a 360° scan without returns is not taken for the
   *  sensor's back (matching::makeRangeProfile (scan, sensor)). beam_count 0 (default):
   *  unknown, the field of view is inferred from the returns. pcl_crf_eval and
   *  pcl_crf_run pass each pair's ScanPair::sensor. */
  SensorInfo sensor;
};

/** \brief \throws std::invalid_argument naming the first setting out of range. */
void
validateParameters (const JointParameters& parameters);

/** \brief A trained joint model: the association chain's boosted classifiers and
 *  passes (a CRF-Matching model: pass 1 gives the static motion and the first
 *  associations), the CRF-Clustering weights that propose the initial clusters, and
 *  the kJointWeightCount weights of the joint CRF, learned jointly.
 *
 *  \code
 *  const pcl_crf::joint::JointModel model = pcl_crf::joint::loadJointModel ("data/models/joint.model");
 *  \endcode
 */
struct JointModel
{
  matching::CrfMatchingModel matcher;
  clustering::CrfClusteringModel initial_clustering;
  Eigen::VectorXd weights = Eigen::VectorXd::Zero (kJointWeightCount);
  /** σ of the Gaussian prior the joint weights were learned with (informative). */
  double prior_sigma = 0.0;
  /** the smallest cluster kept [points] (≥ 1): chosen in training as the value of a
   *  small grid that gives the best mean V-measure on the training pairs. */
  int min_cluster_points = 3;

  /** \brief true when every part is trained. */
  bool
  isTrained () const;
};

/** \brief Version of the joint model file. */
constexpr int kJointModelVersion = 1;

/** \brief Writes the model as text: a header, the joint weights as `name value`
 *  lines, then the CRF-Clustering and CRF-Matching models in their own formats,
 *  each between `begin <part>` and `end <part>` lines. Round trips exactly. */
void
writeJointModel (const JointModel& model, std::ostream& os);

/** \brief Reads writeJointModel's text. \throws std::runtime_error "<name>: <problem>". */
JointModel
readJointModel (std::istream& is, const std::string& name = "joint model");

/** \brief Saves to a file. \throws std::runtime_error when it cannot be written. */
void
saveJointModel (const JointModel& model, const std::string& path);

/** \brief Loads from a file. \throws std::runtime_error naming the file and the problem. */
JointModel
loadJointModel (const std::string& path);

}  // namespace joint
}  // namespace pcl_crf
