#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Settings of the consistency-based moving-object detector (Wang, Thorpe,
 *  Thrun, Hebert & Durrant-Whyte, IJRR 2007). */
struct ConsistencyParameters
{
  /** a point is in the other scan's free space when, seen from the other sensor, it
   *  lies at least this much in front of the other scan's returns [m]; > 0, default
   *  0.3 m (absorbs the ego-motion error and the range noise). */
  double free_space_margin = 0.3;
  /** the other scan's returns on the beams within ± this many of the point's bearing
   *  must all lie behind the point (absorbs the angular error of the ego motion)
   *  [beams]; ≥ 0, default 1. */
  int beam_window = 1;
  /** consecutive points farther apart than this start a new segment [m]; > 0, default 0.5 m. */
  double segment_break_distance = 0.5;
  /** a segment is dynamic when more than this fraction of its points is; in [0, 1), default 0.5. */
  double min_dynamic_fraction = 0.5;
  /** with an ego-motion covariance, the margin grows by this many standard deviations
   *  of the translation and the beam window by as many of the bearing (rotation plus
   *  translation over the range) [σ]; ≥ 0, default 2. */
  double confidence_sigmas = 2.0;
};

/** \brief For every point of one scan: true when it lies in the free space the other
 *  scan observed (the other sensor saw through where the point is, so the point moved).
 *  Points outside the other scan's field of view or on beams without a return are
 *  unknown and reported false (static).
 *  \param[in] points 2 x N points in their own sensor frame
 *  \param[in] T_other_points maps them into the other sensor's frame
 *  \param[in] other 2 x M points of the other scan in beam order, its own frame
 *  \param[in] sensor the laser of both scans (beam angles)
 *  \param[in] parameters margin and beam window
 *  \param[in] covariance covariance of (x [m], y [m], θ [rad]) of the ego motion, or
 *  null; it widens the margin and the window per point (see ConsistencyParameters)
 */
std::vector<bool>
freeSpaceViolations (const Eigen::Matrix2Xd& points, const Rigid2d& T_other_points, const Eigen::Matrix2Xd& other,
                     const SensorInfo& sensor, const ConsistencyParameters& parameters = {},
                     const Eigen::Matrix3d* covariance = nullptr);

/** \brief The source scan split into the static world (cluster 0) and one cluster per
 *  dynamic segment (1, 2, ... in scan order).
 *
 *  The source scan is segmented by distance (segmentByDistance ()); a segment is
 *  dynamic when most of its points violate the target scan's free space under the
 *  ego motion.
 *
 *  \code
 *  const std::vector<int> clusters = pcl_crf::clustering::detectDynamicSegments (
 *      pair.source, pair.target, pair.sensor, pair.odometry.T_source_target.inverse ());
 *  \endcode
 *  \param[in] T_target_source the static world's motion (the inverse of the ego motion)
 *  \param[in] covariance covariance of the ego motion (x, y, θ), or null
 *  \return cluster of every source point
 *  \throws std::invalid_argument for invalid parameters or sensor metadata.
 */
std::vector<int>
detectDynamicSegments (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const SensorInfo& sensor,
                       const Rigid2d& T_target_source, const ConsistencyParameters& parameters = {},
                       const Eigen::Matrix3d* covariance = nullptr);

}  // namespace clustering
}  // namespace pcl_crf
