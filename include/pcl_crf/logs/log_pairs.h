#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/logs/laser_log.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief The odometry covariance given to pairs made from logs: independent
 *  errors whose standard deviations grow with the distance travelled d [m] and
 *  the angle turned |dtheta| [rad] of the odometry step,
 *
 *    sigma_x = sigma_y = max (min_translation_std, translation_per_metre * d)
 *    sigma_theta = max (min_rotation_std, rotation_per_radian * |dtheta| + rotation_per_metre * d)
 *
 *  The defaults are fitted to the raw-odometry errors of the nine shared
 *  corrected CARMEN logs (consecutive scans, mostly about 1 m and up to 0.8 rad
 *  apart; 9 200 steps): pooled, 95 % of the translation errors are within
 *  2.0 sigma_x and 95 % of the rotation errors within 2.0 sigma_theta (per
 *  log, these 95th percentiles range from 1.1 to 3.2 sigma and 0.2 to 2.5 sigma).
 *  The "odometry" row of scripts/ego_motion_table.sh shows the raw errors.
 */
struct OdometryNoiseModel
{
  /** translation standard deviation per metre travelled (default 0.1). */
  double translation_per_metre = 0.1;
  /** rotation standard deviation per radian turned (default 0.2). */
  double rotation_per_radian = 0.2;
  /** rotation standard deviation per metre travelled [rad/m] (default 0.05). */
  double rotation_per_metre = 0.05;
  /** smallest translation standard deviation [m] (default 0.04). */
  double min_translation_std = 0.04;
  /** smallest rotation standard deviation [rad] (default 0.02). */
  double min_rotation_std = 0.02;

  /** \brief The 3x3 covariance of (x [m], y [m], theta [rad]) for one odometry step. */
  Eigen::Matrix3d
  covariance (const Rigid2d& step) const;
};

/** \brief How makeLogPair builds scan pairs from a log. */
struct LogPairOptions
{
  /** pair scan k with scan k + step (default 1: consecutive scans). */
  std::size_t step = 1;
  /** covariance of the odometry when the log has odometry. */
  OdometryNoiseModel noise;
  /** without odometry the guess is the identity with these standard deviations
   *  (default 1 m and 0.5 rad: a weak prior). */
  double no_odometry_translation_std = 1.0;
  double no_odometry_rotation_std = 0.5;
  /** give every point an object label and a true match (default false):
   *  points inside a tracked object's footprint (grown by footprint_margin)
   *  belong to it, all others to the static world; matches follow the
   *  simulator's association rule (pcl_crf::simulation::assignTrueMatches) with
   *  the reference motions. These labels are only as good as the reference
   *  poses and the assumption that everything untracked is static. */
  bool label_points = false;
  /** range noise used by the association tolerance when labelling [m] (default 0.01). */
  double range_noise = 0.01;
  /** footprint growth when labelling tracked objects' points [m] (default 0.05). */
  double footprint_margin = 0.05;
  /** a tracked object stands still in a pair when no corner of its footprint (grown
   *  by footprint_margin) moves this far or farther relative to the static world
   *  between the two scans [m]; it is then part of the static world, not an object
   *  of the pair (a parked car is no mover). Default 0.01, the range noise: a pair
   *  cannot show a smaller motion. 0 keeps every tracked object. */
  double still_tolerance = 0.01;
};

/** \brief Number of pairs (k, k + step) a log of \a scan_count scans holds. */
std::size_t
logPairCount (std::size_t scan_count, std::size_t step);

/** \brief Builds the scan pair (scan k, scan k + options.step) of a log.
 *
 *  - source/target: the scans' points in beam order; sensor: the source scan's.
 *  - odometry: the composed odometry steps k+1 .. k+step with the noise model's
 *    covariance (summed over the steps: first order, the coupling of rotation
 *    into translation is ignored), or the identity with the weak prior
 *    when a step has no odometry; its interval is the scans' stamp difference
 *    (0, unknown, when the stamps do not increase).
 *  - objects: when both scans have a reference pose P_s, P_t (sensor in the
 *    world), the static world (id 0, "world", T_target_source = inv(P_t) * P_s,
 *    the inverse of the reference ego motion) and every tracked object whose
 *    pose O is known at both stamps (ids 1, 2, ... in the order of
 *    LaserLog::objects, T_target_source = inv(P_t) * O_t * inv(O_s) * P_s) that
 *    does not stand still (options.still_tolerance); otherwise none. With labels,
 *    tracked objects no point hit are left out.
 *  - labels and matches only with options.label_points (then the pair passes
 *    validateScanPair and can be saved with saveScanPair); otherwise they stay
 *    empty and ScanPair::hasTruth () is false: an *unlabelled* pair, whose
 *    objects (if any) still give the reference ego motion (referenceEgoMotion).
 *
 *  The pair's name is "scan_KKKKKK" (k zero-padded to 6 digits).
 *  \throws LogError when k + step is past the end, the scans' beam layouts
 *  differ, a scan is empty, or labels are asked for without reference poses.
 *
 *  \code
 *  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog ("intel-corrected.log.gz");
 *  for (std::size_t k = 0; k < pcl_crf::logPairCount (log.scans.size (), 1); ++k) {
 *    const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, k);
 *    pcl_crf::Rigid2d truth;
 *    if (pcl_crf::referenceEgoMotion (pair, truth)) { ... }
 *  }
 *  \endcode
 */
ScanPair
makeLogPair (const LaserLog& log, std::size_t k, const LogPairOptions& options = {});

/** \brief The reference (ground-truth) sensor motion T_source_target of a pair:
 *  the inverse of its static-world object's motion.
 *  \return false when the pair has no static-world object. */
bool
referenceEgoMotion (const ScanPair& pair, Rigid2d& T_source_target);

}  // namespace pcl_crf
