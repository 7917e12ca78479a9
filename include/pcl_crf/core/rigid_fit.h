#pragma once

#include <pcl_crf/core/scan_pair.h>

namespace pcl_crf {

/** \brief Running sums of a weighted 2D point-pair set, from which the
 *  least-squares rigid motion follows in closed form.
 *
 *  The motion minimises Σ_i w_i ||R s_i + T − g_i||² (Tipaldi & Ramos, eq. 3;
 *  the joint paper's eq. 6): with weighted centroids s̄, ḡ and the 2x2
 *  cross-covariance H = Σ w_i (s_i − s̄)(g_i − ḡ)ᵀ, the optimal angle is
 *  atan2(H01 − H10, H00 + H11) and T = ḡ − R s̄. Pairs can be added and removed
 *  in O(1), so a cluster's motion can be refitted incrementally as points move
 *  between clusters.
 */
class RigidFitAccumulator
{
public:
  /** \brief Adds the pair (s → g) with weight w (w ≥ 0; w < 0 removes). */
  void
  add (const Eigen::Vector2d& s, const Eigen::Vector2d& g, double w = 1.0);

  /** \brief Removes a pair added before with the same weight. */
  void
  remove (const Eigen::Vector2d& s, const Eigen::Vector2d& g, double w = 1.0)
  {
    add (s, g, -w);
  }

  /** \brief Total weight added. */
  double
  weight () const
  {
    return w_;
  }

  /** \brief true when the motion is determined: positive weight and a spread of
   *  the source points (at least two distinct points) above \a min_spread [m²]. */
  bool
  isWellPosed (double min_spread = 1e-8) const;

  /** \brief The least-squares motion (identity when the weight is ~0; a pure
   *  translation when the points do not fix a rotation). */
  Rigid2d
  solve () const;

  /** \brief Weighted sum of squared residuals of \a T over the accumulated pairs. */
  double
  residual (const Rigid2d& T) const;

private:
  double w_ = 0.0;
  Eigen::Vector2d sum_s_ = Eigen::Vector2d::Zero ();
  Eigen::Vector2d sum_g_ = Eigen::Vector2d::Zero ();
  Eigen::Matrix2d sum_sg_ = Eigen::Matrix2d::Zero ();  // Σ w s gᵀ
  double sum_ss_ = 0.0;                                // Σ w |s|²
  double sum_gg_ = 0.0;                                // Σ w |g|²
};

/** \brief Weighted least-squares rigid motion mapping source columns onto
 *  target columns (Tipaldi & Ramos, eq. 3). Weights may be empty (all 1).
 *  \throws std::invalid_argument on size mismatch or negative weights.
 */
Rigid2d
fitRigid2d (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
            const Eigen::VectorXd& weights = Eigen::VectorXd ());

}  // namespace pcl_crf
