#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/matching/scan_matching.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace pcl_crf {
namespace joint {

namespace {

/** Gives every point of a cluster that moves relative to the pass's motion (by more
 *  than the overlap radius at that point, matching::overlapRadius ()) its cluster's
 *  motion as hypothesis. */
void
clusterHypotheses (const LadderStart& start, const matching::SegmentMotionParameters& parameters,
                   const matching::ScanShape& source, matching::PassGeometry& pass)
{
  const int clusters = static_cast<int> (start.motions.size ());
  const Eigen::Index n = source.points.cols ();
  for (int i = 0; i < static_cast<int> (start.cluster.size ()); ++i) {
    const int l = start.cluster[i];
    if (l >= clusters)
      continue;
    const Eigen::Vector2d h = start.motions[l] * source.points.col (i) - pass.source_current.col (i);
    if (h.norm () <= matching::overlapRadius (parameters, matching::pointSpacing (source.points, i, 0, n)))
      continue;
    pass.segment_motions.translation.col (i) = h;
    pass.segment_motions.has_hypothesis[i] = true;
  }
}

}  // namespace

AssociationStage
firstAssociationPass (const Eigen::Matrix2Xd& source, const matching::PreparedTarget& target,
                      const matching::MotionGuess& guess, const matching::CrfMatchingModel& matcher)
{
  const std::string problem = matching::motionGuessProblem (guess);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::joint::firstAssociationPass] " + problem);
  AssociationStage stage;
  stage.source = matching::describeScan (source);
  matching::PassResult first = matching::runPass (stage.source, target, guess, guess.T_target_source,
                                                  matcher.stages.front (), matcher.parameters);
  stage.first_matches = std::move (first.matches);
  stage.T_first = first.T_estimate;
  stage.first_shape_neighbours = std::move (first.geometry.shape_neighbours);
  return stage;
}

LadderStart
initialClusters (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const AssociationStage& stage,
                 const JointModel& model, const clustering::CrfClusteringParameters& parameters,
                 const Odometry& odometry)
{
  LadderStart start;
  clustering::CrfClusteringParameters settings = parameters;
  settings.features = model.initial_clustering.features;
  const clustering::ScanClustering scan =
      clustering::clusterScan (source, target, stage.first_matches, model.initial_clustering.weights, settings,
                               &odometry, clustering::UnpairedLabelling::Outlier);
  start.motions = scan.motions;
  if (start.motions.empty ())  // nothing associated: one cluster with pass 1's motion
    start.motions.push_back (stage.T_first);
  // The static world starts from pass 1's motion, CRF-Matching's robust point-to-line
  // fit with the odometry prior, rather than from CRF-Clustering's point-to-point fit
  // of the same matches, which slides along walls when the scans are far apart (and
  // the ladder's refits would follow it).
  if (scan.static_cluster >= 0)
    start.motions[scan.static_cluster] = stage.T_first;
  const int outlier = static_cast<int> (start.motions.size ());
  start.cluster.resize (scan.source_cluster.size ());
  for (std::size_t i = 0; i < scan.source_cluster.size (); ++i)
    start.cluster[i] = scan.source_cluster[i] == kOutlierCluster || scan.motions.empty () ? outlier
                                                                                          : scan.source_cluster[i];
  return start;
}

void
jointPass (AssociationStage& stage, const matching::PreparedTarget& target, const matching::MotionGuess& guess,
           const matching::CrfMatchingModel& matcher, LadderStart& start)
{
  const matching::CandidateParameters parameters =
      matching::limitToInterval (matcher.parameters, guess.interval).candidates;
  stage.pass = matching::preparePassMotions (stage.source, target, guess.T_target_source, stage.T_first, parameters,
                                             &stage.first_shape_neighbours);
  clusterHypotheses (start, parameters.segments, stage.source, stage.pass);
  stage.pass.candidates = matching::passCandidates (target, stage.pass, parameters);
  const std::size_t last = std::min<std::size_t> (1, matcher.stages.size () - 1);
  stage.scores = matching::scorePass (matcher.stages[last], stage.source, target.scan, stage.pass);
  start.association = matching::matchStates (stage.pass.candidates, stage.first_matches);  // pass 1's, as states
}

crf::ChainPotentials
associationPotentials (const AssociationStage& stage, const matching::PreparedTarget& target, const JointModel& model)
{
  return matching::matchingChainPotentials (stage.source, target.scan, stage.pass, stage.scores,
                                            model.weights.head (matching::kCrfWeightCount),
                                            model.matcher.parameters.residual_scale);
}

}  // namespace joint
}  // namespace pcl_crf
