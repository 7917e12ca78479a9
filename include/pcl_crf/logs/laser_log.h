#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Thrown by the log readers; the message names the file (and line or
 *  topic) and what is wrong with it.
 */
class LogError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/** \brief One laser scan of a recorded log (CARMEN or ROS bag), in beam order.
 *
 *  Only valid readings are kept (see the readers for the rules); \c beams holds
 *  the beam index of every kept point, so the order is the beam order and the
 *  angle of point i is sensor.angle_min + beams[i] * sensor.angle_increment.
 *
 *  \code
 *  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog ("intel-corrected.log.gz");
 *  const pcl_crf::LaserScanRecord& scan = log.scans.front ();
 *  std::cout << scan.points.cols () << " points at t = " << scan.stamp << " s\n";
 *  \endcode
 */
struct LaserScanRecord
{
  /** time stamp of the scan [s] (CARMEN: the log's timestamp; bag: header.stamp). */
  double stamp = 0.0;
  /** the laser's beam layout; angles counter-clockwise, x forward, y left. */
  SensorInfo sensor;
  /** valid points (x, y) in the sensor frame [m], in beam order. */
  Eigen::Matrix2Xd points;
  /** beam index of every point (same length as points.cols ()). */
  std::vector<int> beams;
  /** true when \c pose holds a reference pose (CARMEN corrected pose, mocap). */
  bool has_pose = false;
  /** reference pose of the sensor in the log's world frame (x [m], y [m], theta [rad]). */
  Rigid2d pose = Rigid2d::Identity ();
  /** true when \c odometry_step holds the odometry since the previous scan. */
  bool has_odometry_step = false;
  /** raw-odometry motion of the sensor from the previous scan to this one:
   *  the pose at this scan expressed in the previous scan's frame. */
  Rigid2d odometry_step = Rigid2d::Identity ();
};

/** \brief A time series of 2D poses (e.g. motion capture) with interpolation. */
struct PoseTrack
{
  /** time stamps [s], strictly increasing. */
  std::vector<double> stamps;
  /** poses in the log's world frame, one per stamp. */
  std::vector<Rigid2d> poses;

  /** \brief Pose at time \a t [s], linearly interpolated (angle along the
   *  shortest arc) between the two surrounding samples.
   *  \param[in] t the query time [s]
   *  \param[out] pose the interpolated pose
   *  \param[in] max_gap samples farther apart than this around \a t are not
   *  interpolated [s] (default 0.5)
   *  \return false when \a t is outside the track (by more than 1 microsecond)
   *  or inside a gap.
   */
  bool
  interpolate (double t, Rigid2d& pose, double max_gap = 0.5) const;

  /** \brief Adds a sample; samples must come in increasing time order
   *  (an equal or earlier stamp is ignored). */
  void
  append (double stamp, const Rigid2d& pose);

  bool
  empty () const
  {
    return stamps.empty ();
  }
};

/** \brief An object tracked by a reference system (e.g. a motion-capture
 *  marker set on another car): its name, kind, poses and footprint.
 */
struct TrackedObject
{
  /** where the poses come from (the bag topic, e.g. "/red_pose"). */
  std::string name;
  /** one word for ObjectTruth::kind ("car", "pedestrian", ...). */
  std::string kind = "car";
  /** poses of the object's reference point in the log's world frame. */
  PoseTrack track;
  /** half length (along its x) and half width of the object's footprint,
   *  centred on the tracked pose [m]; points inside belong to the object. */
  Eigen::Vector2d half_extent = Eigen::Vector2d (0.22, 0.095);
};

/** \brief Everything a log reader returns: scans in time order, plus tracks of
 *  other moving objects when the log has them.
 */
struct LaserLog
{
  /** the file the log came from. */
  std::string path;
  /** the scans, in the order of the log. */
  std::vector<LaserScanRecord> scans;
  /** other objects with reference poses (bag pose topics); empty for CARMEN. */
  std::vector<TrackedObject> objects;
  /** true when the scans' poses are a reference (corrected or mocap) pose. */
  bool has_reference_poses = false;
  /** true when the scans carry odometry steps. */
  bool has_odometry = false;
  /** what the reader left out of the log and why, one message each naming the file
   *  (e.g. a bag's scans stamped like the scan before them); empty when nothing was.
   *  The tools print them as warnings. */
  std::vector<std::string> warnings;
};

/** \brief How many scans of \a log are stamped at or before the scan before them (a
 *  logger's clock stepping back, or one stamp copied to several scans). A pair a scan
 *  like that ends has no known time interval (makeLogPair () leaves
 *  Odometry::interval at 0), so the search for moving objects is not bounded by it. */
std::size_t
countStampsNotAfterTheLast (const LaserLog& log);

/** \brief true when poses \a a and \a b differ by less than \a tolerance in translation
 *  [m] and in rotation [rad]: the same pose, as a log's text or a bag's messages repeat it. */
bool
samePose (const Rigid2d& a, const Rigid2d& b, double tolerance);

}  // namespace pcl_crf
