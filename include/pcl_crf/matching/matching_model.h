#pragma once

#include <pcl_crf/crf/adaboost_stumps.h>
#include <pcl_crf/matching/candidates.h>

#include <Eigen/Core>

#include <iosfwd>
#include <string>
#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief The error a pair contributes to the motion fit. */
enum class FitMetric
{
  PointToPoint,  ///< ||T s − t||² (closed form without a prior)
  PointToLine    ///< (n_tᵀ (T s − t))², n_t the target scan's normal at t (Censi's PL-ICP metric)
};

/** \brief Robust estimation of the static-world motion from the associated pairs
 *  (iteratively reweighted least squares with a Geman–McClure kernel whose scale
 *  shrinks geometrically from \c initial_scale to \c final_scale).
 */
struct RobustFitParameters
{
  /** IRLS iterations (≥ 1); default 8. */
  int iterations = 8;
  /** residual scale of the first iteration, about the odometry error at the
   *  scan's ranges [m]; default 1.0. */
  double initial_scale = 1.0;
  /** residual scale of the last iteration, about the sensor and sampling noise [m];
   *  default 0.1. */
  double final_scale = 0.1;
  /** re-choose every inlier's target point among its candidates as the nearest
   *  under the current iterate (ICP-style) instead of keeping the MAP pair; default
   *  false (with the point-to-line metric the MAP pairs do as well or better: on the
   *  default test split 0.813 against 0.798 association accuracy). */
  bool reassociate = false;
  /** the pair error; default PointToLine (walls then slide freely, so the few
   *  corners fix the motion instead of the sampling of the walls). */
  FitMetric metric = FitMetric::PointToLine;
};

/** \brief Every setting of CRF-Matching: stored in the model file, so a model
 *  always runs with the settings it was trained with (the runtime ones may be
 *  changed afterwards, e.g. through pcl_crf::CRFMatcher's setters).
 *
 *  \code
 *  pcl_crf::matching::MatchingParameters parameters;
 *  parameters.candidates.guess_neighbours = 6;   // more candidates for a poor odometry
 *  parameters.passes = 1;                        // half the time, lower accuracy
 *  const auto model = pcl_crf::matching::trainCrfMatching (pairs, parameters);
 *  \endcode
 */
struct MatchingParameters
{
  /** candidate target points per source point. */
  CandidateParameters candidates;
  /** AdaBoost rounds (decision stumps) of each classifier (≥ 1); default 50. */
  int boosting_rounds = 50;
  /** σ of the Gaussian prior on the CRF weights in pseudo-likelihood learning (> 0); default 10. */
  double prior_sigma = 10.0;
  /** scale of the geometric residuals of the pairwise features: a residual d enters as
   *  the Geman–McClure term d² / (d² + scale²) [m]; default 0.05. */
  double residual_scale = 0.05;
  /** association passes (1 or 2): pass 2 recomputes the candidates and the registered
   *  translation under the motion estimated by pass 1; default 2. */
  int passes = 2;
  /** estimation of the rigid motion after each pass. */
  RobustFitParameters fit;
  /** angle between the beams of the scans the model was trained on [rad]: set by
   *  trainCrfMatching (the median medianBeamSpacing of its scans). Scans about twice
   *  as fine or finer are matched thinned to it (thinToSpacing), their associations lifted
   *  back to every point (liftMatches), since the shape features and the learned
   *  weights are those of that resolution; 0: never thin (models written before
   *  this field). */
  double training_beam_spacing = 0.0;
};

/** \brief Learned parameters of one association pass: the two boosted
 *  classifiers whose margins are the CRF's local features, and the CRF weights.
 */
struct StageModel
{
  /** scores a (source point, candidate) pair: match (+) vs non-match (−). */
  crf::AdaBoostStumps data_boosting;
  /** scores a source point: outlier (+) vs matched (−). */
  crf::AdaBoostStumps outlier_boosting;
  /** CRF weights [w_u (kUnaryFeatureCount); w_p (kPairwiseFeatureCount)]. */
  Eigen::VectorXd crf_weights;
};

/** \brief A trained CRF-Matching model: one StageModel per pass plus the
 *  parameters it was trained with.
 *
 *  \code
 *  pcl_crf::matching::CrfMatchingModel model = pcl_crf::matching::loadModel ("data/models/crf-matching.model");
 *  pcl_crf::matching::saveModel (model, "/tmp/copy.model");
 *  \endcode
 */
struct CrfMatchingModel
{
  MatchingParameters parameters;
  std::vector<StageModel> stages;

  /** \brief true when every stage is trained (boosters trained, weights sized). */
  bool
  isTrained () const;
};

/** \brief \throws std::invalid_argument naming the first parameter out of range. */
void
validateParameters (const MatchingParameters& parameters);

/** \brief \a parameters for a pair \a interval seconds apart: the segment hypotheses
 *  reach no farther than an object at SegmentMotionParameters::max_speed travels
 *  (limitToInterval of candidates.segments; unchanged when the interval is 0, unknown). */
MatchingParameters
limitToInterval (MatchingParameters parameters, double interval);

/** \brief Version of the model file format written by writeModel. */
constexpr int kModelFileVersion = 1;

/** \brief Writes the model as versioned, human-readable text (exact round trip). */
void
writeModel (const CrfMatchingModel& model, std::ostream& os);

/** \brief Reads a model written by writeModel, checking the version and every field.
 *  \param[in] is the text
 *  \param[in] name what the text is called in error messages (the file name)
 *  \throws std::runtime_error "<name>: line <n>: <problem>".
 */
CrfMatchingModel
readModel (std::istream& is, const std::string& name = "model");

/** \brief writeModel into a file. \throws std::runtime_error when it cannot be written. */
void
saveModel (const CrfMatchingModel& model, const std::string& path);

/** \brief readModel from a file. \throws std::runtime_error naming the file, line and problem. */
CrfMatchingModel
loadModel (const std::string& path);

}  // namespace matching
}  // namespace pcl_crf
