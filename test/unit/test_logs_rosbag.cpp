#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/logs/rosbag_log.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

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
