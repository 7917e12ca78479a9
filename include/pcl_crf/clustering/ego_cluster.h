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

/** \brief The static world among the clusters: the one whose motion best explains
 *  the odometry (Sec. IV: the world moves by the inverse of the robot's motion).
 *
 *  Without \a sizes, the cluster nearest to the odometry in Mahalanobis distance.
 *  With \a sizes (points per cluster), the most probable one under a prior that
 *  makes the static world as likely as the share of the scan it covers:
 *  argmin_l ½ d²_l − log n_l, i.e. argmax p(odometry | T_l) p(static = l) with
 *  p(odometry | T_l) ∝ exp(−½ d²_l) and p(static = l) ∝ n_l. Under a tight odometry
 *  this is the nearest cluster; under a loose one (an odometry that is a guess, e.g.
 *  "not moving" with a wide covariance) a world split into a large and a small
 *  cluster keeps the large one rather than whichever is nearer by a hair. Clusters
 *  of size 0 are never chosen while another has points. Ties go to the lower index.
 *
 *  \code
 *  const int world = pcl_crf::clustering::selectStaticCluster (motions, pair.odometry, sizes);
 *  \endcode
 *  \param[in] motions the clusters' T_target_source
 *  \param[in] odometry the measured sensor motion and its covariance
 *  \param[in] sizes empty, or the number of points of every cluster (as many as \a motions)
 *  \return its index, or −1 when \a motions is empty
 *  \throws std::invalid_argument when \a sizes is neither empty nor one per motion
 */
int
selectStaticCluster (const std::vector<Rigid2d>& motions, const Odometry& odometry,
                     const std::vector<int>& sizes = {});

}  // namespace clustering
}  // namespace pcl_crf
