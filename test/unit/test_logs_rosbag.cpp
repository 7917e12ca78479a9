#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/logs/rosbag_log.h>
#include <pcl_crf/logs/rosbag_structure.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using pcl_crf::makeRigid2d;
using pcl_crf::Rigid2d;

namespace {

#define PCL_CRF_SKIP_WITHOUT_ROSBAG()                                                    \
  if (!pcl_crf::rosbagSupported ())                                                      \
  GTEST_SKIP () << "built without ROS bag support (PCL_CRF_WITH_ROSBAG, librosbag-dev)"

class LogRosbag : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    dir_ = fs::temp_directory_path () / ("pcl_crf_logs_rosbag_" + std::to_string (::getpid ()));
    fs::create_directories (dir_);
  }
  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }

  /** Four scans of 8 beams (beam 2 without return) from a sensor driving +x,
   *  with an object track. */
  static pcl_crf::LaserLog
  smallLog ()
  {
    pcl_crf::LaserLog log;
    for (int k = 0; k < 4; ++k) {
      pcl_crf::LaserScanRecord scan;
      scan.stamp = 1000.0 + 0.1 * k;
      scan.sensor = {8, -M_PI / 2, M_PI / 7, 10.0};
      for (int b = 0; b < 8; ++b) {
        if (b == 2)
          continue;
        const double angle = scan.sensor.angle_min + b * scan.sensor.angle_increment, r = 1.0 + 0.25 * b + 0.01 * k;
        scan.points.conservativeResize (2, scan.points.cols () + 1);
        scan.points.col (scan.points.cols () - 1) << r * std::cos (angle), r * std::sin (angle);
        scan.beams.push_back (b);
      }
      scan.has_pose = true;
      scan.pose = makeRigid2d (0.2 * k, 0.0, 0.05 * k);
      log.scans.push_back (scan);
    }
    pcl_crf::TrackedObject car;
    for (int k = 0; k < 40; ++k)
      car.track.append (999.9 + 0.01 * k, makeRigid2d (3.0 + 0.01 * k, 1.0, 0.5));
    log.objects.push_back (car);
    return log;
  }

  fs::path dir_;
};

TEST_F (LogRosbag, WrittenBagReadsBack)
{
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  pcl_crf::RosbagReadOptions options;
  options.pose_topic = "/ego_pose";
  options.object_topics = {"/car_pose"};
  options.T_pose_laser = makeRigid2d (-0.1, 0.02, 0.0);
  options.pose_delay = 0.025;
  const std::string path = (dir_ / "small.bag").string ();
  const pcl_crf::LaserLog written = smallLog ();
  pcl_crf::writeRosbagLog (path, written, options);

  const auto topics = pcl_crf::listRosbagTopics (path);
  ASSERT_EQ (topics.size (), 3u);
  EXPECT_EQ (topics[0], std::make_pair (std::string ("/car_pose"), std::string ("geometry_msgs/PoseStamped")));
  EXPECT_EQ (topics[2], std::make_pair (std::string ("/scan"), std::string ("sensor_msgs/LaserScan")));
  EXPECT_EQ (pcl_crf::detectLaserLogFormat (path), pcl_crf::LaserLogFormat::Rosbag);

  pcl_crf::LaserLogReadOptions read;
  read.rosbag = options;
  const pcl_crf::LaserLog log = pcl_crf::readLaserLog (path, read);
  ASSERT_EQ (log.scans.size (), 4u);
  EXPECT_TRUE (log.has_reference_poses);
  EXPECT_FALSE (log.has_odometry);
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& scan = log.scans[k];
    EXPECT_NEAR (scan.stamp, written.scans[k].stamp, 1e-6);
    EXPECT_EQ (scan.sensor.beam_count, 8);
    EXPECT_NEAR (scan.sensor.angle_increment, M_PI / 7, 1e-6);
    EXPECT_EQ (scan.beams, written.scans[k].beams);
    EXPECT_TRUE (scan.points.isApprox (written.scans[k].points, 1e-5));
    ASSERT_TRUE (scan.has_pose);
    EXPECT_TRUE (scan.pose.isApprox (written.scans[k].pose, 1e-6)) << "scan " << k;
  }
  ASSERT_EQ (log.objects.size (), 1u);
  EXPECT_EQ (log.objects[0].name, "/car_pose");
  EXPECT_EQ (log.objects[0].track.stamps.size (), 40u);
  EXPECT_NEAR (log.objects[0].track.stamps.front (), 999.9, 1e-6);
  // pairs: the reference ego motion and the object motion (+0.1 m in x over 0.1 s)
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 1);
  Rigid2d ego;
  ASSERT_TRUE (pcl_crf::referenceEgoMotion (pair, ego));
  EXPECT_TRUE (ego.isApprox (written.scans[1].pose.inverse () * written.scans[2].pose, 1e-5));
  ASSERT_EQ (pair.objects.size (), 2u);
}

