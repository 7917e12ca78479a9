#include <pcl_crf/logs/carmen_log.h>
#include <pcl_crf/logs/read_laser_log.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using pcl_crf::makeRigid2d;
using pcl_crf::Rigid2d;

namespace {

/** Range from (x, y) along angle a to the walls of the room [-4, 8] x [-3, 5]. */
double
rayToRoom (double x, double y, double a)
{
  const double dx = std::cos (a), dy = std::sin (a);
  double t = 1e9;
  for (double wall_x : {-4.0, 8.0})
    if (std::abs (dx) > 1e-12 && (wall_x - x) / dx > 0)
      t = std::min (t, (wall_x - x) / dx);
  for (double wall_y : {-3.0, 5.0})
    if (std::abs (dy) > 1e-12 && (wall_y - y) / dy > 0)
      t = std::min (t, (wall_y - y) / dy);
  return t;
}

/** Corrected pose of scan j. */
Rigid2d
truePose (int j)
{
  return makeRigid2d (0.5 * j, 0.1 * j, 0.05 * j);
}

/** The error the log's raw odometry makes on step j-1 -> j. */
Rigid2d
odometryError (int j)
{
  return makeRigid2d (0.01 * j, -0.005, 0.002 * j);
}

std::string
flaser (int j, int beams, bool corrected)
{
  const Rigid2d T = truePose (j);
  const Eigen::Vector3d p = pcl_crf::toXYTheta (T);
  std::ostringstream line;
  line.precision (10);
  line << "FLASER " << beams;
  for (int i = 0; i < beams; ++i) {
    const double a = -M_PI / 2 + i * M_PI / (beams - 1);
    double r = rayToRoom (p.x (), p.y (), p.z () + a);
    if (i == 0)
      r = 81.9;  // no return
    if (i == 5)
      r = 0.0;  // below min range
    if (i == 7)
      r = 50.0;  // no return
    line << ' ' << r;
  }
  // raw logs: the odometry fields drift away from the pose
  const Eigen::Vector3d o = corrected ? p : Eigen::Vector3d (p + Eigen::Vector3d (0.3, -0.2, 0.1 * j));
  line << ' ' << p.x () << ' ' << p.y () << ' ' << p.z () << ' ' << o.x () << ' ' << o.y () << ' ' << o.z ()
       << ' ' << 100.0 + j << " testhost " << 100.0 + j;
  return line.str ();
}

std::string
odom (const Rigid2d& T, double stamp)
{
  const Eigen::Vector3d p = pcl_crf::toXYTheta (T);
  std::ostringstream line;
  line.precision (12);
  line << "ODOM " << p.x () << ' ' << p.y () << ' ' << p.z () << " 0 0 0 " << stamp << " testhost " << stamp;
  return line.str ();
}

/** A Radish-style corrected log: FLASER with the corrected pose as pose and
 *  odometry, and an ODOM stream re-anchored at every scan. */
std::string
correctedLog (int scans, int beams = 181)
{
  std::ostringstream log;
  log << "# CARMEN Logfile\nPARAM robot_frontlaser_offset 0.0 nohost 0\n";
  for (int j = 0; j < scans; ++j) {
    if (j > 0) {
      const Rigid2d before = truePose (j - 1) * (truePose (j - 1).inverse () * truePose (j)) * odometryError (j);
      log << odom (truePose (j - 1) * makeRigid2d (0.1, 0.0, 0.0), 99.5 + j) << "\n"  // an intermediate reading
          << odom (before, 99.9 + j) << "\n";
    }
    log << flaser (j, beams, true) << "\n" << odom (truePose (j), 0.0) << "\nNEFF 15\n";
  }
  return log.str ();
}

/** A raw log as the CARMEN logger writes it: every FLASER's pose and odometry fields
 *  are both the robot's odometry at the scan (truePose here), and the ODOM stream, when
 *  there is one, is that odometry sampled between the scans: by the first ODOM line
 *  after a scan the robot has moved on. */
std::string
rawLog (int scans, bool with_odom_stream)
{
  std::ostringstream log;
  for (int j = 0; j < scans; ++j) {
    log << flaser (j, 91, true) << "\n";
    if (with_odom_stream)
      log << odom (truePose (j) * makeRigid2d (0.1, 0.0, 0.01), 100.5 + j) << "\n";
  }
  return log.str ();
}

class LogCarmen : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    dir_ = fs::temp_directory_path () / ("pcl_crf_logs_carmen_" + std::to_string (::getpid ()));
    fs::create_directories (dir_);
  }
  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }
  std::string
  write (const std::string& name, const std::string& text, bool gzip)
  {
    const std::string path = (dir_ / name).string ();
    std::ofstream file (path, std::ios::binary);
    if (!gzip) {
      file << text;
      return path;
    }
    boost::iostreams::filtering_ostream out;
    out.push (boost::iostreams::gzip_compressor ());
    out.push (file);
    out << text;
    return path;
  }
  fs::path dir_;
};

