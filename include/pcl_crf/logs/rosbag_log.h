#pragma once

#include <pcl_crf/logs/laser_log.h>

#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {

/** \brief Which topics readRosbagLog reads and how it turns them into scans.
 *
 *  Scans come from a sensor_msgs/LaserScan topic; optional
 *  geometry_msgs/PoseStamped topics give the reference (ground-truth) pose of
 *  the ego vehicle and of other moving objects (e.g. motion capture).
 */
struct RosbagReadOptions
{
  /** the sensor_msgs/LaserScan topic (default "/scan"). */
  std::string scan_topic = "/scan";
  /** the ego vehicle's geometry_msgs/PoseStamped topic, or "" for none (default). */
  std::string pose_topic;
  /** geometry_msgs/PoseStamped topics of other moving objects (default none). */
  std::vector<std::string> object_topics;
  /** pose of the laser in the ego pose frame (default identity). For the
   *  datmo bags of shared/data, (-0.166, 0.019, 0) fits best. */
  Rigid2d T_pose_laser = Rigid2d::Identity ();
  /** the reference pose belonging to a scan stamped t is the one stamped
   *  t + pose_delay [s] (default 0). Every pose track of the returned log is
   *  shifted by -pose_delay, so it is on the scans' clock. */
  double pose_delay = 0.0;
  /** largest time gap between two pose samples that is interpolated [s] (default 0.5). */
  double max_pose_gap = 0.5;
  /** footprint half length and half width of every tracked object around its
   *  pose [m] (default 0.22 x 0.095: the 1/10-scale cars of the datmo bags). */
  Eigen::Vector2d object_half_extent = Eigen::Vector2d (0.22, 0.095);
  /** ObjectTruth::kind of the tracked objects (default "car"). */
  std::string object_kind = "car";
  /** stop after this many scans (0 = all). */
  std::size_t max_scans = 0;
};

/** \brief true when pcl_crf was built with the ROS bag reader (CMake option
 *  PCL_CRF_WITH_ROSBAG and Debian's librosbag-dev). Without it, the functions
 *  below throw LogError saying so.
 */
bool
rosbagSupported ();

/** \brief The topics of a ROS1 bag with their message types, sorted by topic.
 *  \throws LogError for a missing or unreadable bag, or one whose records are
 *  truncated or corrupted (checkRosbagStructure (), naming the byte). */
std::vector<std::pair<std::string, std::string>>
listRosbagTopics (const std::string& path);

/** \brief Reads the laser scans of a ROS1 bag (v2.0, any chunk compression),
 *  with reference poses when a pose topic is given.
 *
 *  Readings that are not finite or outside [range_min, range_max) of their
 *  message are dropped; the others keep beam order (a negative
 *  angle_increment is turned into the counter-clockwise order by reversing the
 *  beams). With \c pose_topic, each scan's \c pose is the ego pose interpolated
 *  at stamp + pose_delay times T_pose_laser (\c has_pose false where the track
 *  does not cover the scan). Every object topic becomes a TrackedObject.
 *  Bags carry no odometry here (LaserLog::has_odometry is false).
 *
 *  Repeated stamps: of the scans stamped alike only the first in the bag's order
 *  is kept (a pair of two would have no time step, and one reference pose at their
 *  stamp for both); pose samples stamped alike with the same pose are one sample,
 *  and a stamp that carries different poses is left out of its track (which pose is
 *  right is unknown; the track interpolates across it). Either adds a message to
 *  LaserLog::warnings naming the topic, the count and the first such stamp.
 *  \throws LogError naming the bag and topic (missing file, unknown topic
 *  listing the bag's topics, wrong message type, no scan, built without
 *  ROS bag support), or the byte where the bag's records are truncated or
 *  corrupted (checkRosbagStructure (), run first on the topics read).
 *
 *  \code
 *  pcl_crf::RosbagReadOptions options;
 *  options.pose_topic = "/ego_pose";
 *  options.object_topics = {"/red_pose"};
 *  options.T_pose_laser = pcl_crf::makeRigid2d (-0.166, 0.019, 0.0);
 *  const pcl_crf::LaserLog log = pcl_crf::readRosbagLog ("overtakes.bag", options);
 *  \endcode
 */
LaserLog
readRosbagLog (const std::string& path, const RosbagReadOptions& options = {});

/** \brief Writes \a log as a ROS1 bag that readRosbagLog reads back: every scan
 *  as a sensor_msgs/LaserScan on options.scan_topic (dropped beams as +inf),
 *  the scans' poses (times inv(T_pose_laser), stamped at stamp + pose_delay)
 *  as geometry_msgs/PoseStamped on options.pose_topic when it is set, and each
 *  tracked object on the matching entry of options.object_topics. Meant for
 *  tests and for handing simulated scans to ROS tools.
 *  \throws LogError when the bag cannot be written or a topic is missing.
 */
void
writeRosbagLog (const std::string& path, const LaserLog& log, const RosbagReadOptions& options = {});

}  // namespace pcl_crf