TEST_F (LogRosbag, WithoutPoseTopicScansHaveNoReference)
{
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  const std::string path = (dir_ / "scans_only.bag").string ();
  pcl_crf::LaserLog written = smallLog ();
  written.objects.clear ();
  pcl_crf::writeRosbagLog (path, written);
  const pcl_crf::LaserLog log = pcl_crf::readRosbagLog (path);
  for (const auto& scan : log.scans) {
    EXPECT_TRUE (std::is_sorted (scan.beams.begin (), scan.beams.end ()));
    EXPECT_GT (scan.sensor.angle_increment, 0.0);
    EXPECT_FALSE (scan.has_pose);
  }
  EXPECT_FALSE (log.has_reference_poses);
}

TEST_F (LogRosbag, ErrorsNameTheBagAndTopic)
{
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  const std::string path = (dir_ / "small.bag").string ();
  pcl_crf::LaserLog written = smallLog ();
  EXPECT_THROW (pcl_crf::writeRosbagLog (path, written), pcl_crf::LogError);  // the object needs a topic
  written.objects.clear ();
  pcl_crf::writeRosbagLog (path, written);
  pcl_crf::RosbagReadOptions options;
  options.scan_topic = "/laser";
  try {
    pcl_crf::readRosbagLog (path, options);
    FAIL () << "no exception";
  }
  catch (const pcl_crf::LogError& error) {
    EXPECT_NE (std::string (error.what ()).find ("no topic /laser in the bag; it has: /scan (sensor_msgs/LaserScan)"),
               std::string::npos)
        << error.what ();
  }
  options.scan_topic = "/scan";
  options.pose_topic = "/scan";
  try {
    pcl_crf::readRosbagLog (path, options);
    FAIL () << "no exception";
  }
  catch (const pcl_crf::LogError& error) {
    EXPECT_NE (std::string (error.what ()).find ("holds sensor_msgs/LaserScan, not geometry_msgs/PoseStamped"),
               std::string::npos)
        << error.what ();
  }
  EXPECT_THROW (pcl_crf::readRosbagLog ((dir_ / "missing.bag").string ()), pcl_crf::LogError);
  const std::string garbage = (dir_ / "garbage.bag").string ();
  std::ofstream (garbage) << "#ROSBAG V2.0\nthis is not a bag";
  EXPECT_THROW (pcl_crf::readRosbagLog (garbage), pcl_crf::LogError);
}