TEST_F (LogCarmen, ReadsScansInBeamOrderAndDropsNoReturns)
{
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("room.log", correctedLog (4), false));
  ASSERT_EQ (log.scans.size (), 4u);
  EXPECT_TRUE (log.has_reference_poses);
  EXPECT_TRUE (log.has_odometry);
  const pcl_crf::LaserScanRecord& scan = log.scans[2];
  EXPECT_EQ (scan.sensor.beam_count, 181);
  EXPECT_NEAR (scan.sensor.angle_min, -M_PI / 2, 1e-12);
  EXPECT_NEAR (scan.sensor.angle_increment, M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ (scan.stamp, 102.0);
  ASSERT_EQ (scan.points.cols (), 181 - 3);  // beams 0, 5, 7 carry no return
  ASSERT_EQ (scan.beams.size (), 178u);
  EXPECT_EQ (scan.beams[0], 1);
  EXPECT_EQ (scan.beams[4], 6);
  EXPECT_EQ (scan.beams[5], 8);
  EXPECT_TRUE (std::is_sorted (scan.beams.begin (), scan.beams.end ()));
  // every point lies on a wall of the room once mapped with the corrected pose
  for (Eigen::Index i = 0; i < scan.points.cols (); ++i) {
    const Eigen::Vector2d w = scan.pose * scan.points.col (i);
    const double to_wall = std::min ({std::abs (w.x () + 4), std::abs (w.x () - 8), std::abs (w.y () + 3),
                                      std::abs (w.y () - 5)});
    EXPECT_LT (to_wall, 1e-6) << "point " << i;
  }
  EXPECT_TRUE (scan.has_pose);
  EXPECT_TRUE (scan.pose.isApprox (truePose (2), 1e-9));
}

TEST_F (LogCarmen, CorrectedLogTakesOdometryFromTheReanchoredOdomStream)
{
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("room.log", correctedLog (4), false));
  EXPECT_FALSE (log.scans[0].has_odometry_step);
  for (int j = 1; j < 4; ++j) {
    ASSERT_TRUE (log.scans[j].has_odometry_step);
    const Rigid2d expected = truePose (j - 1).inverse () * truePose (j) * odometryError (j);
    EXPECT_TRUE (log.scans[j].odometry_step.isApprox (expected, 1e-8)) << "scan " << j;
  }
}

TEST_F (LogCarmen, RawLogTakesOdometryFromTheLaserRecords)
{
  std::string text;
  for (int j = 0; j < 3; ++j)
    text += flaser (j, 91, false) + "\n";
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("raw.log", text, false));
  EXPECT_FALSE (log.has_reference_poses);
  EXPECT_FALSE (log.scans[1].has_pose);
  ASSERT_TRUE (log.scans[2].has_odometry_step);
  // odometry fields of scan j: truePose (j) shifted by (0.3, -0.2) and rotated by 0.1 j more
  const auto fields = [] (int j) {
    const Eigen::Vector3d p = pcl_crf::toXYTheta (truePose (j));
    return makeRigid2d (p.x () + 0.3, p.y () - 0.2, p.z () + 0.1 * j);
  };
  EXPECT_TRUE (log.scans[2].odometry_step.isApprox (fields (1).inverse () * fields (2), 1e-8));
}

TEST_F (LogCarmen, RawLogWhosePoseEqualsItsOdometryHasNoReferencePoses)
{
  // Its pose equals its odometry fields, as in a corrected log, but no ODOM line
  // re-anchors the stream at a scan's pose: the pose is odometry, not a reference.
  for (const bool with_odom_stream : {true, false}) {
    const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("raw.log", rawLog (4, with_odom_stream), false));
    EXPECT_FALSE (log.has_reference_poses) << "with ODOM stream: " << with_odom_stream;
    for (const auto& scan : log.scans)
      EXPECT_FALSE (scan.has_pose);
    EXPECT_TRUE (log.has_odometry);
    ASSERT_TRUE (log.scans[2].has_odometry_step);
    EXPECT_TRUE (log.scans[2].odometry_step.isApprox (truePose (1).inverse () * truePose (2), 1e-8));
  }
  // One scan whose next ODOM line is not its pose makes the whole log raw.
  std::string text = correctedLog (4);
  const std::string anchor = odom (truePose (2), 0.0) + "\n";
  ASSERT_NE (text.find (anchor), std::string::npos);
  text.replace (text.find (anchor), anchor.size (), odom (truePose (2) * makeRigid2d (0.1, 0.0, 0.0), 0.0) + "\n");
  EXPECT_FALSE (pcl_crf::readCarmenLog (write ("mixed.log", text, false)).has_reference_poses);
  EXPECT_TRUE (pcl_crf::readCarmenLog (write ("room.log", correctedLog (4), false)).has_reference_poses);
}

