#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

#include <limits>

namespace pcl_crf {

/** \brief Settings of scorePair. */
struct ScoreOptions
{
  /** a predicted match within this distance of the true target point also
   *  counts as correct in association_accuracy_tolerance [m] (default 0.1). */
  double match_tolerance = 0.1;
  /** beta of the V-measure, weight of completeness against homogeneity (default 1). */
  double v_beta = 1.0;
};

/** \brief Every score of one method on one scan pair.
 *
 *  A field is NaN when it does not apply: association fields when the method
 *  gives no source_match, clustering fields when it gives no source_cluster.
 *  true_outlier_pct and objects_true describe the truth alone and are filled
 *  whenever the truth carries the labels they need.
 */
struct PairScores
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

  // ---- data association (needs source_match)
  /** fraction of source points with the true match (kNoMatch == kNoMatch is correct). */
  double association_accuracy = kNaN;
  /** same, a match within ScoreOptions::match_tolerance of the true target
   *  point also correct. */
  double association_accuracy_tolerance = kNaN;
  /** edit distance between the predicted and the true match sequences, read in the
   *  source scan's beam order (beamOrder ()) [edits]. */
  double association_sed = kNaN;
  /** source points predicted as kNoMatch [%]. */
  double predicted_outlier_pct = kNaN;
  /** source points truly kNoMatch [%] (truth only). */
  double true_outlier_pct = kNaN;
  /** true outliers predicted as kNoMatch, over the true outliers [%]; NaN
   *  without true outliers. */
  double found_outlier_pct = kNaN;

  // ---- motion clustering (needs source_cluster)
  /** homogeneity of the raw cluster labels (kOutlierCluster a label of its own)
   *  against the object ids. */
  double homogeneity = kNaN;
  /** completeness, same labels. */
  double completeness = kNaN;
  /** V-measure with ScoreOptions::v_beta, same labels. */
  double v_measure = kNaN;
  /** fraction of source points whose cluster is paired with their object
   *  ("motion detection accuracy"). */
  double cluster_accuracy = kNaN;
  /** edit distance between the mapped object sequence and the true object sequence, in
   *  the source scan's beam order (beamOrder ()) [edits]. */
  double cluster_sed = kNaN;
  /** distinct cluster labels used, outliers excluded [count]. */
  double clusters_found = kNaN;
  /** distinct object ids among the source points [count] (truth only). */
  double objects_true = kNaN;

  // ---- motion estimation of correctly clustered objects (needs source_cluster)
  /** static world rotation error [rad]. */
  double static_rotation_error = kNaN;
  /** static world translation error [m]. */
  double static_translation_error = kNaN;
  /** mean rotation error of the correctly clustered moving objects [rad]. */
  double moving_rotation_error = kNaN;
  /** mean translation error of the correctly clustered moving objects [m]. */
  double moving_translation_error = kNaN;

  // ---- ego motion (every method)
  /** rotation error of T_source_target [rad]. */
  double ego_rotation_error = kNaN;
  /** translation error of T_source_target [m]. */
  double ego_translation_error = kNaN;

  /** wall-clock time of the method on this pair [s]. */
  double seconds = kNaN;
};

/** \brief Scores a method's prediction on one scan pair against its truth.
 *
 *  Association: accuracy, accuracy within tolerance, edit distance and outlier
 *  percentages (association_metrics.h). Clustering: clusters are paired with
 *  objects greedily (cluster_matching.h), giving the cluster accuracy, the
 *  clustering edit distance and, for every correctly clustered object, its
 *  motion error; V-measure on the raw labels (v_measure.h). Ego motion: the
 *  prediction's T_source_target against the inverse of the static world's
 *  T_target_source (motion_error.h).
 *
 *  \param[in] truth the scan pair with its ground truth
 *  \param[in] prediction the method's output for that pair
 *  \param[in] options tolerance and V-measure beta
 *  \throws std::invalid_argument when the prediction does not fit the truth
 *          (see validatePrediction).
 *
 *  \code
 *  const pcl_crf::PairScores scores = pcl_crf::scorePair (pair, prediction);
 *  if (!std::isnan (scores.v_measure))
 *    std::cout << "V = " << scores.v_measure << '\n';
 *  \endcode
 */
PairScores
scorePair (const ScanPair& truth, const Prediction& prediction, const ScoreOptions& options = {});

}  // namespace pcl_crf
