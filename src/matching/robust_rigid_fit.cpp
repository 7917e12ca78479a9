#include <pcl_crf/matching/robust_rigid_fit.h>
#include <pcl_crf/core/rigid_fit.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** Gauss–Newton steps per IRLS iteration. */
constexpr int kGaussNewtonSteps = 3;
/** Relative Levenberg damping that keeps an unconstrained direction (a corridor
 *  without a prior) where it is instead of failing. */
constexpr double kDamping = 1e-9;

/** c_k = c_0 (c_end / c_0)^(k / (K − 1)): geometric from the initial to the final scale. */
double
iterationScale (const RobustFitParameters& parameters, int k)
{
  if (parameters.iterations <= 1)
    return parameters.final_scale;
  const double fraction = static_cast<double> (k) / (parameters.iterations - 1);
  return parameters.initial_scale * std::pow (parameters.final_scale / parameters.initial_scale, fraction);
}

double
wrapAngle (double a)
{
  return std::atan2 (std::sin (a), std::cos (a));
}

/** One IRLS iteration's weighted pairs. */
struct WeightedPairs
{
  const Eigen::Matrix2Xd& source;
  const Eigen::Matrix2Xd& target;
  const Eigen::Matrix2Xd& normals;  // empty: point-to-point
  std::vector<int> matches;
  Eigen::VectorXd weights;
};

/** The pair of every kept source point under T: the MAP match, or the candidate nearest to T s_i. */
void
choosePairs (const Candidates& candidates, const std::vector<int>& map_matches, const Rigid2d& T, bool reassociate,
             WeightedPairs& pairs)
{
  pairs.matches = map_matches;
  if (!reassociate)
    return;
  for (int i = 0; i < candidates.size (); ++i) {
    if (map_matches[i] == kNoMatch)
      continue;
    const Eigen::Vector2d moved = T * pairs.source.col (i);
    double best = (moved - pairs.target.col (map_matches[i])).squaredNorm ();
    for (int c = candidates.offsets[i]; c < candidates.offsets[i + 1]; ++c) {
      const double d = (moved - pairs.target.col (candidates.targets[c])).squaredNorm ();
      if (d < best) {
        best = d;
        pairs.matches[i] = candidates.targets[c];
      }
    }
  }
}

/** Residual of pair i under T: along the target normal when there is one, else the 2D offset. */
bool
hasNormal (const WeightedPairs& pairs, int j)
{
  return pairs.normals.cols () > j && pairs.normals.col (j).squaredNorm () > 0.5;
}

/** Geman–McClure IRLS weights p_i / (1 + r_i² / c²)² under T (0 for unmatched points). */
void
gemanMcClureWeights (const Eigen::VectorXd& confidence, const Rigid2d& T, double scale, WeightedPairs& pairs)
{
  const double inverse_squared_scale = 1.0 / (scale * scale);
  pairs.weights.setZero (pairs.source.cols ());
  for (Eigen::Index i = 0; i < pairs.source.cols (); ++i) {
    const int j = pairs.matches[i];
    if (j == kNoMatch || !(confidence (i) > 0.0))
      continue;
    const Eigen::Vector2d r = T * pairs.source.col (i) - pairs.target.col (j);
    const double squared = hasNormal (pairs, j) ? std::pow (pairs.normals.col (j).dot (r), 2) : r.squaredNorm ();
    const double denominator = 1.0 + squared * inverse_squared_scale;
    pairs.weights (i) = confidence (i) / (denominator * denominator);
  }
}

/** argmin Σ w_i e_i(T)² / c² + (ξ − ξ_g)ᵀ Λ (ξ − ξ_g) by Gauss–Newton from T, e_i the
 *  point-to-line (or point-to-point) error. */
Rigid2d
gaussNewtonFit (const WeightedPairs& pairs, double scale, const MotionGuess& guess, Rigid2d T)
{
  const Eigen::Vector3d xi_guess = toXYTheta (guess.T_target_source);
  const double inverse_squared_scale = 1.0 / (scale * scale);
  for (int step = 0; step < kGaussNewtonSteps; ++step) {
    Eigen::Vector3d xi = toXYTheta (T);
    Eigen::Vector3d delta_prior = xi - xi_guess;
    delta_prior (2) = wrapAngle (delta_prior (2));
    Eigen::Matrix3d H = guess.information;
    Eigen::Vector3d g = guess.information * delta_prior;
    for (Eigen::Index i = 0; i < pairs.source.cols (); ++i) {
      if (pairs.weights (i) <= 0.0)
        continue;
      const int j = pairs.matches[i];
      const Eigen::Vector2d rotated = T.linear () * pairs.source.col (i);
      const Eigen::Vector2d r = rotated + T.translation () - pairs.target.col (j);
      Eigen::Matrix<double, 2, 3> J;  // ∂r/∂(x, y, θ)
      J << 1.0, 0.0, -rotated.y (), 0.0, 1.0, rotated.x ();
      const double w = pairs.weights (i) * inverse_squared_scale;
      if (hasNormal (pairs, j)) {  // e = nᵀ r
        const Eigen::RowVector3d Jn = pairs.normals.col (j).transpose () * J;
        H.noalias () += w * Jn.transpose () * Jn;
        g.noalias () += w * Jn.transpose () * pairs.normals.col (j).dot (r);
      }
      else {
        H.noalias () += w * J.transpose () * J;
        g.noalias () += w * J.transpose () * r;
      }
    }
    H.diagonal ().array () += kDamping * (H.trace () + 1e-12);
    const Eigen::LDLT<Eigen::Matrix3d> solver (H);
    if (solver.info () != Eigen::Success || !(solver.vectorD ().array () > 0.0).all ())
      return T;
    xi -= solver.solve (g);
    T = makeRigid2d (xi (0), xi (1), xi (2));
  }
  return T;
}