TEST_F (LogRosbag, ScansAndPosesThatAreNotFiniteAreErrors)
{
  // A NaN pose gave a NaN ego error (exit 0) or an object that never moved, and a zero
  // angle step put every beam on one ray, all without a word.
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  pcl_crf::RosbagReadOptions options;
  options.pose_topic = "/ego_pose";
  const std::string path = (dir_ / "bad.bag").string ();
  const auto expectReadError = [&] (const pcl_crf::LaserLog& log, const std::string& fragment) {
    pcl_crf::writeRosbagLog (path, log, options);
    try {
      pcl_crf::readRosbagLog (path, options);
      ADD_FAILURE () << "no exception; expected " << fragment;
    }
    catch (const pcl_crf::LogError& error) {
      EXPECT_NE (std::string (error.what ()).find (fragment), std::string::npos) << error.what ();
    }
  };
  pcl_crf::LaserLog log = smallLog ();
  log.objects.clear ();
  pcl_crf::writeRosbagLog (path, log, options);
  EXPECT_NO_THROW (pcl_crf::readRosbagLog (path, options));
  pcl_crf::LaserLog bad = log;
  bad.scans[1].sensor.angle_increment = 0.0;
  expectReadError (bad, "bad.bag: topic /scan, message at 1000.1");
  expectReadError (bad, "angle_increment must be a finite angle other than 0");
  bad = log;
  bad.scans[2].sensor.range_max = std::nan ("");
  expectReadError (bad, "range_min and range_max must be finite and range_max positive");
  bad = log;
  bad.scans[0].sensor.angle_min = std::nan ("");
  expectReadError (bad, "angle_min is not a finite angle");
  bad = log;
  bad.scans[3].pose = makeRigid2d (std::nan (""), 0.0, 0.0);
  expectReadError (bad, "topic /ego_pose, message at 1000.3");
  expectReadError (bad, "the position is not finite");
  // Finite nonsense: points beyond 1e18 m, every beam on one ray, a start turns away.
  bad = log;
  bad.scans[2].sensor.range_max = 3e38;
  expectReadError (bad, "range_max lies beyond 1e18 m");
  bad = log;
  bad.scans[1].sensor.angle_increment = 1e-30;
  expectReadError (bad, "angle_increment 1e-30 rad is finer than 2π / 100000");
  bad = log;
  bad.scans[1].sensor.angle_min = 1e30;
  expectReadError (bad, "from angle_min 1e+30 rad: more than one turn, or a start beyond two turns");
  bad = log;
  bad.scans[3].pose = makeRigid2d (1e300, 0.0, 0.0);
  expectReadError (bad, "the position lies beyond 1e18 m");
}

TEST_F (LogRosbag, PosesThatCoverNoScanAreAnError)
{
  // Scan stamps of zero, or poses 100 s off, gave "the log has no reference poses" with
  // exit 0 though the pose topic held hundreds.
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  pcl_crf::RosbagReadOptions options;
  options.pose_topic = "/ego_pose";
  const std::string path = (dir_ / "late.bag").string ();
  pcl_crf::LaserLog log = smallLog ();
  log.objects.clear ();
  pcl_crf::writeRosbagLog (path, log, options);
  options.pose_delay = 100.0;
  try {
    pcl_crf::readRosbagLog (path, options);
    FAIL () << "no exception";
  }
  catch (const pcl_crf::LogError& error) {
    EXPECT_NE (std::string (error.what ()).find ("no scan of /scan (stamps 1000.000 to 1000.300 s) lies within the 4 "
                                                 "poses of /ego_pose"),
               std::string::npos)
        << error.what ();
  }
}

TEST_F (LogRosbag, ScansStampedLikeTheScanBeforeAreLeftOutWithAWarning)
{
  // Scan 2 carries scan 1's stamp (a copied stamp): the pair (1, 2) had no time step, and
  // the one pose at that stamp made its reference ego motion the identity.
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  pcl_crf::RosbagReadOptions options;
  options.pose_topic = "/ego_pose";
  const std::string path = (dir_ / "copied.bag").string ();
  pcl_crf::LaserLog written = smallLog ();
  written.objects.clear ();
  written.scans[2].stamp = written.scans[1].stamp;
  written.scans[2].has_pose = false;  // the pose topic holds one pose at the stamp
  pcl_crf::writeRosbagLog (path, written, options);
  const pcl_crf::LaserLog log = pcl_crf::readRosbagLog (path, options);
  ASSERT_EQ (log.scans.size (), 3u);
  EXPECT_TRUE (log.scans[1].points.isApprox (written.scans[1].points, 1e-5));  // the first in the bag stays
  EXPECT_NEAR (log.scans[2].stamp, written.scans[3].stamp, 1e-6);
  EXPECT_EQ (pcl_crf::countStampsNotAfterTheLast (log), 0u);
  ASSERT_EQ (log.warnings.size (), 1u);
  EXPECT_NE (log.warnings[0].find ("copied.bag: 1 scan of /scan stamped like the scan before it was left out (the "
                                   "first at 1000.100 s)"),
             std::string::npos)
      << log.warnings[0];
  EXPECT_EQ (pcl_crf::readRosbagLog (path).scans.size (), 3u);  // without the pose topic too
  written = smallLog ();
  written.objects.clear ();
  pcl_crf::writeRosbagLog (path, written, options);
  EXPECT_TRUE (pcl_crf::readRosbagLog (path, options).warnings.empty ());
}

