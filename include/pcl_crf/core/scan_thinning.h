#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {

/** \brief Median angle between the bearings of consecutive points of a scan, seen
 *  from its origin (the sensor) [rad]; 0 with fewer than two points off the origin.
 *
 *  Missing returns only add a few multiples of the step, which the median ignores.
 */
double
medianBeamSpacing (const Eigen::Matrix2Xd& points);

/** \brief By how many beams to thin a scan \a scan_spacing apart for a model trained
 *  at \a model_spacing: the most whose span does not exceed the model's spacing,
 *  ⌊model_spacing / scan_spacing + 0.1⌋ (the 0.1 absorbs the noise of measured
 *  spacings), at least 1; 1 when either spacing is 0 (unknown). Thinning no coarser
 *  than the training scans: on 541-beam scans over 180° (0.33°), thinning by 2 (to
 *  0.67°) associated worse than matching every beam.
 */
int
thinningFactor (double scan_spacing, double model_spacing);

/** \brief A scan thinned to a coarser angular resolution: the points kept, in scan order. */
struct ThinnedScan
{
  /** indices of the kept points in the full scan, increasing. */
  std::vector<int> kept;
  /** the kept points (points.col (k) is the full scan's point kept[k]) [m]. */
  Eigen::Matrix2Xd points;
  /** every factor-th beam was kept (1: every point). */
  int factor = 1;

  /** \brief true when points were dropped. */
  bool
  isThinned (Eigen::Index full_size) const
  {
    return static_cast<Eigen::Index> (kept.size ()) != full_size;
  }
};

/** \brief Thins a scan by \a factor beams: every point's beam is counted from the
 *  first point's along the unwrapped bearings (round(swept angle / \a scan_spacing)),
 *  and the points on every factor-th beam are kept, so that a missing return does not
 *  shift the beams after it. All points are kept when factor ≤ 1.
 *  \param[in] points the scan in beam order, in its sensor frame [m]
 *  \param[in] factor thinningFactor
 *  \param[in] scan_spacing medianBeamSpacing of the scan [rad]
 *  \throws std::invalid_argument when factor > 1 and \a scan_spacing is not an angle > 0,
 *  or \a points hold a NaN or infinite coordinate.
 */
ThinnedScan
thinScan (const Eigen::Matrix2Xd& points, int factor, double scan_spacing);

/** \brief thinScan to the beam spacing a model was trained at (thinningFactor of the
 *  scan's medianBeamSpacing: no thinning unless the scan is about twice as fine or
 *  finer, or when \a model_spacing is 0).
 *
 *  \code
 *  const pcl_crf::ThinnedScan coarse = pcl_crf::thinToSpacing (hokuyo_xy, 0.5 * M_PI / 180);  // 0.25° → 0.5°
 *  \endcode
 */
ThinnedScan
thinToSpacing (const Eigen::Matrix2Xd& points, double model_spacing);

}  // namespace pcl_crf