/** The closed-form weighted point-to-point fit (Tipaldi & Ramos eq. 3); T unchanged when ill-posed. */
Rigid2d
closedFormFit (const WeightedPairs& pairs, const Rigid2d& T)
{
  RigidFitAccumulator accumulator;
  for (Eigen::Index i = 0; i < pairs.source.cols (); ++i)
    if (pairs.weights (i) > 0.0)
      accumulator.add (pairs.source.col (i), pairs.target.col (pairs.matches[i]), pairs.weights (i));
  return accumulator.isWellPosed () ? accumulator.solve () : T;
}

/** \throws std::invalid_argument naming robustRigidFit and the problem when the inputs
 *  do not describe one pair per source point of these scans. */
void
checkFitInputs (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Eigen::Matrix2Xd& target_normals,
                const Candidates& candidates, const std::vector<int>& map_matches, const Eigen::VectorXd& confidence,
                const Rigid2d& T_start, bool reassociate)
{
  const auto fail = [] (const std::string& what) {
    throw std::invalid_argument ("[pcl_crf::matching::robustRigidFit] " + what);
  };
  const auto n = static_cast<std::size_t> (source.cols ());
  if (map_matches.size () != n || static_cast<std::size_t> (confidence.size ()) != n)
    fail (std::to_string (n) + " source points, " + std::to_string (map_matches.size ()) + " matches and " +
          std::to_string (confidence.size ()) + " confidences: give one of each per point");
  if (target_normals.cols () != 0 && target_normals.cols () != target.cols ())
    fail (std::to_string (target_normals.cols ()) + " normals for " + std::to_string (target.cols ()) +
          " target points: give one per point, or none");
  for (std::size_t i = 0; i < n; ++i)
    if (map_matches[i] != kNoMatch && (map_matches[i] < 0 || map_matches[i] >= target.cols ()))
      fail ("point " + std::to_string (i) + " is matched to target point " + std::to_string (map_matches[i]) + " of " +
            std::to_string (target.cols ()));
  if (!T_start.matrix ().allFinite ())
    fail ("the starting motion has a NaN or infinite value");
  if (!reassociate)
    return;
  if (candidates.size () != static_cast<int> (n))
    fail (std::to_string (candidates.size ()) + " candidate lists for " + std::to_string (n) + " source points");
  for (const int j : candidates.targets)
    if (j < 0 || j >= target.cols ())
      fail ("a candidate is target point " + std::to_string (j) + " of " + std::to_string (target.cols ()));
}

}  // namespace

MotionGuess
MotionGuess::fromOdometry (const Odometry& odometry)
{
  const std::string problem = odometryProblem (odometry);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::matching::MotionGuess::fromOdometry] " + problem);
  MotionGuess guess;
  guess.T_target_source = odometry.T_source_target.inverse ();
  guess.interval = odometry.interval;
  // T_ts = (−R(φ)ᵀ t, −φ) of T_st = (t, φ); J = ∂T_ts / ∂T_st.
  const Eigen::Vector3d xi = toXYTheta (odometry.T_source_target);
  const double c = std::cos (xi (2)), s = std::sin (xi (2));
  Eigen::Matrix3d J;
  J << -c, -s, s * xi (0) - c * xi (1),  //
      s, -c, c * xi (0) + s * xi (1),    //
      0.0, 0.0, -1.0;
  const Eigen::Matrix3d covariance = J * odometry.covariance * J.transpose ();
  const Eigen::LDLT<Eigen::Matrix3d> solver (covariance);
  if (covariance.allFinite () && solver.info () == Eigen::Success && (solver.vectorD ().array () > 0.0).all ())
    guess.information = solver.solve (Eigen::Matrix3d::Identity ());
  return guess;
}

std::string
motionGuessProblem (const MotionGuess& guess)
{
  if (!guess.T_target_source.matrix ().allFinite ())
    return "the motion guess has a NaN or infinite value";
  if (!isRotation (guess.T_target_source))
    return "the motion guess's linear part is not a rotation";
  if (!guess.information.allFinite ())
    return "the motion guess's information matrix has a NaN or infinite value";
  if (!guess.information.isApprox (guess.information.transpose (), 1e-9))
    return "the motion guess's information matrix is not symmetric";
  if (!std::isfinite (guess.interval) || guess.interval < 0.0)
    return "the interval between the scans must be a time >= 0 s (0: unknown), not " + std::to_string (guess.interval);
  return {};
}

Rigid2d
robustRigidFit (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Eigen::Matrix2Xd& target_normals,
                const Candidates& candidates, const std::vector<int>& map_matches, const Eigen::VectorXd& confidence,
                const Rigid2d& T_start, const MotionGuess& guess, const RobustFitParameters& parameters)
{
  checkFitInputs (source, target, target_normals, candidates, map_matches, confidence, T_start, parameters.reassociate);
  const bool has_prior = !guess.information.isZero (0.0);
  const bool point_to_line = parameters.metric == FitMetric::PointToLine;
  static const Eigen::Matrix2Xd no_normals;
  WeightedPairs pairs{source, target, point_to_line ? target_normals : no_normals, {}, {}};
  Rigid2d T = T_start;
  for (int k = 0; k < parameters.iterations; ++k) {
    const double scale = iterationScale (parameters, k);
    choosePairs (candidates, map_matches, T, parameters.reassociate, pairs);
    gemanMcClureWeights (confidence, T, scale, pairs);
    T = has_prior || point_to_line ? gaussNewtonFit (pairs, scale, guess, T) : closedFormFit (pairs, T);
  }
  return T;
}

}  // namespace matching
}  // namespace pcl_crf
