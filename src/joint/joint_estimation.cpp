#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/ego_cluster.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/repeated_points.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/lifted_matches.h>

#include "cluster_numbering.h"
#include "lifted_copies.h"
#include "scan_views.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace joint {

using detail::numberLargestFirst;

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::joint::estimateJoint] " + what);
}

[[noreturn]] void
failIn (const char* function, const std::string& what)
{
  throw std::invalid_argument (std::string ("[pcl_crf::joint::") + function + "] " + what);
}

/** \throws std::invalid_argument, naming \a function, when a match of \a result is not a
 *  point of \a target. */
void
checkMatches (const char* function, const Eigen::Matrix2Xd& target, const JointResult& result)
{
  for (std::size_t i = 0; i < result.source_match.size (); ++i) {
    const int j = result.source_match[i];
    if (j != kNoMatch && (j < 0 || j >= target.cols ()))
      failIn (function, "point " + std::to_string (i) + " is matched to target point " + std::to_string (j) + " of " +
                            std::to_string (target.cols ()));
  }
}

/** The clusters worth keeping after a round: not ambiguous (Tipaldi & Ramos eq. 8 on
 *  the local evidence of the points they hold) and not vacuous. Points of a
 *  removed cluster move to their best kept one. \return true when one was removed. */
bool
pruneClusters (const LadderResult& round, const JointParameters& parameters, int min_points, LadderStart& next)
{
  const int clusters = static_cast<int> (round.motions.size ());
  std::vector<int> members;  // points in a real cluster
  for (int i = 0; i < static_cast<int> (round.cluster.size ()); ++i)
    if (round.cluster[i] < clusters)
      members.push_back (i);
  Eigen::MatrixXd beliefs (clusters, static_cast<Eigen::Index> (members.size ()));
  std::vector<int> labels (members.size ());
  for (std::size_t m = 0; m < members.size (); ++m) {
    beliefs.col (m) = round.cluster_evidence.col (members[m]).head (clusters);
    labels[m] = round.cluster[members[m]];
  }
  std::vector<int> kept = members.empty () ? std::vector<int>{0}
                                           : clustering::selectClusters (beliefs, labels, parameters.max_average_neff);
  const std::vector<int> sizes = clustering::clusterSizes (labels, clusters);
  std::vector<int> solid;
  for (int l : kept)
    if (sizes[l] >= min_points)
      solid.push_back (l);
  if (solid.empty ())  // never remove every cluster: keep the largest
    solid.push_back (static_cast<int> (std::max_element (sizes.begin (), sizes.end ()) - sizes.begin ()));
  if (static_cast<int> (solid.size ()) == clusters)
    return false;
  // Renumber: the kept clusters 0 … K'−1, the outlier cluster K'.
  const int outlier = static_cast<int> (solid.size ());
  std::vector<int> rank (static_cast<std::size_t> (clusters + 1), -1);
  for (int k = 0; k < outlier; ++k)
    rank[solid[k]] = k;
  next.motions.clear ();
  for (int l : solid)
    next.motions.push_back (round.motions[l]);
  next.association = round.association;
  next.cluster.assign (round.cluster.size (), outlier);
  for (std::size_t i = 0; i < round.cluster.size (); ++i) {
    if (round.cluster[i] >= clusters)
      continue;
    int best = -1;  // the most believed kept cluster
    for (int l : solid)
      if (best < 0 || round.cluster_beliefs (l, i) > round.cluster_beliefs (best, i))
        best = l;
    next.cluster[i] = rank[rank[round.cluster[i]] >= 0 ? round.cluster[i] : best];
  }
  return true;
}

/** Fills the result from the last round: clusters numbered largest first, the
 *  static one nearest to the odometry. */
void
assemble (const LadderResult& round, const matching::Candidates& candidates, const Odometry& odometry,
          JointResult& result)
{
  const int clusters = static_cast<int> (round.motions.size ());
  const int n = static_cast<int> (round.cluster.size ());
  result.cluster_motions = round.motions;
  result.source_match.assign (static_cast<std::size_t> (n), kNoMatch);
  result.source_cluster.assign (static_cast<std::size_t> (n), kOutlierCluster);
  for (int i = 0; i < n; ++i) {
    if (round.association[i] < candidates.count (i))
      result.source_match[i] = candidates.target (i, round.association[i]);
    if (round.cluster[i] < clusters)  // the outlier cluster K stays kOutlierCluster
      result.source_cluster[i] = round.cluster[i];
  }
  numberLargestFirst (result);
  result.static_cluster = clustering::selectStaticCluster (result.cluster_motions, odometry, result.cluster_sizes);
  result.T_source_target =
      result.static_cluster >= 0 ? result.cluster_motions[result.static_cluster].inverse () : odometry.T_source_target;
}

