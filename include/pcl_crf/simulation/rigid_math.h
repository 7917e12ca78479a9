#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace simulation {

/** \brief Rigid-motion arithmetic with a fixed order of scalar operations.
 *
 *  Eigen picks SIMD code paths (and explicit fused multiply-adds) by the
 *  instruction set a build targets, which changes the last bits of products like
 *  \c A * B. The simulator promises byte-identical output for any build, so the
 *  motions and points it writes go through these plain scalar versions (compiled
 *  without multiply-add contraction).
 *  \code
 *  const pcl_crf::Rigid2d T = pcl_crf::simulation::composeRigid (A, pcl_crf::simulation::invertRigid (B));
 *  const Eigen::Vector2d q = pcl_crf::simulation::transformPoint (T, p);
 *  \endcode
 */

/** \brief A * B. */
Rigid2d
composeRigid (const Rigid2d& A, const Rigid2d& B);

/** \brief The inverse motion (R^T, -R^T t). */
Rigid2d
invertRigid (const Rigid2d& T);

/** \brief T * p. */
Eigen::Vector2d
transformPoint (const Rigid2d& T, const Eigen::Vector2d& p);

/** \brief u . v */
double
dot2 (const Eigen::Vector2d& u, const Eigen::Vector2d& v);

/** \brief |p - q|^2 */
double
squaredDistance2 (const Eigen::Vector2d& p, const Eigen::Vector2d& q);

}  // namespace simulation
}  // namespace pcl_crf
