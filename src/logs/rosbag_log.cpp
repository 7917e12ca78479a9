#include <pcl_crf/logs/rosbag_log.h>
#include <pcl_crf/logs/rosbag_structure.h>

#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/dataset_io.h>

// The ROS headers are only seen by this file; the CMake option PCL_CRF_WITH_ROSBAG
// defines PCL_CRF_HAVE_ROSBAG and adds their include folders to it alone.
#if defined(PCL_CRF_HAVE_ROSBAG) && PCL_CRF_HAVE_ROSBAG
#include <geometry_msgs/PoseStamped.h>
#include <rosbag/bag.h>
#include <ros/exception.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

namespace pcl_crf {

#if defined(PCL_CRF_HAVE_ROSBAG) && PCL_CRF_HAVE_ROSBAG

namespace {

using StampedPoses = std::vector<std::pair<double, Rigid2d>>;

/** Pose messages of one stamp agree to this [m, rad] when they carry one pose. */
constexpr double kSamePoseTolerance = 1e-9;

double
yawOf (const geometry_msgs::Quaternion& q)
{
  return yawOfQuaternion (q.w, q.x, q.y, q.z);
}

/** \brief Opens \a bag; for reading, once checkRosbagStructure () has checked what
 *  librosbag will follow (\a topics: those whose messages will be read). */
void
openBag (rosbag::Bag& bag, const std::string& path, rosbag::bagmode::BagMode mode,
         const std::vector<std::string>& topics = {})
{
  if (mode == rosbag::bagmode::Read && !std::filesystem::is_regular_file (path))
    throw LogError (path + ": bag file not found");
  if (mode == rosbag::bagmode::Read)
    checkRosbagStructure (path, topics);  // librosbag trusts the bag's lengths and offsets
  try {
    bag.open (path, mode);
  }
  catch (const rosbag::BagException& error) {
    throw LogError (path + ": cannot open the ROS bag (" + error.what () + ")");
  }
}

std::string
describeTopics (const std::vector<std::pair<std::string, std::string>>& topics)
{
  std::string text;
  for (const auto& topic : topics)
    text += (text.empty () ? "" : ", ") + topic.first + " (" + topic.second + ")";
  return text.empty () ? "none" : text;
}

void
requireTopic (const std::string& path, const std::vector<std::pair<std::string, std::string>>& topics,
              const std::string& topic, const std::string& type)
{
  for (const auto& entry : topics)
    if (entry.first == topic) {
      if (entry.second != type)
        throw LogError (path + ": topic " + topic + " holds " + entry.second + ", not " + type);
      return;
    }
  throw LogError (path + ": no topic " + topic + " in the bag; it has: " + describeTopics (topics));
}

/** \brief \a value as the shortest text that names it ("1e+30", "-100"). */
std::string
shortNumber (double value)
{
  return formatGeneral (value, 6);
}

/** \brief A time stamp [s] to the millisecond ("1575811858.273"). */
std::string
stampText (double seconds)
{
  return formatFixed (seconds, 3);
}

/** \brief What makes a LaserScan message unusable, or an empty string when nothing does:
 *  an angle that is not finite, beams without a step between them (or one finer than
 *  2π / kMaxBeamCount), beams spanning more than one turn, a negative minimum range, or
 *  no finite positive maximum range within 1e18 m (every beam would fall on one ray,
 *  none be a return, or points overflow single precision). */
std::string
laserScanProblem (const sensor_msgs::LaserScan& message)
{
  if (message.ranges.size () > static_cast<std::size_t> (kMaxBeamCount))
    return std::to_string (message.ranges.size ()) + " beams, more than " + std::to_string (kMaxBeamCount);
  if (!std::isfinite (message.angle_min))
    return "angle_min is not a finite angle";
  if (!std::isfinite (message.angle_increment) || message.angle_increment == 0.0f)
    return "angle_increment must be a finite angle other than 0";
  if (!std::isfinite (message.range_min) || !std::isfinite (message.range_max) || !(message.range_max > 0.0f))
    return "range_min and range_max must be finite and range_max positive";
  if (message.range_min < 0.0f)
    return "range_min " + shortNumber (message.range_min) + " is negative (a negative range would be mirrored "
           "behind the sensor)";
  if (message.range_max > kMaxCoordinate)
    return "range_max lies beyond 1e18 m";
  // No laser steps by less than 2π / kMaxBeamCount, nor turns more than one circle
  // between its first and last beam (or starts its scan beyond two turns).
  const double step = std::abs (static_cast<double> (message.angle_increment));
  const double span = step * static_cast<double> (std::max<std::size_t> (message.ranges.size (), 1) - 1);
  constexpr double kTurn = 2.0 * M_PI;
  if (step < kTurn / kMaxBeamCount)
    return "angle_increment " + shortNumber (message.angle_increment) + " rad is finer than 2π / " +
           std::to_string (kMaxBeamCount) + " (every beam on nearly one ray)";
  if (span > kTurn * (1.0 + 1e-6) || std::abs (message.angle_min) > 2.0 * kTurn)
    return "the beams span " + shortNumber (span) + " rad from angle_min " + shortNumber (message.angle_min) +
           " rad: more than one turn, or a start beyond two turns";
  return {};
}

/** \brief What makes a PoseStamped message unusable, or an empty string: a position or
 *  orientation that is not finite, or an orientation of zero length. */
std::string
poseProblem (const geometry_msgs::Pose& pose)
{
  const geometry_msgs::Point& p = pose.position;
  const geometry_msgs::Quaternion& q = pose.orientation;
  if (!std::isfinite (p.x) || !std::isfinite (p.y) || !std::isfinite (p.z))
    return "the position is not finite";
  if (std::max ({std::abs (p.x), std::abs (p.y), std::abs (p.z)}) > kMaxCoordinate)
    return "the position lies beyond 1e18 m";
  const double norm = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  if (!std::isfinite (norm) || !(norm > 0.0))
    return "the orientation is not a finite, non-zero quaternion";
  return {};
}

/** \brief A LogError naming the bag, the topic and the message's time. */
LogError
messageError (const std::string& path, const rosbag::MessageInstance& message, const std::string& problem)
{
  return LogError (path + ": topic " + message.getTopic () + ", message at " + std::to_string (message.getTime ().toSec ()) +
                   " s: " + problem);
}

/** \brief The LaserScan of \a message, deserialized from its bytes once the lengths they
 *  declare (frame id, ranges, intensities) are checked to fit them. ROS's deserializer
 *  sizes each array from its declared length before reading it: a corrupt length of 2^31
 *  allocated 8 GB (for 40 s) before the read failed. Layout: seq, stamp (2 x uint32),
 *  frame_id (uint32 length + bytes), 7 float32 (angles, times, ranges), then two float32
 *  arrays (uint32 count + values).
 *  \throws LogError (messageError ()) when a length does not fit. */
sensor_msgs::LaserScan
readLaserScan (const std::string& path, const rosbag::MessageInstance& message)
{
  std::vector<std::uint8_t> bytes (message.size ());
  ros::serialization::OStream out (bytes.data (), static_cast<std::uint32_t> (bytes.size ()));
  message.write (out);
  std::size_t at = 12;  // seq, stamp
  const auto length = [&] (std::size_t item) -> bool {  // reads a uint32 length, skips its items
    if (at + 4 > bytes.size ())
      return false;
    std::uint32_t count = 0;
    std::memcpy (&count, bytes.data () + at, 4);  // little-endian, as ROS writes it
    at += 4;
    if (count > (bytes.size () - at) / item)
      return false;
    at += count * item;
    return true;
  };
  const bool frame_id_fits = length (1);
  at += 7 * 4;
  if (!frame_id_fits || !length (4) || !length (4))
    throw messageError (path, message, "its frame id, ranges or intensities declare more values than the message "
                                       "holds (a corrupt bag)");
  sensor_msgs::LaserScan scan;
  ros::serialization::IStream in (bytes.data (), static_cast<std::uint32_t> (bytes.size ()));
  ros::serialization::deserialize (in, scan);
  return scan;
}

LaserScanRecord
toRecord (const sensor_msgs::LaserScan& message)
{
  LaserScanRecord record;
  record.stamp = message.header.stamp.toSec ();
  const int n = static_cast<int> (message.ranges.size ());
  const bool reversed = message.angle_increment < 0.0f;
  record.sensor.beam_count = n;
  record.sensor.angle_increment = std::abs (static_cast<double> (message.angle_increment));
  record.sensor.angle_min =
      reversed ? message.angle_min + (n - 1) * static_cast<double> (message.angle_increment) : message.angle_min;
  record.sensor.range_max = message.range_max;
  record.points.resize (2, n);
  Eigen::Index kept = 0;
  for (int b = 0; b < n; ++b) {
    const double r = message.ranges[reversed ? n - 1 - b : b];
    if (!std::isfinite (r) || r < message.range_min || r >= message.range_max)
      continue;
    const double angle = record.sensor.angle_min + b * record.sensor.angle_increment;
    record.points.col (kept++) << r * std::cos (angle), r * std::sin (angle);
    record.beams.push_back (b);
  }
  record.points.conservativeResize (2, kept);
  return record;
}

/** \brief "path: N <noun>s of <topic> <description> were left out (the first at T s):
 *  <consequence>", a LaserLog warning. */
std::string
repeatedStampsWarning (const std::string& path, std::size_t count, const std::string& noun, const std::string& topic,
                       const std::string& description, double first_stamp, const std::string& consequence)
{
  return path + ": " + std::to_string (count) + " " + noun + (count == 1 ? "" : "s") + " of " + topic + " " +
         description + (count == 1 ? " was" : " were") + " left out (the first at " + stampText (first_stamp) +
         " s): " + consequence;
}

/** \brief Keeps the first of every run of scans stamped alike (\a scans sorted by stamp):
 *  two of them would make a pair without a time step, with one reference pose for both.
 *  \return the warning, or "" when every stamp is distinct. */
std::string
dropScansStampedAlike (const std::string& path, const std::string& topic, std::vector<LaserScanRecord>& scans)
{
  const auto alike = [] (const LaserScanRecord& a, const LaserScanRecord& b) { return a.stamp == b.stamp; };
  const auto first = std::adjacent_find (scans.begin (), scans.end (), alike);
  if (first == scans.end ())
    return {};
  const double stamp = first->stamp;
  const auto end = std::unique (scans.begin (), scans.end (), alike);
  const auto dropped = static_cast<std::size_t> (scans.end () - end);
  scans.erase (end, scans.end ());
  return repeatedStampsWarning (path, dropped, "scan", topic, "stamped like the scan before it", stamp,
                                "a pair of two such scans would have no time step, and one reference pose for both");
}

/** \brief The track of \a samples shifted by -delay. Samples stamped alike with the same
 *  pose are one; a stamp that carries different poses is left out (which is right is
 *  unknown), and its bag stamp added to \a conflicting. */
PoseTrack
toTrack (StampedPoses samples, double delay, std::vector<double>& conflicting)
{
  std::stable_sort (samples.begin (), samples.end (),
                    [] (const auto& a, const auto& b) { return a.first < b.first; });
  PoseTrack track;
  for (std::size_t i = 0, j = 0; i < samples.size (); i = j) {
    bool agree = true;
    for (j = i + 1; j < samples.size () && samples[j].first == samples[i].first; ++j)
      agree = agree && samePose (samples[i].second, samples[j].second, kSamePoseTolerance);
    if (agree)
      track.append (samples[i].first - delay, samples[i].second);
    else
      conflicting.push_back (samples[i].first);
  }
  return track;
}

/** \brief The track of a pose topic's samples (toTrack ()), with a warning in \a log
 *  when stamps carrying different poses were left out. */
PoseTrack
poseTrack (const StampedPoses& samples, const std::string& topic, double delay, LaserLog& log)
{
  std::vector<double> conflicting;
  PoseTrack track = toTrack (samples, delay, conflicting);
  if (!conflicting.empty ())
    log.warnings.push_back (repeatedStampsWarning (log.path, conflicting.size (), "stamp", topic,
                                                   "carrying different poses", conflicting.front (),
                                                   "which pose is right is unknown; the track interpolates across it"));
  return track;
}

void
checkOptions (const std::string& path, const RosbagReadOptions& options)
{
  if (options.scan_topic.empty ())
    throw LogError (path + ": no scan topic given");
  if (!(options.max_pose_gap > 0.0) || !std::isfinite (options.pose_delay))
    throw LogError (path + ": the pose gap must be positive and the pose delay finite");
  if (!(options.object_half_extent.array () > 0.0).all ())
    throw LogError (path + ": the object footprint must have a positive size");
}

}  // namespace

bool
rosbagSupported ()
{
  return true;
}

namespace {

/** \brief The topics of the open \a bag with their message types, sorted by topic. */
std::vector<std::pair<std::string, std::string>>
topicsOf (const rosbag::Bag& bag, const std::string& path)
{
  std::set<std::pair<std::string, std::string>> topics;
  try {
    rosbag::View view (bag);
    for (const rosbag::ConnectionInfo* connection : view.getConnections ())
      topics.emplace (connection->topic, connection->datatype);
  }
  catch (const rosbag::BagException& error) {
    throw LogError (path + ": cannot read the ROS bag (" + error.what () + ")");
  }
  return {topics.begin (), topics.end ()};
}

}  // namespace

std::vector<std::pair<std::string, std::string>>
listRosbagTopics (const std::string& path)
{
  rosbag::Bag bag;
  openBag (bag, path, rosbag::bagmode::Read);
  return topicsOf (bag, path);
}

LaserLog
readRosbagLog (const std::string& path, const RosbagReadOptions& options)
{
  checkOptions (path, options);
  std::vector<std::string> pose_topics = options.object_topics;
  if (!options.pose_topic.empty ())
    pose_topics.insert (pose_topics.begin (), options.pose_topic);
  std::vector<std::string> wanted = pose_topics;
  wanted.push_back (options.scan_topic);
  rosbag::Bag bag;
  openBag (bag, path, rosbag::bagmode::Read, wanted);
  const auto topics = topicsOf (bag, path);
  requireTopic (path, topics, options.scan_topic, "sensor_msgs/LaserScan");
  for (const auto& topic : pose_topics)
    requireTopic (path, topics, topic, "geometry_msgs/PoseStamped");

  LaserLog log;
  log.path = path;
  std::map<std::string, StampedPoses> samples;
  try {
    rosbag::View view (bag, rosbag::TopicQuery (wanted));
    for (const rosbag::MessageInstance& message : view) {
      if (message.getTopic () == options.scan_topic) {
        if (options.max_scans > 0 && log.scans.size () >= options.max_scans)
          continue;
        if (message.getMD5Sum () != ros::message_traits::md5sum<sensor_msgs::LaserScan> ())
          continue;  // not a LaserScan of this definition (what instantiate () would give null for)
        const sensor_msgs::LaserScan scan = readLaserScan (path, message);  // its bytes read once
        if (scan.ranges.empty ())
          continue;
        const std::string problem = laserScanProblem (scan);
        if (!problem.empty ())
          throw messageError (path, message, problem);
        log.scans.push_back (toRecord (scan));
        continue;
      }
      const auto pose = message.instantiate<geometry_msgs::PoseStamped> ();
      if (!pose)
        continue;
      const std::string problem = poseProblem (pose->pose);
      if (!problem.empty ())
        throw messageError (path, message, problem);
      const double stamp = pose->header.stamp.isZero () ? message.getTime ().toSec () : pose->header.stamp.toSec ();
      samples[message.getTopic ()].emplace_back (
          stamp, makeRigid2d (pose->pose.position.x, pose->pose.position.y, yawOf (pose->pose.orientation)));
    }
  }
  catch (const ros::Exception& error) {  // BagException, and the serializer's StreamOverrunException
    throw LogError (path + ": cannot read the ROS bag (" + error.what () + ")");
  }
  if (log.scans.empty ())
    throw LogError (path + ": topic " + options.scan_topic + " holds no laser scan");
  std::stable_sort (log.scans.begin (), log.scans.end (),
                    [] (const LaserScanRecord& a, const LaserScanRecord& b) { return a.stamp < b.stamp; });
  const std::string repeated = dropScansStampedAlike (path, options.scan_topic, log.scans);
  if (!repeated.empty ())
    log.warnings.push_back (repeated);

  if (!options.pose_topic.empty ()) {
    const PoseTrack ego = poseTrack (samples[options.pose_topic], options.pose_topic, options.pose_delay, log);
    for (auto& scan : log.scans) {
      Rigid2d pose;
      scan.has_pose = ego.interpolate (scan.stamp, pose, options.max_pose_gap);
      scan.pose = scan.has_pose ? Rigid2d (pose * options.T_pose_laser) : Rigid2d::Identity ();
      log.has_reference_poses = log.has_reference_poses || scan.has_pose;
    }
    if (!log.has_reference_poses && !ego.empty ())  // else "no reference poses", though the topic holds them
      throw LogError (path + ": no scan of " + options.scan_topic + " (stamps " + stampText (log.scans.front ().stamp) +
                      " to " + stampText (log.scans.back ().stamp) + " s) lies within the " +
                      std::to_string (ego.stamps.size ()) + " poses of " + options.pose_topic + " (" +
                      stampText (ego.stamps.front ()) + " to " + stampText (ego.stamps.back ()) +
                      " s, at most " + shortNumber (options.max_pose_gap) +
                      " s apart): are the scans' or the poses' stamps zero, repeated or out of order?");
  }
  for (const auto& topic : options.object_topics) {
    TrackedObject object;
    object.name = topic;
    object.kind = options.object_kind;
    object.half_extent = options.object_half_extent;
    object.track = poseTrack (samples[topic], topic, options.pose_delay, log);
    log.objects.push_back (std::move (object));
  }
  return log;
}

namespace {

geometry_msgs::PoseStamped
toPoseMessage (double stamp, const Rigid2d& pose, std::uint32_t seq)
{
  geometry_msgs::PoseStamped message;
  message.header.seq = seq;
  message.header.stamp.fromSec (stamp);
  message.header.frame_id = "map";
  message.pose.position.x = pose.translation ().x ();
  message.pose.position.y = pose.translation ().y ();
  const double theta = rotationAngle (pose);
  message.pose.orientation.z = std::sin (theta / 2.0);
  message.pose.orientation.w = std::cos (theta / 2.0);
  return message;
}

sensor_msgs::LaserScan
toScanMessage (const LaserScanRecord& record, std::uint32_t seq)
{
  sensor_msgs::LaserScan message;
  message.header.seq = seq;
  message.header.stamp.fromSec (record.stamp);
  message.header.frame_id = "laser";
  message.angle_min = static_cast<float> (record.sensor.angle_min);
  message.angle_max = static_cast<float> (record.sensor.angleMax ());
  message.angle_increment = static_cast<float> (record.sensor.angle_increment);
  message.range_min = 0.0f;
  message.range_max = static_cast<float> (record.sensor.range_max);
  message.ranges.assign (record.sensor.beam_count, std::numeric_limits<float>::infinity ());
  for (std::size_t i = 0; i < record.beams.size (); ++i)
    message.ranges.at (record.beams[i]) = static_cast<float> (record.points.col (i).norm ());
  return message;
}

}  // namespace

void
writeRosbagLog (const std::string& path, const LaserLog& log, const RosbagReadOptions& options)
{
  checkOptions (path, options);
  if (options.object_topics.size () < log.objects.size ())
    throw LogError (path + ": give one object topic per tracked object (" + std::to_string (log.objects.size ()) +
                    ")");
  rosbag::Bag bag;
  openBag (bag, path, rosbag::bagmode::Write);
  try {
    std::uint32_t seq = 0;
    for (const auto& record : log.scans) {
      if (record.beams.size () != static_cast<std::size_t> (record.points.cols ()))
        throw LogError (path + ": a scan's beam indices do not match its points");
      bag.write (options.scan_topic, ros::Time (record.stamp), toScanMessage (record, seq++));
      if (!options.pose_topic.empty () && record.has_pose) {
        const double stamp = record.stamp + options.pose_delay;
        bag.write (options.pose_topic, ros::Time (stamp),
                   toPoseMessage (stamp, record.pose * options.T_pose_laser.inverse (), seq));
      }
    }
    for (std::size_t k = 0; k < log.objects.size (); ++k) {
      const PoseTrack& track = log.objects[k].track;
      for (std::size_t i = 0; i < track.stamps.size (); ++i) {
        const double stamp = track.stamps[i] + options.pose_delay;
        bag.write (options.object_topics[k], ros::Time (stamp),
                   toPoseMessage (stamp, track.poses[i], static_cast<std::uint32_t> (i)));
      }
    }
    bag.close ();
  }
  catch (const rosbag::BagException& error) {
    throw LogError (path + ": cannot write the ROS bag (" + error.what () + ")");
  }
}

#else  // built without ROS bag support

namespace {

[[noreturn]] void
unsupported (const std::string& path)
{
  throw LogError (path + ": pcl_crf was built without ROS bag support (install Debian's librosbag-dev, "
                         "libsensor-msgs-dev and libgeometry-msgs-dev, then re-run CMake with "
                         "-DPCL_CRF_WITH_ROSBAG=AUTO or ON)");
}

}  // namespace

bool
rosbagSupported ()
{
  return false;
}

std::vector<std::pair<std::string, std::string>>
listRosbagTopics (const std::string& path)
{
  unsupported (path);
}

LaserLog
readRosbagLog (const std::string& path, const RosbagReadOptions&)
{
  unsupported (path);
}

void
writeRosbagLog (const std::string& path, const LaserLog&, const RosbagReadOptions&)
{
  unsupported (path);
}

#endif

}  // namespace pcl_crf