/** The static world's motion re-estimated from its MAP pairs with CRF-Matching's
 *  robust point-to-line fit and the odometry prior (the ladder's closed-form refits
 *  are point-to-point least squares, which walls bias along themselves). */
void
refineStaticMotion (const Eigen::Matrix2Xd& source, const matching::PreparedTarget& target,
                    const matching::Candidates& candidates, const matching::MotionGuess& guess,
                    const matching::RobustFitParameters& fit, JointResult& result)
{
  if (result.static_cluster < 0)
    return;
  std::vector<int> matches (result.source_match.size (), kNoMatch);
  for (std::size_t i = 0; i < matches.size (); ++i)
    if (result.source_cluster[i] == result.static_cluster)
      matches[i] = result.source_match[i];
  Rigid2d& T_static = result.cluster_motions[result.static_cluster];
  T_static = matching::robustRigidFit (source, target.scan.points, target.normals, candidates, matches,
                                       Eigen::VectorXd::Ones (static_cast<Eigen::Index> (matches.size ())), T_static,
                                       guess, fit);
  result.T_source_target = T_static.inverse ();
}

/** The points with a match and a real cluster (not the outlier one). */
std::vector<int>
matchedClusteredPoints (const std::vector<int>& source_match, const std::vector<int>& source_cluster)
{
  std::vector<int> points;
  for (int i = 0; i < static_cast<int> (source_match.size ()); ++i)
    if (source_match[i] != kNoMatch && source_cluster[i] != kOutlierCluster)
      points.push_back (i);
  return points;
}

/** CRF-Clustering (the model's clustering weights) of the final associations: the
 *  clusters and motions of \a result given its associations, which stand. Its
 *  sum-product marginals and N_eff merging keep apart clusters whose motions differ by
 *  little, which the ladder's hard refits let collapse into one; each cluster is
 *  refitted as JointParameters::final_motion_fit says. Without any
 *  association the ladder's clusters stand. */
void
clusterFinalAssociations (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Odometry& odometry,
                          const JointModel& model, const JointParameters& parameters, JointResult& result)
{
  clustering::CrfClusteringParameters settings = parameters.initial_clustering;
  settings.features = model.initial_clustering.features;
  settings.motion_fit = parameters.final_motion_fit;
  if (parameters.bound_weighted_neighbours_by_missing_returns)
    settings.features.weighted_neighbour_max_gap = model.matcher.parameters.candidates.segments.max_missing_returns;
  const clustering::ScanClustering scan =
      clustering::clusterScan (source, target, result.source_match, model.initial_clustering.weights, settings,
                               &odometry, clustering::UnpairedLabelling::Outlier);
  if (scan.motions.empty ())
    return;
  result.cluster_motions = scan.motions;
  result.source_cluster = scan.source_cluster;
  result.static_cluster = scan.static_cluster;
  numberLargestFirst (result);
  result.T_source_target =
      result.static_cluster >= 0 ? result.cluster_motions[result.static_cluster].inverse () : odometry.T_source_target;
}

/** The joint model at the resolution of the scans it is given: the ladder's result
 *  (its clusters and motions, under which the associations were taken) and the
 *  final result (the same associations, the final clusters and motions). */
struct ScanResolutionEstimate
{
  JointResult ladder;
  JointResult result;
};