TEST_F (LogRosbag, PoseStampsCarryingDifferentPosesAreLeftOutOfTheirTrack)
{
  // Two poses of the car stamped 1000.05 s, the first 1 m off: the track took the first.
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  pcl_crf::LaserLog written = smallLog ();
  pcl_crf::PoseTrack& track = written.objects[0].track;
  ASSERT_NEAR (track.stamps[15], 1000.05, 1e-9);
  track.stamps.insert (track.stamps.begin () + 15, track.stamps[15]);
  track.poses.insert (track.poses.begin () + 15, track.poses[15] * makeRigid2d (1.0, 0.0, 0.0));
  // ... and the sample at 1000.1 s twice, alike: one sample, no warning.
  track.stamps.insert (track.stamps.begin () + 21, track.stamps[21]);
  track.poses.insert (track.poses.begin () + 21, track.poses[21]);
  pcl_crf::RosbagReadOptions options;
  options.pose_topic = "/ego_pose";
  options.object_topics = {"/car_pose"};
  const std::string path = (dir_ / "car.bag").string ();
  pcl_crf::writeRosbagLog (path, written, options);
  const pcl_crf::LaserLog log = pcl_crf::readRosbagLog (path, options);
  ASSERT_EQ (log.objects.size (), 1u);
  EXPECT_EQ (log.objects[0].track.stamps.size (), 39u);
  Rigid2d car;
  ASSERT_TRUE (log.objects[0].track.interpolate (1000.05, car));
  EXPECT_TRUE (car.isApprox (makeRigid2d (3.15, 1.0, 0.5), 1e-6)) << pcl_crf::toXYTheta (car).transpose ();
  ASSERT_EQ (log.warnings.size (), 1u);
  EXPECT_NE (log.warnings[0].find ("car.bag: 1 stamp of /car_pose carrying different poses was left out (the first at "
                                   "1000.050 s): which pose is right is unknown"),
             std::string::npos)
      << log.warnings[0];
}

TEST_F (LogRosbag, AScanWhoseRangesCountExceedsItsBytesIsAnError)
{
  // ROS's deserializer sized the ranges from a corrupt count of 2^31 - 1 first: 8 GB and
  // 40 s before "Buffer Overrun".
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  const std::string path = (dir_ / "count.bag").string ();
  pcl_crf::LaserLog log = smallLog ();
  log.objects.clear ();
  pcl_crf::writeRosbagLog (path, log);
  std::string bytes;
  {
    std::ifstream in (path, std::ios::binary);
    bytes.assign (std::istreambuf_iterator<char> (in), std::istreambuf_iterator<char> ());
  }
  const float range_max = 10.0f;
  const std::uint32_t beams = 8, corrupt = 0x7fffffff;
  std::string pattern (reinterpret_cast<const char*> (&range_max), 4);  // range_max, then the ranges' count
  pattern.append (reinterpret_cast<const char*> (&beams), 4);
  const std::size_t at = bytes.find (pattern);
  ASSERT_NE (at, std::string::npos);
  bytes.replace (at + 4, 4, std::string (reinterpret_cast<const char*> (&corrupt), 4));
  std::ofstream (path, std::ios::binary | std::ios::trunc) << bytes;
  try {
    pcl_crf::readRosbagLog (path);
    FAIL () << "no exception";
  }
  catch (const pcl_crf::LogError& error) {
    EXPECT_NE (std::string (error.what ()).find ("ranges or intensities declare more values than the message holds"),
               std::string::npos)
        << error.what ();
  }
}

/** Little-endian bytes of an integer, as the bag format writes them. */
template <typename T>
std::string
littleEndian (T value)
{
  std::string bytes (sizeof (T), '\0');
  for (std::size_t i = 0; i < sizeof (T); ++i)
    bytes[i] = static_cast<char> ((static_cast<std::uint64_t> (value) >> (8 * i)) & 0xff);
  return bytes;
}

/** A record: header length, header fields (length, name=value; op first), data length,
 *  data. */