TEST_F (LogCarmen, ReadsGzipLikePlainText)
{
  const std::string text = correctedLog (3);
  const pcl_crf::LaserLog plain = pcl_crf::readCarmenLog (write ("a.log", text, false));
  const pcl_crf::LaserLog packed = pcl_crf::readCarmenLog (write ("a.log.gz", text, true));
  ASSERT_EQ (plain.scans.size (), packed.scans.size ());
  for (std::size_t k = 0; k < plain.scans.size (); ++k) {
    EXPECT_TRUE (plain.scans[k].points.isApprox (packed.scans[k].points));
    EXPECT_TRUE (plain.scans[k].odometry_step.isApprox (packed.scans[k].odometry_step));
  }
  EXPECT_EQ (pcl_crf::detectLaserLogFormat ((dir_ / "a.log.gz").string ()), pcl_crf::LaserLogFormat::Carmen);
  EXPECT_EQ (pcl_crf::readLaserLog ((dir_ / "a.log.gz").string ()).scans.size (), 3u);
}

TEST_F (LogCarmen, HonoursRangeLimitsAndMaxScans)
{
  pcl_crf::CarmenReadOptions options;
  options.max_range = 5.0;
  options.max_scans = 2;
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("room.log", correctedLog (4), false), options);
  ASSERT_EQ (log.scans.size (), 2u);
  for (const auto& scan : log.scans)
    for (Eigen::Index i = 0; i < scan.points.cols (); ++i)
      EXPECT_LE (scan.points.col (i).norm (), 5.0 + 1e-9);
  EXPECT_LT (log.scans[0].points.cols (), 178);
}

TEST_F (LogCarmen, ReadsRobotLaser1)
{
  // ROBOTLASER1 type start fov res max acc remission n r.. m e.. laser_pose robot_pose tv rv fs ss ta ts host lts
  std::string text;
  for (int j = 0; j < 2; ++j) {
    std::ostringstream line;
    line << "ROBOTLASER1 0 -1.0 2.0 0.5 20 0.01 0 5 1 2 3 4 99 2 7 7 " << j << " 0 0 " << j + 0.5
         << " 0.1 0 0 0 0 0 0 " << 10 + j << " host " << 10 + j;
    text += line.str () + "\n";
  }
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (write ("robot.log", text, false));
  ASSERT_EQ (log.scans.size (), 2u);
  const auto& scan = log.scans[1];
  EXPECT_EQ (scan.sensor.beam_count, 5);
  EXPECT_DOUBLE_EQ (scan.sensor.angle_min, -1.0);
  EXPECT_DOUBLE_EQ (scan.sensor.angle_increment, 0.5);
  EXPECT_DOUBLE_EQ (scan.sensor.range_max, 20.0);
  ASSERT_EQ (scan.points.cols (), 4);  // 99 > 20 m is no return
  EXPECT_NEAR (scan.points (0, 0), std::cos (-1.0), 1e-12);
  EXPECT_NEAR (scan.points (1, 3), 4 * std::sin (0.5), 1e-12);
  EXPECT_DOUBLE_EQ (scan.stamp, 11.0);
  // robot poses (j + 0.5, 0.1, 0) differ from the laser poses (j, 0, 0): a raw log,
  // odometry from the robot poses
  EXPECT_FALSE (log.has_reference_poses);
  EXPECT_TRUE (scan.odometry_step.isApprox (makeRigid2d (1.0, 0.0, 0.0), 1e-12));
}

TEST_F (LogCarmen, RobotLaser1ReadingsAtItsOwnMaximumRangeAreNoReturns)
{
  // A laser of 8 m maximum range writes 8 for a beam without a return; readings of
  // 1, 7.9, 8, 8.5 and 25 m: only 1 and 7.9 are returns, though all are within the
  // reader's 30 m.
  const std::string line = "ROBOTLASER1 0 -1.0 2.0 0.5 8 0.01 0 5 1 7.9 8 8.5 25 0 "
                           "0 0 0 0 0 0 0 0 0 0 0 10 host 10\n";
  const std::string path = write ("short_range.log", line, false);
  const pcl_crf::LaserLog log = pcl_crf::readCarmenLog (path);
  ASSERT_EQ (log.scans.size (), 1u);
  EXPECT_DOUBLE_EQ (log.scans[0].sensor.range_max, 8.0);
  EXPECT_EQ (log.scans[0].beams, (std::vector<int>{0, 1}));
  // The smaller of the two applies: with max_range 7.9 m a reading of 7.9 m is still
  // a return (max_range is inclusive, as for FLASER), with 5 m it is not, ...
  pcl_crf::CarmenReadOptions options;
  options.max_range = 7.9;
  EXPECT_EQ (pcl_crf::readCarmenLog (path, options).scans[0].beams, (std::vector<int>{0, 1}));
  options.max_range = 5.0;
  EXPECT_EQ (pcl_crf::readCarmenLog (path, options).scans[0].beams, (std::vector<int>{0}));
  EXPECT_DOUBLE_EQ (pcl_crf::readCarmenLog (path, options).scans[0].sensor.range_max, 5.0);
  // ... and a record without a maximum range (0) keeps every reading up to max_range.
  std::string unknown = line;
  unknown.replace (unknown.find (" 8 0.01"), 7, " 0 0.01");
  EXPECT_EQ (pcl_crf::readCarmenLog (write ("no_max.log", unknown, false)).scans[0].beams,
             (std::vector<int>{0, 1, 2, 3, 4}));
}