ScanResolutionEstimate
estimateAtScanResolution (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Odometry& odometry,
                          const JointModel& model, const JointParameters& parameters)
{
  const matching::PreparedTarget prepared = matching::prepareTarget (target, model.matcher.parameters.candidates);
  const matching::MotionGuess guess = matching::MotionGuess::fromOdometry (odometry);
  AssociationStage stage = firstAssociationPass (source, prepared, guess, model.matcher);
  LadderStart start = initialClusters (source, target, stage, model, parameters.initial_clustering, odometry);
  if (parameters.add_segment_motion_hypotheses)
    addSegmentMotionHypotheses (source, prepared.index.points, stage.T_first,
                                matching::limitToInterval (model.matcher.parameters, guess.interval).candidates.segments,
                                start);
  jointPass (stage, prepared, guess, model.matcher, start);
  const crf::ChainPotentials chain = associationPotentials (stage, prepared, model);
  const LadderGeometry geometry =
      makeLadderGeometry (source, target, stage.pass.candidates, model.initial_clustering.features.min_spacing,
                          model.initial_clustering.features.min_neighbour_distance);
  const int min_points = parameters.min_cluster_points > 0 ? parameters.min_cluster_points : model.min_cluster_points;
  JointResult result;
  result.initial_clusters = static_cast<int> (start.motions.size ());
  LadderResult round;
  for (;;) {
    round = inferLadder (geometry, chain, model.weights, start.motions, start.association, start.cluster,
                         parameters.inference);
    ++result.rounds;
    result.iterations += round.iterations;
    if (result.rounds >= parameters.max_rounds || !pruneClusters (round, parameters, min_points, start))
      break;
  }
  result.converged = round.converged;
  assemble (round, stage.pass.candidates, odometry, result);
  refineStaticMotion (source, prepared, stage.pass.candidates, guess, model.matcher.parameters.fit, result);
  associateUnderClusterMotions (source, prepared.index.points,
                                matchedClusteredPoints (result.source_match, result.source_cluster),
                                result.source_cluster, result.cluster_motions, result.source_match);
  ScanResolutionEstimate estimate{result, std::move (result)};  // braced: the copy is made first
  clusterFinalAssociations (source, target, odometry, model, parameters, estimate.result);
  refineStaticMotion (source, prepared, stage.pass.candidates, guess, model.matcher.parameters.fit, estimate.result);
  return estimate;
}

/** The ladder's associations on the thinned scans lifted to the full ones: every
 *  point takes its anchor's cluster and matched-or-outlier decision, and the matched
 *  points of real clusters their target point under their cluster's motion (as at
 *  scan resolution). */
std::vector<int>
liftedMatches (const JointResult& ladder, const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
               const matching::ThinnedPair& thinned)
{
  const std::vector<int> cluster = matching::liftLabels (thinned.anchors, ladder.source_cluster);
  const std::vector<int> matched =
      matchedClusteredPoints (matching::liftLabels (thinned.anchors, ladder.source_match), cluster);
  std::vector<int> matches (cluster.size (), kNoMatch);
  KnnIndex target_points;
  target_points.build (target);
  associateUnderClusterMotions (source, target_points, matched, cluster, ladder.cluster_motions, matches);
  return matches;
}

}  // namespace