std::string
bagRecord (std::uint8_t op, std::vector<std::pair<std::string, std::string>> fields, const std::string& data)
{
  fields.insert (fields.begin (), {"op", std::string (1, static_cast<char> (op))});
  std::string header;
  for (const auto& [name, value] : fields)
    header += littleEndian<std::uint32_t> (name.size () + 1 + value.size ()) + name + "=" + value;
  return littleEndian<std::uint32_t> (header.size ()) + header + littleEndian<std::uint32_t> (data.size ()) + data;
}

/** A ROS bag v2.0 written byte by byte: one chunk holding a connection record and two
 *  messages of it, the chunk's index, the connection, the chunk info; and where each is. */
struct SyntheticBag
{
  std::string bytes;
  std::size_t chunk_at = 0, index_at = 0, index_pos = 0, chunk_info_at = 0;
  std::size_t first_entry_offset_at = 0;  // file offset of the first index entry's offset field
  std::size_t first_message_at = 0;       // file offset of the first message data record

  explicit SyntheticBag (const std::string& compression = "none")
  {
    const std::string connection_fields = bagRecord (7, {{"conn", littleEndian<std::uint32_t> (0)},
                                                         {"topic", "/scan"}}, "type=x");
    std::string chunk = connection_fields;
    std::vector<std::uint32_t> offsets;
    for (const std::string payload : {"first", "second"}) {
      offsets.push_back (static_cast<std::uint32_t> (chunk.size ()));
      chunk += bagRecord (2, {{"conn", littleEndian<std::uint32_t> (0)},
                              {"time", littleEndian<std::uint64_t> (offsets.size ())}}, payload);
    }
    bytes = "#ROSBAG V2.0\n";
    bytes += bagRecord (3, {{"index_pos", littleEndian<std::uint64_t> (0)},
                            {"conn_count", littleEndian<std::uint32_t> (1)},
                            {"chunk_count", littleEndian<std::uint32_t> (1)}}, std::string (16, ' '));
    chunk_at = bytes.size ();
    bytes += bagRecord (5, {{"compression", compression},
                            {"size", littleEndian<std::uint32_t> (chunk.size ())}}, chunk);
    first_message_at = bytes.size () - chunk.size () + offsets.front ();
    index_at = bytes.size ();
    std::string entries;
    for (const std::uint32_t offset : offsets)
      entries += littleEndian<std::uint64_t> (offset) + littleEndian (offset);
    bytes += bagRecord (4, {{"ver", littleEndian<std::uint32_t> (1)},
                            {"conn", littleEndian<std::uint32_t> (0)}, {"count", littleEndian<std::uint32_t> (2)}},
                        entries);
    first_entry_offset_at = bytes.size () - entries.size () + 8;
    index_pos = bytes.size ();
    bytes += connection_fields;
    chunk_info_at = bytes.size ();
    bytes += bagRecord (6, {{"ver", littleEndian<std::uint32_t> (1)},
                            {"chunk_pos", littleEndian<std::uint64_t> (chunk_at)},
                            {"start_time", littleEndian<std::uint64_t> (1)}, {"end_time", littleEndian<std::uint64_t> (2)},
                            {"count", littleEndian<std::uint32_t> (1)}},
                        littleEndian<std::uint32_t> (0) + littleEndian<std::uint32_t> (2));
    set ("index_pos=", littleEndian<std::uint64_t> (index_pos));
  }

  /** Overwrites the value after the first \a name (e.g. "index_pos=") with \a value. */
  void
  set (const std::string& name, const std::string& value, std::size_t from = 0)
  {
    bytes.replace (bytes.find (name, from) + name.size (), value.size (), value);
  }
};

class LogRosbagStructure : public LogRosbag
{
protected:
  /** Writes \a bytes as a bag; expects checkRosbagStructure, reading /scan, to throw
   *  naming \a fragment. */
  void
  expectError (const std::string& bytes, const std::string& fragment)
  {
    const std::string path = write (bytes);
    try {
      pcl_crf::checkRosbagStructure (path, {"/scan"});
      ADD_FAILURE () << "no exception; expected " << fragment;
    }
    catch (const pcl_crf::LogError& error) {
      EXPECT_NE (std::string (error.what ()).find ("corrupt.bag: not a readable ROS bag (truncated or corrupted?): "),
                 std::string::npos)
          << error.what ();
      EXPECT_NE (std::string (error.what ()).find (fragment), std::string::npos) << error.what ();
    }
  }