TEST_F (LogCarmen, ErrorsNameTheFileLineAndProblem)
{
  const auto expectError = [] (const std::string& path, const std::string& fragment) {
    try {
      pcl_crf::readCarmenLog (path);
      ADD_FAILURE () << "no exception; expected " << fragment;
    }
    catch (const pcl_crf::LogError& error) {
      EXPECT_NE (std::string (error.what ()).find (fragment), std::string::npos) << error.what ();
    }
  };
  expectError ((dir_ / "missing.log").string (), "missing.log: cannot read the CARMEN log: no such file");
  // std::ifstream opens a directory; its reads then failed as "a corrupt gzip file?"
  expectError (dir_.string (), "cannot read the CARMEN log: is a directory, not a file");
  const std::string broken = write ("broken.log", correctedLog (1) + "FLASER 4 1 2 x 4 0 0 0 0 0 0 1 h 1\n", false);
  expectError (broken, "broken.log:6: FLASER record: a range reading");
  // More ranges than the count: they were read as the pose, odometry and timestamp.
  const std::string longer = write ("longer.log", correctedLog (1) + "FLASER 2 1 2 3 0 0 0 0 0 0 1 h 1\n", false);
  expectError (longer, "longer.log:6: FLASER record: more fields than its 2 readings, pose, odometry and timestamp "
                       "(the host name is a number");
  const std::string trailing = write ("trailing.log", correctedLog (1) + "FLASER 2 1 2 0 0 0 0 0 0 1 h 1 7\n", false);
  expectError (trailing, "host name and logger timestamp: '7'");
  const std::string far = write ("far.log", correctedLog (1) + "FLASER 2 1 2 1e300 0 0 0 0 0 1 h 1\n", false);
  expectError (far, "FLASER record: the pose x y theta lies beyond 1e18 m");
  // Beams 1e308 rad apart made NaN points (2 x 1e308 is inf).
  const std::string wide = write ("wide.log", "ROBOTLASER1 0 -1.5707963 3.1415927 1e308 81.9 0.01 0 3 1 1 1 0 "
                                              "0 0 0 0 0 0 0 0 0.5 0.3 0 1.0 host 1.0\n", false);
  expectError (wide, "wide.log:1: ROBOTLASER1 record: 3 beams 1e+308 rad apart from the start angle -1.5708 rad: "
                     "the beams must span at most one turn");
  // Without the host name and logger timestamp (some converted logs): read as before.
  EXPECT_EQ (pcl_crf::readCarmenLog (write ("short.log", correctedLog (1) + "FLASER 2 1 2 0 0 0 0 0 0 1\n", false))
                 .scans.size (),
             2u);
  const std::string truncated = write ("cut.log", "FLASER 3 1 2 3 0 0\n", false);
  EXPECT_THROW (pcl_crf::readCarmenLog (truncated), pcl_crf::LogError);
  const std::string empty = write ("empty.log", "PARAM a b\nODOM 0 0 0 0 0 0 1 h 1\n", false);
  expectError (empty, "no FLASER or ROBOTLASER1 record");
  const std::string not_gzip = write ("bad.log.gz", "\x1f\x8b garbage that is not deflate data", false);
  EXPECT_THROW (pcl_crf::readCarmenLog (not_gzip), pcl_crf::LogError);
  const std::string whole = write ("whole.log.gz", correctedLog (20), true);
  fs::resize_file (whole, fs::file_size (whole) / 2);  // a cut download
  expectError (whole, "truncated or corrupt gzip");
  pcl_crf::CarmenReadOptions nonsense;
  nonsense.max_range = -1.0;
  EXPECT_THROW (pcl_crf::readCarmenLog (write ("ok.log", correctedLog (2), false), nonsense), pcl_crf::LogError);
}

}  // namespace
