#pragma once

#include <pcl_crf/core/scan_pair.h>

namespace pcl_crf {

/** \brief How far an estimated rigid motion is from the true one. */
struct MotionError
{
  /** |angle(T_est^-1 * T_true)| [rad], in [0, pi]. */
  double rotation = 0.0;
  /** ||translation(T_est^-1 * T_true)|| [m]. */
  double translation = 0.0;
};

/** \brief Rotation and translation error of \a T_estimated against \a T_true,
 *  both taken from the residual motion T_estimated^-1 * T_true.
 *
 *  \code
 *  const auto e = pcl_crf::computeMotionError (pcl_crf::makeRigid2d (0, 0, 0.08),
 *                                              pcl_crf::makeRigid2d (0, 0, 0.1));
 *  // e.rotation == 0.02, e.translation == 0
 *  \endcode
 */
MotionError
computeMotionError (const Rigid2d& T_estimated, const Rigid2d& T_true);

/** \brief Error of an estimated sensor motion T_source_target. The truth is the
 *  inverse of the static-world object's T_target_source.
 *  \return NaN errors when the pair has no static-world object.
 */
MotionError
computeEgoMotionError (const ScanPair& truth, const Rigid2d& T_source_target);

}  // namespace pcl_crf