  std::string
  write (const std::string& bytes)
  {
    const std::string path = (dir_ / "corrupt.bag").string ();
    std::ofstream (path, std::ios::binary | std::ios::trunc) << bytes;
    return path;
  }
};

TEST_F (LogRosbagStructure, AWellFormedBagPasses)
{
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (write (SyntheticBag ().bytes), {"/scan"}));
  // compressed chunks: their offsets are checked against their size alone
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (write (SyntheticBag ("bz2").bytes), {"/scan"}));
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (write ("#ROSBAG V1.2\nanother version")));  // left to librosbag
  EXPECT_THROW (pcl_crf::checkRosbagStructure ((dir_ / "missing.bag").string ()), pcl_crf::LogError);
  if (!pcl_crf::rosbagSupported ())
    return;
  const std::string path = (dir_ / "written.bag").string ();
  pcl_crf::RosbagReadOptions topics;
  topics.pose_topic = "/ego_pose";
  topics.object_topics = {"/car_pose"};
  pcl_crf::writeRosbagLog (path, smallLog (), topics);
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (path, {"/scan", "/ego_pose", "/car_pose"}));
}

TEST_F (LogRosbagStructure, OnlyTheMessagesOfTheTopicsReadAreChecked)
{
  // librosbag follows no index entry of a topic it does not read: a damaged one there
  // does no harm (listRosbagTopics reads none).
  std::string bytes = SyntheticBag ().bytes;
  const std::size_t entry = SyntheticBag ().first_entry_offset_at;
  bytes[entry + 1] = static_cast<char> (bytes[entry + 1] ^ 0xff);
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (write (bytes)));
  EXPECT_NO_THROW (pcl_crf::checkRosbagStructure (write (bytes), {"/ego_pose"}));
  expectError (bytes, "an index entry's offset");
}

TEST_F (LogRosbagStructure, ATruncatedBagNamesWhereItEnds)
{
  const SyntheticBag bag;
  expectError (bag.bytes.substr (0, 20), "at byte 13, the record runs past the end of the file (20 bytes)");
  expectError (bag.bytes.substr (0, bag.index_pos + 10),
               "at byte 13, 1 connection and 1 chunk-info records cannot fit in the 10 bytes after index_pos");
  expectError (bag.bytes.substr (0, bag.index_pos), "at byte 13, index_pos " + std::to_string (bag.index_pos) +
                                                        " lies outside the records");
  expectError (bag.bytes.substr (0, bag.bytes.size () - 3),
               "at byte " + std::to_string (bag.chunk_info_at) + ", the chunk info record's data (8 bytes) runs past "
               "the end of the file");
}

