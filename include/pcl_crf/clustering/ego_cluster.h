#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Squared Mahalanobis distance between a cluster's motion and the odometry.
 *
 *  The static world moves by the inverse of the sensor's motion, so the cluster's
 *  T_target_source is inverted into a sensor motion (x, y, θ) and compared with the
 *  odometry's T_source_target (x, y, θ), the angle difference wrapped to (−π, π]:
 *  d² = eᵀ Σ⁻¹ e with Σ the odometry covariance (a singular Σ uses its pseudo-inverse).
 *  \param[in] T_target_source the cluster's motion
 *  \param[in] odometry the measured sensor motion and its covariance
 */
double
odometryMahalanobis (const Rigid2d& T_target_source, const Odometry& odometry);

/** \brief The cluster whose motion is nearest to the odometry in Mahalanobis
 *  distance: the static world, whose motion is the robot's (Sec. IV). Ties go to
 *  the lower index.
 *
 *  \code
 *  const int world = pcl_crf::clustering::selectStaticCluster (motions, pair.odometry);
 *  \endcode
 *  \return its index, or −1 when \a motions is empty
 */
int
selectStaticCluster (const std::vector<Rigid2d>& motions, const Odometry& odometry);

}  // namespace clustering
}  // namespace pcl_crf
