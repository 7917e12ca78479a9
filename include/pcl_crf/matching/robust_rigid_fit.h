#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/candidates.h>
#include <pcl_crf/matching/matching_model.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief The initial guess of the static-world motion and how much to trust it.
 *
 *  \c information is the inverse covariance of (x [m], y [m], θ [rad]) of
 *  T_target_source; the zero matrix (the default) means "no prior": the guess
 *  then only seeds the candidates and the iterations.
 *
 *  \code
 *  const pcl_crf::matching::MotionGuess guess = pcl_crf::matching::MotionGuess::fromOdometry (pair.odometry);
 *  pcl_crf::matching::MotionGuess no_prior;
 *  no_prior.T_target_source = guess.T_target_source;
 *  \endcode
 */
struct MotionGuess
{
  Rigid2d T_target_source = Rigid2d::Identity ();
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero ();
  /** time from the source scan to the target scan [s]; 0 when unknown (Odometry::interval). */
  double interval = 0.0;

  /** \brief The guess an odometry reading gives: T_target_source = T_source_target⁻¹,
   *  its covariance propagated through the inversion (first order). A covariance
   *  that is not positive definite gives no prior. */
  static MotionGuess
  fromOdometry (const Odometry& odometry);
};

/** \brief What makes a motion guess unusable, or an empty string when nothing does: a
 *  NaN or infinite motion, a motion whose linear part is not a rotation, an information
 *  matrix with a NaN or infinite entry, or an interval that is negative or not finite. */
std::string
motionGuessProblem (const MotionGuess& guess);

/** \brief The static-world motion from associated pairs, robust to the pairs of
 *  moving objects.
 *
 *  Iteratively reweighted least squares (the joint paper's eq. 6) from \a T_start
 *  over the source points the association keeps (map_matches[i] ≠ kNoMatch):
 *  iteration k gives point i the weight p_i / (1 + r_i² / c_k²)² (the Geman–McClure
 *  kernel), r_i = ||T s_i − t|| under the previous iterate, with the scale c_k
 *  shrinking geometrically from RobustFitParameters::initial_scale to final_scale
 *  (graduated non-convexity, as in Zhou, Park & Koltun's Fast Global Registration). The
 *  target point t is map_matches[i], or, with RobustFitParameters::reassociate,
 *  the candidate of i nearest to T s_i (ICP-style re-association within the
 *  candidates, which removes the pull of the guess that chose the MAP pairs).
 *  With FitMetric::PointToLine a pair's error is its distance to the target
 *  scan's line at t (target_normals), minimised by Gauss–Newton.
 *  Without a prior each iteration is the closed-form weighted fit
 *  (RigidFitAccumulator); with one (MotionGuess::information ≠ 0) it minimises
 *  Σ w_i r_i² / c_k² + (ξ − ξ_guess)ᵀ Λ (ξ − ξ_guess) by Gauss–Newton, so that
 *  a majority of moving points (a car driving alongside) cannot drag the estimate
 *  far from what the odometry allows.
 *
 *  \param[in] source source points [m, source frame]
 *  \param[in] target target points [m, target frame]
 *  \param[in] target_normals unit normal of the target scan at every target point
 *             (zero where undefined: that pair uses the point-to-point error);
 *             may be empty for FitMetric::PointToPoint
 *  \param[in] candidates the candidate target points of every source point
 *  \param[in] map_matches target index of every source point, or kNoMatch (skipped)
 *  \param[in] confidence p_i ≥ 0 of every source point (its inlier probability)
 *  \param[in] T_start the first iterate T_target_source
 *  \param[in] guess the prior (its information may be zero)
 *  \param[in] parameters iterations and scales
 *  \return the estimated T_target_source; the last iterate when too few distinct
 *  source points are matched to fix a motion
 *
 *  \code
 *  const pcl_crf::Rigid2d T = pcl_crf::matching::robustRigidFit (
 *      source, target, normals, candidates, matches, p, guess.T_target_source, guess, {});
 *  \endcode
 */
Rigid2d
robustRigidFit (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Eigen::Matrix2Xd& target_normals,
                const Candidates& candidates, const std::vector<int>& map_matches, const Eigen::VectorXd& confidence,
                const Rigid2d& T_start, const MotionGuess& guess, const RobustFitParameters& parameters);

}  // namespace matching
}  // namespace pcl_crf