void
detail::numberLargestFirst (JointResult& result)
{
  const int clusters = static_cast<int> (result.cluster_motions.size ());
  const std::vector<int> sizes = clustering::clusterSizes (result.source_cluster, clusters);
  std::vector<int> order (static_cast<std::size_t> (clusters));
  std::iota (order.begin (), order.end (), 0);
  std::stable_sort (order.begin (), order.end (), [&sizes] (int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank (static_cast<std::size_t> (clusters));
  std::vector<Rigid2d> motions;
  result.cluster_sizes.clear ();
  for (int k = 0; k < clusters; ++k) {
    rank[order[k]] = k;
    motions.push_back (result.cluster_motions[order[k]]);
    result.cluster_sizes.push_back (sizes[order[k]]);
  }
  result.cluster_motions = std::move (motions);
  result.outliers.clear ();
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i) {
    int& cluster = result.source_cluster[i];
    if (cluster == kOutlierCluster)
      result.outliers.push_back (static_cast<int> (i));
    else
      cluster = rank[cluster];
  }
  if (result.static_cluster >= 0)
    result.static_cluster = rank[result.static_cluster];
}

void
detail::markMovedAway (const std::vector<int>& points, JointResult& result)
{
  std::vector<int>& moved_away = result.moved_away;
  moved_away.insert (moved_away.end (), points.begin (), points.end ());
  std::sort (moved_away.begin (), moved_away.end ());
  moved_away.erase (std::unique (moved_away.begin (), moved_away.end ()), moved_away.end ());
}

void
detail::checkResultClusters (const char* function, const JointResult& result)
{
  const std::size_t n = result.source_cluster.size ();
  if (result.source_match.size () != n)
    failIn (function, std::to_string (n) + " clusters but " + std::to_string (result.source_match.size ()) +
                          " matches: give one of each per source point");
  const int clusters = static_cast<int> (result.cluster_motions.size ());
  if (result.static_cluster >= clusters)
    failIn (function, "the static cluster " + std::to_string (result.static_cluster) + " is not one of the " +
                          std::to_string (clusters) + " clusters");
  for (std::size_t i = 0; i < n; ++i) {
    const int l = result.source_cluster[i];
    if (l != kOutlierCluster && (l < 0 || l >= clusters))
      failIn (function, "point " + std::to_string (i) + " is in cluster " + std::to_string (l) + " of " +
                            std::to_string (clusters));
  }
}

void
detail::checkResultAgainstSource (const char* function, const Eigen::Matrix2Xd& source, const JointResult& result)
{
  checkResultClusters (function, result);
  if (!source.allFinite ())
    failIn (function, "the source scan holds NaN or infinite points");
  if (static_cast<Eigen::Index> (result.source_cluster.size ()) != source.cols ())
    failIn (function, std::to_string (source.cols ()) + " source points but " +
                          std::to_string (result.source_cluster.size ()) + " clusters: give one per point");
}

void
detail::checkSegmentParameters (const char* function, const matching::SegmentMotionParameters& parameters)
{
  const std::string problem = matching::segmentParametersProblem (parameters);
  if (!problem.empty ())
    failIn (function, "the segment parameters: " + problem);
}

void
detail::checkResultAgainstTarget (const char* function, const Eigen::Matrix2Xd& target, const JointResult& result)
{
  checkResultClusters (function, result);
  if (!target.allFinite ())
    failIn (function, "the target scan holds NaN or infinite points");
  checkMatches (function, target, result);
}

void
detail::checkResultAgainstScans (const char* function, const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                 const JointResult& result)
{
  checkResultAgainstSource (function, source, result);
  checkResultAgainstTarget (function, target, result);
}

void
associateUnderClusterMotions (const Eigen::Matrix2Xd& source, const KnnIndex& target_points,
                              const std::vector<int>& points, const std::vector<int>& cluster,
                              const std::vector<Rigid2d>& motions, std::vector<int>& source_match)
{
  const auto n = static_cast<std::size_t> (source.cols ());
  if (cluster.size () != n || source_match.size () != n)
    throw std::invalid_argument ("[pcl_crf::joint::associateUnderClusterMotions] " + std::to_string (n) +
                                 " source points, " + std::to_string (cluster.size ()) + " clusters and " +
                                 std::to_string (source_match.size ()) + " matches: give one of each per point");
  if (!points.empty () && target_points.size () == 0)
    throw std::invalid_argument ("[pcl_crf::joint::associateUnderClusterMotions] the target has no point");
  Eigen::Matrix2Xd moved (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k) {
    const int i = points[k];
    if (i < 0 || static_cast<std::size_t> (i) >= n || cluster[i] < 0 || cluster[i] >= static_cast<int> (motions.size ()))
      throw std::invalid_argument ("[pcl_crf::joint::associateUnderClusterMotions] point " + std::to_string (i) +
                                   " is not a source point of a cluster with a motion");
    moved.col (k) = motions[cluster[i]] * source.col (i);
  }
  const KnnIndex::Result nearest = target_points.search (moved, 1);  // one batched query
  for (std::size_t k = 0; k < points.size (); ++k)
    source_match[points[k]] = nearest.indices (0, static_cast<Eigen::Index> (k));
}

JointResult
estimateJoint (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Odometry& odometry,
               const JointModel& model, const JointParameters& parameters)
{
  if (!model.isTrained ())
    fail ("the model is not trained (train or load one first)");
  validateParameters (parameters);
  matching::validateParameters (model.matcher.parameters);
  if (source.cols () == 0 || target.cols () == 0)
    fail ("the source and target scans must not be empty");
  for (const std::string& problem : {scanPointsProblem (source, "source"), scanPointsProblem (target, "target")})
    if (!problem.empty ())
      fail (problem);
  const std::string odometry_problem = odometryProblem (odometry);
  if (!odometry_problem.empty ())
    fail (odometry_problem);
  const std::vector<int> source_first = firstOfEqualPoints (source), target_first = firstOfEqualPoints (target);
  if (repeatsAPoint (source_first) || repeatsAPoint (target_first))  // the first copies alone, lifted to the others
    return detail::liftToCopies (estimateJoint (source (Eigen::all, firstCopies (source_first)),
                                                target (Eigen::all, firstCopies (target_first)), odometry, model,
                                                parameters),
                                 source_first, target_first);
  const matching::ThinnedPair thinned =
      matching::thinPair (source, target, model.matcher.parameters.training_beam_spacing);
  JointResult result;
  JointResult ladder;  // the ladder's clusters and motions over every source point
  if (!thinned.isThinned (source, target)) {
    ScanResolutionEstimate full = estimateAtScanResolution (source, target, odometry, model, parameters);
    result = std::move (full.result);
    ladder = std::move (full.ladder);
  } else {
    ScanResolutionEstimate coarse =
        estimateAtScanResolution (thinned.source.points, thinned.target.points, odometry, model, parameters);
    result = std::move (coarse.result);  // the final clusters and motions, lifted below
    result.source_match = liftedMatches (coarse.ladder, source, target, thinned);
    result.source_cluster = matching::liftLabels (thinned.anchors, result.source_cluster);
    numberLargestFirst (result);
    ladder = std::move (coarse.ladder);
    ladder.source_cluster = matching::liftLabels (thinned.anchors, ladder.source_cluster);
    ladder.source_match = result.source_match;
  }
  const matching::SegmentMotionParameters segments =
      matching::limitToInterval (model.matcher.parameters.candidates.segments, odometry.interval);
  const detail::ScanViews views (source, target, segments, parameters.sensor);  // shared by the steps below
  if (parameters.keep_ladder_clusters_the_final_clustering_merges)
    detail::keepLadderClustersTheFinalClusteringMerged (views, ladder, segments.min_segment_points * thinned.source.factor,
                                                        result);
  if (parameters.remove_clusters_the_static_world_explains)
    removeClustersTheStaticWorldExplains (target, segments, result);
  if (parameters.remove_clusters_a_nearer_cluster_explains)
    removeClustersANearerClusterExplains (source, target, segments, result);
  if (parameters.remove_clusters_the_target_sees_through)
    detail::removeClustersTheTargetSeesThrough (views, result);
  if (parameters.remove_clusters_on_the_static_outline)
    detail::removeClustersOnTheStaticOutline (views, result);
  const detail::StaticFitCheck static_fit{parameters.slight_motion, segments.min_segment_points * thinned.source.factor};
  const detail::StaticFitCheck* check =
      parameters.check_free_space_motions_against_the_static_fit ? &static_fit : nullptr;
  if (parameters.separate_objects_in_free_space)
    detail::separateObjectsInFreeSpace (views, result, check);
  // The slid segments' least evidence is counted at the model's resolution: a scan
  // thinned by k above shows k times as many points over the same bearings.
  if (parameters.separate_segments_the_target_sees_through)
    detail::separateSegmentsTheTargetSeesThrough (
        views, parameters.segment_min_points_seen_through * thinned.source.factor, result);
  if (parameters.separate_points_the_target_sees_through)
    detail::separatePointsTheTargetSeesThrough (views, result);
  if (parameters.separate_segments_that_moved_slightly)
    detail::separateSegmentsThatMovedSlightly (views, parameters.slight_motion,
                                               segments.min_segment_points * thinned.source.factor, result);
  if (parameters.merge_adjacent_clusters_that_move_alike)
    detail::mergeAdjacentClustersThatMoveAlike (views, result);
  if (parameters.extend_moving_clusters_over_their_surfaces)
    detail::extendMovingClustersOverTheirSurfaces (views, result);
  if (parameters.separate_distant_parts)
    separateDistantParts (source, parameters.part_gap, result);
  if (parameters.mark_points_that_moved_away)
    detail::markPointsThatMovedAway (views, result);
  return result;
}

}  // namespace joint
}  // namespace pcl_crf
