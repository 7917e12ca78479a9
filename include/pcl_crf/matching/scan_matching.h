#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/core/scan_thinning.h>
#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/pass_geometry.h>
#include <pcl_crf/matching/robust_rigid_fit.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief What CRF-Matching finds for one scan pair (frames as in ScanPair).
 *
 *  \code
 *  const pcl_crf::matching::MatchResult r = pcl_crf::matching::matchScans (source, target, guess, model);
 *  if (r.matches[i] != pcl_crf::kNoMatch)
 *    const double p = r.map_probability (i);   // its marginal probability
 *  \endcode
 */
struct MatchResult
{
  /** per source point: the index of its target point (MAP association), or kNoMatch. */
  std::vector<int> matches;
  /** per source point: the candidates that were its states (the last pass's). */
  Candidates candidates;
  /** per source point: the marginal p(y_i = s) over its states, the candidates
   *  in Candidates order then the outlier state (last entry). */
  std::vector<Eigen::VectorXd> marginals;
  /** per source point: the marginal of its MAP state (of the outlier state for an outlier). */
  Eigen::VectorXd map_probability;
  /** the estimated static-world motion: p_target = T_target_source * p_source. */
  Rigid2d T_target_source = Rigid2d::Identity ();
  /** source points with a match. */
  int inlier_count = 0;
  /** passes run. */
  int passes = 0;
};

/** \brief The outcome of one association pass (what the learner needs too). */
struct PassResult
{
  PassGeometry geometry;
  BoostedScores scores;
  crf::MapResult map;
  crf::MarginalResult marginals;
  /** target index per source point from the MAP labelling, or kNoMatch. */
  std::vector<int> matches;
  /** the motion re-estimated from the MAP pairs weighted by their marginals. */
  Rigid2d T_estimate = Rigid2d::Identity ();
};

/** \brief One pass: candidates under \a T_current, boosted features, Viterbi and
 *  forward–backward on the chain, then the robust motion estimate from the MAP
 *  inlier pairs, each weighted by its marginal inlier probability 1 − p(y_i = outlier).
 *  \param[in] earlier the previous pass's shape neighbours (same source and target), or
 *             nullptr; only saves searching (preparePass)
 */
PassResult
runPass (const ScanShape& source, const PreparedTarget& target, const MotionGuess& guess, const Rigid2d& T_current,
         const StageModel& stage, const MatchingParameters& parameters, const ShapeNeighbours* earlier = nullptr);

/** \brief CRF-Matching of a source scan against a prepared target scan, both at
 *  the resolution they come in (no thinning, and every point a state or a node even
 *  when it repeats another: see the MatchingTarget overload).
 *
 *  Runs model.parameters.passes passes (stage k of the model in pass k, the last
 *  stage again when the model has fewer): pass 1 from the guess, pass 2 from
 *  pass 1's estimate.
 *  \param[in] source source points in beam order [m, source frame]
 *  \param[in] target the target scan (prepareTarget)
 *  \param[in] guess initial guess of T_target_source and its information
 *             (MotionGuess::fromOdometry; zero information: no prior)
 *  \param[in] model a trained model
 *  \throws std::invalid_argument for an untrained model or non-finite points.
 *
 *  \code
 *  const auto model = pcl_crf::matching::loadModel ("data/models/crf-matching.model");
 *  const pcl_crf::matching::MatchResult r = pcl_crf::matching::matchScans (
 *      pair.source, pair.target, pcl_crf::matching::MotionGuess::fromOdometry (pair.odometry), model);
 *  \endcode
 */
MatchResult
matchScans (const Eigen::Matrix2Xd& source, const PreparedTarget& target, const MotionGuess& guess,
            const CrfMatchingModel& model);

/** \brief A target scan prepared for CRF-Matching at the resolution of the model:
 *  the first copy of every point (firstOfEqualPoints: a point repeated exactly is no
 *  return of its own), thinned to MatchingParameters::training_beam_spacing when it is
 *  about twice as fine or finer (thinToSpacing), then prepareTarget of the points kept. */
struct MatchingTarget
{
  /** the full target scan [m]. */
  Eigen::Matrix2Xd points;
  /** per full target point: the first point with its coordinates (firstOfEqualPoints). */
  std::vector<int> first_copy;
  /** the points the model sees: thinned.kept indexes the full scan (first copies only). */
  ThinnedScan thinned;
  /** prepareTarget of thinned.points. */
  PreparedTarget prepared;
};

/** \brief prepareTarget at the resolution of the model. \throws std::invalid_argument for non-finite points. */
MatchingTarget
prepareMatchingTarget (const Eigen::Matrix2Xd& target, const MatchingParameters& parameters);

/** \brief CRF-Matching at the resolution the model was trained at: when either scan
 *  is about twice as fine as MatchingParameters::training_beam_spacing or finer, both
 *  are thinned to it, matched, and the associations lifted back to every point
 *  (liftMatches, under the estimated motion). A point's candidates and marginals are
 *  then those of the kept point that stands for it (thinnedAnchors), each kept target
 *  point's index in the full scan, its MAP one replaced by the lifted match.
 *
 *  Points repeated exactly (firstOfEqualPoints; a converter's placeholder for beams
 *  without a return, say) are matched once: the chain holds the first copy of every
 *  source point, and a later copy takes its result; the states are first copies of
 *  target points, and a match is always a target point's first copy.
 */
MatchResult
matchScans (const Eigen::Matrix2Xd& source, const MatchingTarget& target, const MotionGuess& guess,
            const CrfMatchingModel& model);

/** \brief Same, preparing the target scan first (prepareMatchingTarget). */
MatchResult
matchScans (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const MotionGuess& guess,
            const CrfMatchingModel& model);

}  // namespace matching
}  // namespace pcl_crf
