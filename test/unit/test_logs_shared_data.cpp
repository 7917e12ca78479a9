// Reads the real logs of ../shared/data when present (skips otherwise).

#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/metrics/motion_error.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <utility>

namespace fs = std::filesystem;

namespace {

std::string
sharedFile (const std::string& relative)
{
  return (fs::path (PCL_CRF_SHARED_DATA_DIR) / relative).string ();
}

#define PCL_CRF_SKIP_WITHOUT_FILE(path)                                                  \
  if (!fs::is_regular_file (path))                                                       \
  GTEST_SKIP () << path << " is absent (the shared real-data folder is optional)"

double
median (std::vector<double> v)
{
  std::nth_element (v.begin (), v.begin () + v.size () / 2, v.end ());
  return v[v.size () / 2];
}

TEST (LogSharedData, IntelCorrectedLogHasPosesAndOdometry)
{
  const std::string path = sharedFile ("carmen/intel-corrected.log.gz");
  PCL_CRF_SKIP_WITHOUT_FILE (path);
  const pcl_crf::LaserLog log = pcl_crf::readLaserLog (path);
  ASSERT_EQ (log.scans.size (), 910u);
  EXPECT_TRUE (log.has_reference_poses);
  EXPECT_TRUE (log.has_odometry);
  EXPECT_EQ (log.scans.front ().sensor.beam_count, 180);
  std::vector<double> odometry_error;
  for (std::size_t k = 0; k + 1 < log.scans.size (); ++k) {
    EXPECT_LE (log.scans[k].points.cols (), 180);
    EXPECT_GT (log.scans[k].points.cols (), 100);
    const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, k);
    pcl_crf::Rigid2d reference;
    ASSERT_TRUE (pcl_crf::referenceEgoMotion (pair, reference));
    odometry_error.push_back (pcl_crf::computeMotionError (pair.odometry.T_source_target, reference).translation);
  }
  // the ODOM stream gives a real odometry: a few cm off per ~0.7 m step (not 0, not the pose)
  EXPECT_GT (median (odometry_error), 0.01);
  EXPECT_LT (median (odometry_error), 0.1);
}

TEST (LogSharedData, EveryShippedCarmenLogReadsAsCorrected)
{
  // Their FLASER poses equal their odometry fields, as a raw log's do; the ODOM stream
  // re-anchored at every scan is what makes them corrected logs.
  const std::pair<const char*, std::size_t> logs[] = {
      {"acapulco", 861}, {"belgioioso", 395},       {"csail", 406},
      {"fhw", 488},      {"freiburg-079", 4791},    {"freiburg-101", 292},
      {"freiburg-campus", 2008}, {"infinite-corridor", 1941}, {"intel", 910}};
  for (const auto& [name, scans] : logs) {
    const std::string path = sharedFile (std::string ("carmen/") + name + "-corrected.log.gz");
    PCL_CRF_SKIP_WITHOUT_FILE (path);
    const pcl_crf::LaserLog log = pcl_crf::readLaserLog (path);
    EXPECT_EQ (log.scans.size (), scans) << name;
    EXPECT_TRUE (log.has_reference_poses) << name;
    EXPECT_TRUE (std::all_of (log.scans.begin (), log.scans.end (), [] (const auto& s) { return s.has_pose; }))
        << name;
  }
}

TEST (LogSharedData, DatmoBagHasScansAndMocapPoses)
{
  const std::string path = sharedFile ("rosbag/intersection.bag");
  PCL_CRF_SKIP_WITHOUT_FILE (path);
  if (!pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  pcl_crf::LaserLogReadOptions options;
  options.rosbag.pose_topic = "/ego_pose";
  options.rosbag.object_topics = {"/red_pose"};
  options.rosbag.T_pose_laser = pcl_crf::makeRigid2d (-0.166, 0.019, 0.0);
  options.rosbag.pose_delay = 0.025;
  const pcl_crf::LaserLog log = pcl_crf::readLaserLog (path, options);
  ASSERT_EQ (log.scans.size (), 85u);
  EXPECT_EQ (log.scans.front ().sensor.beam_count, 360);
  EXPECT_NEAR (log.scans.front ().sensor.angle_increment, M_PI / 180, 1e-6);
  EXPECT_TRUE (log.has_reference_poses);
  ASSERT_EQ (log.objects.size (), 1u);
  EXPECT_GT (log.objects[0].track.stamps.size (), 500u);
  std::size_t with_pose = 0;
  for (const auto& scan : log.scans)
    with_pose += scan.has_pose ? 1 : 0;
  EXPECT_GT (with_pose, 80u);
  pcl_crf::LogPairOptions pairs;
  pairs.label_points = true;
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 40, pairs);
  EXPECT_TRUE (pair.hasTruth ());
}

}  // namespace