TEST_F (LogRosbagStructure, FlippedLengthsAndOffsetsAreNamed)
{
  const SyntheticBag bag;
  const auto flipped = [&] (std::size_t at, unsigned char mask = 0xff) {
    std::string bytes = bag.bytes;
    bytes[at] = static_cast<char> (bytes[at] ^ mask);
    return bytes;
  };
  const std::string chunk = std::to_string (bag.chunk_at), index = std::to_string (bag.index_at);
  // header lengths: 4 bytes more swallow the data length, 0xff00 more run past the file
  expectError (flipped (bag.chunk_at, 0x04), "at byte " + chunk + ", the chunk record's header holds a field whose "
                                             "length runs past it, or without '='");
  expectError (flipped (bag.chunk_at + 1), "at byte " + chunk + ", the record runs past the end of the file (" +
                                               std::to_string (bag.bytes.size ()) + " bytes)");
  expectError (flipped (bag.index_at + 3), "at byte " + index + ", the record runs past the end of the file");
  // a header field's length, a data length
  expectError (flipped (bag.index_at + 4), "at byte " + index + ", the index data record's header holds a field");
  expectError (flipped (bag.first_entry_offset_at - 8 - 2), "at byte " + index + ", the index data record's data (");
  // index entries: beyond the chunk, and one byte into a message record (whose header
  // length is then read from the middle of its bytes)
  expectError (flipped (bag.first_entry_offset_at + 1), "at byte " + std::to_string (bag.first_entry_offset_at - 8) +
                                                            ", an index entry's offset");
  expectError (flipped (bag.first_entry_offset_at, 0x01),
               "at byte " + std::to_string (bag.first_message_at + 1) + ", the record runs past the end of the chunk");
  // a compressed chunk: its offsets are checked against its size only
  const SyntheticBag packed ("bz2");
  std::string bytes = packed.bytes;
  bytes[packed.first_entry_offset_at + 1] = '\x7f';
  expectError (bytes, "lies beyond its chunk's");
  // the bag header's and the chunk info's numbers
  SyntheticBag wrong;
  wrong.set ("index_pos=", littleEndian<std::uint64_t> (wrong.bytes.size () + 5));
  expectError (wrong.bytes, "at byte 13, index_pos " + std::to_string (wrong.bytes.size () + 5) +
                                " lies outside the records");
  wrong = SyntheticBag ();
  wrong.set ("conn_count=", littleEndian<std::uint32_t> (1000000));
  expectError (wrong.bytes, "at byte 13, 1000000 connection and 1 chunk-info records cannot fit in the");
  wrong = SyntheticBag ();
  wrong.set ("index_pos=", littleEndian<std::uint64_t> (0));
  expectError (wrong.bytes, "at byte 13, the bag has no index (index_pos 0");
  wrong = SyntheticBag ();
  wrong.set ("chunk_pos=", littleEndian<std::uint64_t> (wrong.index_pos + 1));
  expectError (wrong.bytes, "at byte " + std::to_string (wrong.chunk_info_at) + ", chunk_pos " +
                                std::to_string (wrong.index_pos + 1) + " lies outside the chunks");
  wrong = SyntheticBag ();
  wrong.set ("chunk_pos=", littleEndian<std::uint64_t> (wrong.index_at));
  expectError (wrong.bytes, "at byte " + index + ", expected a chunk record, found another kind of record");
  wrong = SyntheticBag ();
  wrong.set ("count=", littleEndian<std::uint32_t> (3), wrong.chunk_info_at);
  expectError (wrong.bytes, "a chunk info of 3 connections holds 8 bytes, not 8 per connection");
  wrong = SyntheticBag ();
  wrong.set ("size=", littleEndian<std::uint32_t> (7));
  expectError (wrong.bytes, "at byte " + chunk + ", an uncompressed chunk of 7 bytes holds");
}

TEST_F (LogRosbagStructure, ReadingACorruptBagIsALogErrorNamingTheByte)
{
  // A flipped byte in an index entry of /scan made librosbag read out of its chunk and
  // crash pcl_crf_run (SIGSEGV); a truncated bag said "wanted 4 bytes, read 0 bytes".
  PCL_CRF_SKIP_WITHOUT_ROSBAG ();
  const std::string path = (dir_ / "cut.bag").string ();
  pcl_crf::LaserLog log = smallLog ();
  log.objects.clear ();
  pcl_crf::writeRosbagLog (path, log);
  fs::resize_file (path, fs::file_size (path) - 100);
  for (const auto& read : {std::function<void ()> ([&] { pcl_crf::readRosbagLog (path); }),
                           std::function<void ()> ([&] { pcl_crf::listRosbagTopics (path); })})
    try {
      read ();
      ADD_FAILURE () << "no exception";
    }
    catch (const pcl_crf::LogError& error) {
      EXPECT_NE (std::string (error.what ()).find ("cut.bag: not a readable ROS bag (truncated or corrupted?): at byte "),
                 std::string::npos)
          << error.what ();
    }
}

TEST_F (LogRosbag, WithoutSupportEveryCallSaysHowToEnableIt)
{
  if (pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built with ROS bag support";
  try {
    pcl_crf::readRosbagLog ((dir_ / "any.bag").string ());
    FAIL () << "no exception";
  }
  catch (const pcl_crf::LogError& error) {
    EXPECT_NE (std::string (error.what ()).find ("built without ROS bag support"), std::string::npos);
  }
  EXPECT_THROW (pcl_crf::listRosbagTopics ("x.bag"), pcl_crf::LogError);
  EXPECT_THROW (pcl_crf::writeRosbagLog ("x.bag", {}), pcl_crf::LogError);
}

}  // namespace
