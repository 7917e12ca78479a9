#pragma once

#include <pcl_crf/logs/carmen_log.h>
#include <pcl_crf/logs/rosbag_log.h>

#include <string>

namespace pcl_crf {

/** \brief The log formats readLaserLog understands. */
enum class LaserLogFormat
{
  /** CARMEN text log, plain or gzip-compressed (readCarmenLog). */
  Carmen,
  /** ROS1 bag v2.0 (readRosbagLog; needs rosbagSupported ()). */
  Rosbag
};

/** \brief Reading options for both formats; only the one matching the file is used. */
struct LaserLogReadOptions
{
  CarmenReadOptions carmen;
  RosbagReadOptions rosbag;
};

/** \brief The format of a log file, from its first bytes ("#ROSBAG V2.0" is a
 *  bag; anything else is taken for a CARMEN log).
 *  \throws LogError when the file cannot be opened. */
LaserLogFormat
detectLaserLogFormat (const std::string& path);

/** \brief Reads a CARMEN log or a ROS bag, whichever \a path is.
 *  \throws LogError from the reader.
 *
 *  \code
 *  pcl_crf::LaserLogReadOptions options;
 *  options.rosbag.pose_topic = "/ego_pose";
 *  const pcl_crf::LaserLog log = pcl_crf::readLaserLog (path, options);
 *  \endcode
 */
LaserLog
readLaserLog (const std::string& path, const LaserLogReadOptions& options = {});

}  // namespace pcl_crf
