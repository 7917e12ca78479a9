#include <pcl_crf/core/beam_order.h>
#include <pcl_crf/metrics/association_metrics.h>
#include <pcl_crf/metrics/cluster_matching.h>
#include <pcl_crf/metrics/clustering_metrics.h>
#include <pcl_crf/metrics/edit_distance.h>
#include <pcl_crf/metrics/motion_error.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/metrics/v_measure.h>
#include <pcl_crf/metrics/validate_prediction.h>

namespace pcl_crf {
namespace {

bool
hasOneLabelPerSourcePoint (const ScanPair& truth, const std::vector<int>& labels)
{
  const auto points = static_cast<std::size_t> (truth.source.cols ());
  return points > 0 && labels.size () == points;
}

/** The entries of \a values in \a order. */
std::vector<int>
reordered (const std::vector<int>& values, const std::vector<int>& order)
{
  std::vector<int> out;
  out.reserve (order.size ());
  for (int i : order)
    out.push_back (values[static_cast<std::size_t> (i)]);
  return out;
}

/** The edit distance between two per-source-point sequences read in the source scan's
 *  beam order (beamOrder ()): the chains' order, whatever order the file lists the
 *  points in (a scan in beam order is read as listed; one listed clockwise backwards,
 *  which leaves the distance as it is). */
double
editDistanceInBeamOrder (const std::vector<int>& a, const std::vector<int>& b, const std::vector<int>& order)
{
  return editDistance (reordered (a, order), reordered (b, order));
}

/** Fields that describe the truth alone, whatever the method predicts. */
void
scoreTruth (const ScanPair& truth, PairScores& scores)
{
  if (hasOneLabelPerSourcePoint (truth, truth.source_match))
    scores.true_outlier_pct = outlierPercentage (truth.source_match);
  if (hasOneLabelPerSourcePoint (truth, truth.source_object))
    scores.objects_true = countObjects (truth.source_object);
}

void
scoreAssociation (const ScanPair& truth, const std::vector<int>& predicted, const std::vector<int>& order,
                  const ScoreOptions& options, PairScores& scores)
{
  const std::vector<int>& expected = truth.source_match;
  scores.association_accuracy = associationAccuracy (predicted, expected);
  scores.association_accuracy_tolerance =
      associationAccuracyWithin (predicted, expected, truth.target, options.match_tolerance);
  scores.association_sed = editDistanceInBeamOrder (predicted, expected, order);
  const OutlierStatistics outliers = computeOutlierStatistics (predicted, expected);
  scores.predicted_outlier_pct = outliers.predicted_pct;
  scores.found_outlier_pct = outliers.found_pct;
}

void
scoreClustering (const ScanPair& truth, const Prediction& prediction, const std::vector<int>& order,
                 const ScoreOptions& options, PairScores& scores)
{
  const std::vector<int>& clusters = prediction.source_cluster;
  const std::vector<int>& objects = truth.source_object;

  const VMeasure v = computeVMeasure (objects, clusters, options.v_beta);
  scores.homogeneity = v.homogeneity;
  scores.completeness = v.completeness;
  scores.v_measure = v.v;

  const ClusterObjectMatching matching = matchClustersToObjects (clusters, objects);
  const std::vector<int> mapped = mapClustersToObjects (clusters, matching);
  scores.cluster_accuracy = clusterAccuracy (mapped, objects);
  scores.cluster_sed = editDistanceInBeamOrder (mapped, objects, order);
  scores.clusters_found = countClusters (clusters);

  const ObjectMotionErrors errors = computeObjectMotionErrors (truth, prediction, matching);
  scores.static_rotation_error = errors.static_rotation;
  scores.static_translation_error = errors.static_translation;
  scores.moving_rotation_error = errors.moving_rotation;
  scores.moving_translation_error = errors.moving_translation;
}

}  // namespace

PairScores
scorePair (const ScanPair& truth, const Prediction& prediction, const ScoreOptions& options)
{
  validatePrediction (truth, prediction);
  PairScores scores;
  scoreTruth (truth, scores);
  const std::vector<int> order = beamOrder (truth.source);
  if (!prediction.source_match.empty ())
    scoreAssociation (truth, prediction.source_match, order, options, scores);
  if (!prediction.source_cluster.empty ())
    scoreClustering (truth, prediction, order, options, scores);
  const MotionError ego = computeEgoMotionError (truth, prediction.T_source_target);
  scores.ego_rotation_error = ego.rotation;
  scores.ego_translation_error = ego.translation;
  scores.seconds = prediction.seconds;
  return scores;
}

}  // namespace pcl_crf
