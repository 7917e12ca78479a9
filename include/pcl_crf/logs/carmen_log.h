#pragma once

#include <pcl_crf/logs/laser_log.h>

#include <istream>
#include <string>

namespace pcl_crf {

/** \brief How readCarmenLog interprets a CARMEN log.
 *
 *  Readings outside [min_range, max_range] are "no return" and dropped: CARMEN
 *  logs write 81.9, 50 or 32.76 (and similar) for beams that saw nothing. A
 *  ROBOTLASER1 record carries its laser's own maximum range: readings at or beyond
 *  it are no return as well (the smaller of the two ranges applies).
 */
struct CarmenReadOptions
{
  /** shortest valid reading [m] (default 0.01; shorter readings are dropped). */
  double min_range = 0.01;
  /** longest valid reading [m] (default 30; longer readings are dropped, and so are a
   *  ROBOTLASER1 record's readings at or beyond its own maximum range when shorter). */
  double max_range = 30.0;
  /** angle of the first beam [rad] (default -pi/2: the scans cover 180 degrees
   *  from right to left). */
  double angle_min = -1.5707963267948966;
  /** field of view [rad] (default pi): beam i of n is at angle_min + i * fov / (n - 1). */
  double field_of_view = 3.141592653589793;
  /** stop after this many scans (0 = read the whole log). */
  std::size_t max_scans = 0;
};

/** \brief Reads a CARMEN log (plain text or gzip-compressed, detected from the
 *  file's first bytes).
 *
 *  Understood records: \c FLASER (front laser, old format), \c ROBOTLASER1
 *  (new format; its own start angle, resolution and maximum range are used) and
 *  \c ODOM.
 *  Other records (PARAM, NEFF, RLASER, comments, ...) are skipped. Each laser
 *  record becomes one LaserScanRecord with the logged pose (\c has_pose) and
 *  the odometry step since the previous scan:
 *
 *  - If every laser record's odometry fields equal its pose and the ODOM stream
 *    is re-anchored at the records (the first ODOM line after every record that
 *    has one equals its pose, and at least one has one), the log is a corrected
 *    log (the Radish "-corrected" logs, whose pose is the SLAM-corrected one) and
 *    the odometry comes from the ODOM stream:
 *    step(j -> j+1) = inv(T_j) * ODOM_last, T_j the corrected pose of scan j and
 *    ODOM_last the last ODOM line before scan j+1 (if scan j+1 has no ODOM line
 *    since scan j, it has no odometry step).
 *  - Otherwise (raw logs) the laser records' odometry fields are odometry:
 *    step(j -> j+1) = inv(O_j) * O_j+1. A raw log's pose equals its odometry
 *    fields too (both are the robot's odometry), but its ODOM stream is the
 *    odometry itself, which moves on after a record; a raw log without ODOM lines
 *    is raw as well. (A raw log of a robot that never moves reads as corrected:
 *    its poses are then right.)
 *
 *  LaserLog::has_reference_poses is true in the first case only (a raw log's
 *  pose is not a reference). The laser's mounting offset is not applied.
 *  \throws LogError naming the file, the line and the problem (missing file,
 *  malformed record, no laser record at all).
 *
 *  \code
 *  pcl_crf::CarmenReadOptions options;
 *  options.max_range = 25.0;
 *  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog ("intel-corrected.log.gz", options);
 *  \endcode
 */
LaserLog
readCarmenLog (const std::string& path, const CarmenReadOptions& options = {});

/** \brief Same as readCarmenLog, from an already opened (uncompressed) stream.
 *  \param[in] in the log text
 *  \param[in] name the name used in messages and LaserLog::path
 *  \param[in] options the reading rules
 */
LaserLog
readCarmenLog (std::istream& in, const std::string& name, const CarmenReadOptions& options = {});

}  // namespace pcl_crf
