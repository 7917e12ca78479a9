// pcl_crf_run: usage, errors and a run over a tiny CARMEN log the test writes.

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/logs/carmen_log.h>
#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/rosbag_log.h>

#include "app_runner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>

namespace fs = std::filesystem;
using pcl_crf::test::runTool;

namespace {

/** A corrected CARMEN log: a robot drives +x in the room [-4, 8] x [-3, 5]
 *  (361 beams), the ODOM stream re-anchored at every scan. The raw odometry before
 *  scan j is off the true pose by \a odometry_offsets[j] in x (default 2 cm). */
std::string
roomLog (int scans, bool reanchored = true, const std::vector<double>& odometry_offsets = {})
{
  std::ostringstream log;
  log.precision (10);
  for (int j = 0; j < scans; ++j) {
    const double x = 0.3 * j, y = 0.05 * j, theta = 0.02 * j;
    const double offset = j < static_cast<int> (odometry_offsets.size ()) ? odometry_offsets[j] : 0.02;
    if (j > 0)  // last raw odometry before this scan: the true step plus the offset
      log << "ODOM " << x + offset << ' ' << y << ' ' << theta << " 0 0 0 " << j << " h " << j << "\n";
    log << "FLASER 361";
    for (int i = 0; i < 361; ++i) {
      const double a = theta - M_PI / 2 + i * M_PI / 360, dx = std::cos (a), dy = std::sin (a);
      double t = 1e9;
      for (double wx : {-4.0, 8.0})
        if (std::abs (dx) > 1e-12 && (wx - x) / dx > 0)
          t = std::min (t, (wx - x) / dx);
      for (double wy : {-3.0, 5.0})
        if (std::abs (dy) > 1e-12 && (wy - y) / dy > 0)
          t = std::min (t, (wy - y) / dy);
      log << ' ' << (i % 50 == 3 ? 81.9 : t);
    }
    log << ' ' << x << ' ' << y << ' ' << theta << ' ' << x << ' ' << y << ' ' << theta << ' ' << j + 0.5
        << " h " << j + 0.5 << "\n";
    if (reanchored)  // a raw log's pose is odometry, which no ODOM line re-anchors
      log << "ODOM " << x << ' ' << y << ' ' << theta << " 0 0 0 0 h 0\n";
  }
  return log.str ();
}

class ToolRun : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    dir_ = fs::temp_directory_path () / ("pcl_crf_tool_run_" + std::to_string (::getpid ()));
    fs::create_directories (dir_);
    std::ofstream (dir_ / "room.log") << roomLog (6);
  }
  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }
  std::string
  log () const
  {
    return (dir_ / "room.log").string ();
  }
  /** The room log's scans and corrected poses, stamped from 100 s on (bags need positive times). */
  pcl_crf::LaserLog
  roomForBag () const
  {
    std::ifstream text (log ());
    pcl_crf::LaserLog room = pcl_crf::readCarmenLog (text, "room");
    for (auto& scan : room.scans)
      scan.stamp += 100.0;
    return room;
  }
  fs::path dir_;
};

TEST_F (ToolRun, HelpListsOptionsWithDefaultsAndUnits)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_run", "-h");
  EXPECT_EQ (run.exit_code, 0);
  for (const char* text : {"Usage:", "--method NAME", "(default: icp)", "--step N", "--max-pairs N",
                           "--scan-topic T", "(default: /scan)", "--pose-topic T", "[m]", "ROS1 bags",
                           "ego_motion.csv columns", "Example:"})
    EXPECT_NE (run.output.find (text), std::string::npos) << text << "\n" << run.output;
  EXPECT_TRUE (run.output.find ("supported in this build") != std::string::npos ||
               run.output.find ("NOT supported in this build") != std::string::npos);
  EXPECT_EQ (runTool ("pcl_crf_run", "").exit_code, 1);
}

TEST_F (ToolRun, RunsIcpOverALogAndWritesPredictionsAndCsv)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const fs::path out = dir_ / "out";
  const auto run = runTool ("pcl_crf_run", log () + " --method icp -o " + out.string () + " -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Ran icp on 5 pairs"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("pairs/s"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("odometry   translation error mean 0.0200 m"), std::string::npos) << run.output;
  ASSERT_TRUE (fs::is_regular_file (out / "ego_motion.csv"));
  std::ifstream csv (out / "ego_motion.csv");
  std::string header, row;
  std::getline (csv, header);
  EXPECT_EQ (header.rfind ("pair,source_scan,target_scan,", 0), 0u) << header;
  int rows = 0;
  while (std::getline (csv, row)) {
    ++rows;
    EXPECT_EQ (std::count (row.begin (), row.end (), ','), std::count (header.begin (), header.end (), ','));
  }
  EXPECT_EQ (rows, 5);
  const pcl_crf::Prediction prediction = pcl_crf::loadPrediction ((out / "scan_000002").string ());
  // the room is static and well structured: ICP finds the true step (0.3 m, 0.02 rad) closely
  const Eigen::Vector3d ego = pcl_crf::toXYTheta (prediction.T_source_target);
  EXPECT_NEAR (ego.z (), 0.02, 0.01);
  EXPECT_NEAR (ego.head<2> ().norm (), std::hypot (0.3, 0.05), 0.05);
}

TEST_F (ToolRun, TheSummarysMedianOfAnEvenCountIsTheMeanOfTheTwoMiddleValues)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  // Four pairs whose odometry is off by 2, 3, 5 and 9 cm: the median is 4 cm (the upper
  // middle value, 5 cm, was printed).
  std::ofstream (dir_ / "offsets.log") << roomLog (5, true, {0.0, 0.02, 0.03, 0.05, 0.09});
  const auto run = runTool ("pcl_crf_run", (dir_ / "offsets.log").string () + " --method icp -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("odometry   translation error mean 0.0475 m, median 0.0400 m"), std::string::npos)
      << run.output;
}

TEST_F (ToolRun, StepStartMaxPairsAndSavedPairs)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const fs::path pairs = dir_ / "pairs";
  const auto run = runTool ("pcl_crf_run", log () + " --start 1 --step 2 --max-pairs 2 -q --save-pairs " +
                                               pairs.string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Ran icp on 2 pairs"), std::string::npos) << run.output;
  const auto names = pcl_crf::listScanPairs (pairs.string ());
  ASSERT_EQ (names.size (), 2u);
  EXPECT_EQ (names[0], "scan_000001");
  EXPECT_EQ (names[1], "scan_000003");
  const pcl_crf::ScanPair pair = pcl_crf::loadScanPair ((pairs / "scan_000003").string ());
  EXPECT_TRUE (pair.hasTruth ());
  EXPECT_EQ (pair.sensor.beam_count, 361);
  // Saved again into the same folder, another log's pairs would mix with these.
  const auto again = runTool ("pcl_crf_run", log () + " --max-pairs 1 -q --save-pairs " + pairs.string ());
  EXPECT_EQ (again.exit_code, 1);
  EXPECT_NE (again.output.find ("is not a new or empty folder"), std::string::npos) << again.output;
  EXPECT_EQ (pcl_crf::listScanPairs (pairs.string ()).size (), 2u);
}

TEST_F (ToolRun, RawCarmenLogWhosePoseEqualsItsOdometryHasNoReference)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  // Its FLASER poses equal their odometry fields, as in the corrected room log, but the
  // ODOM stream is not re-anchored at them: they are odometry, not reference poses.
  const fs::path raw = dir_ / "raw.log";
  std::ofstream (raw) << roomLog (6, false);
  const auto run = runTool ("pcl_crf_run", raw.string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Read 6 scans"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("(reference poses: no, odometry: yes)"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("The log has no reference poses: no ego-motion error to report."), std::string::npos)
      << run.output;
  EXPECT_NE (runTool ("pcl_crf_run", log ()).output.find ("(reference poses: yes, odometry: yes)"), std::string::npos);
}

TEST_F (ToolRun, ScansStampedOutOfOrderAreCountedAndTheirPairsHaveNoInterval)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  // Scan 3 carries scan 2's stamp (a copied stamp), scan 5 one before scan 4's (a clock
  // stepping back): pairs 2-3 and 4-5 have no known interval, pair 3-4 2 s, the others 1 s.
  std::string text = roomLog (6);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{" 3.5 h 3.5\n", " 2.5 h 2.5\n"},
                                 std::pair<std::string, std::string>{" 5.5 h 5.5\n", " 4 h 4\n"}}) {
    ASSERT_NE (text.find (from), std::string::npos) << from;
    text.replace (text.find (from), from.size (), to);
  }
  const fs::path unordered = dir_ / "unordered.log";
  std::ofstream (unordered) << text;
  std::ifstream in (unordered);
  const pcl_crf::LaserLog read = pcl_crf::readCarmenLog (in, "unordered");
  EXPECT_EQ (pcl_crf::countStampsNotAfterTheLast (read), 2u);
  pcl_crf::LogPairOptions options;
  const std::vector<double> intervals = {1.0, 1.0, 0.0, 2.0, 0.0};
  for (std::size_t k = 0; k < intervals.size (); ++k)
    EXPECT_EQ (pcl_crf::makeLogPair (read, k, options).odometry.interval, intervals[k]) << k;
  const auto run = runTool ("pcl_crf_run", unordered.string () + " -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("2 of the 6 scans are stamped at or before the scan before them"), std::string::npos)
      << run.output;
  EXPECT_EQ (runTool ("pcl_crf_run", log () + " -q").output.find ("stamped at or before"), std::string::npos);
}

TEST_F (ToolRun, RunsOnARosBagWithMocapPoses)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  if (!pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  const pcl_crf::LaserLog room = roomForBag ();  // as a bag with an ego pose topic
  pcl_crf::RosbagReadOptions topics;
  topics.scan_topic = "/base_scan";
  topics.pose_topic = "/mocap";
  const std::string bag = (dir_ / "room.bag").string ();
  pcl_crf::writeRosbagLog (bag, room, topics);
  auto run = runTool ("pcl_crf_run", bag + " --scan-topic /base_scan --pose-topic /mocap -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Ran icp on 5 pairs"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("Ego motion vs the reference poses (5 pairs)"), std::string::npos) << run.output;
  EXPECT_EQ (run.output.find ("odometry   translation"), std::string::npos) << run.output;  // bags: none
  // Without the pose topic the bag has no reference; --stationary makes it the identity,
  // so the error is the size of ICP's estimate of the true step (0.3, 0.05, 0.02).
  const fs::path csv_path = dir_ / "stationary.csv";
  run = runTool ("pcl_crf_run", bag + " --scan-topic /base_scan --stationary -q --csv " + csv_path.string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Ego motion vs the identity (5 pairs)"), std::string::npos) << run.output;
  std::ifstream csv (csv_path);
  std::string header, row;
  std::getline (csv, header);
  ASSERT_TRUE (std::getline (csv, row)) << header;
  const auto column = [] (const std::string& line, int k) {  // the k-th comma-separated field
    std::istringstream fields (line);
    std::string field;
    for (int j = 0; j <= k; ++j)
      std::getline (fields, field, ',');
    return field;
  };
  EXPECT_EQ (column (header, 15), "ref_x");
  EXPECT_EQ (column (row, 15), "0.000000");
  EXPECT_EQ (column (header, 18), "translation_error");
  EXPECT_NEAR (std::stod (column (row, 18)), std::hypot (0.3, 0.05), 0.05) << row;
  EXPECT_NEAR (std::stod (column (row, 19)), 0.02, 0.01) << row;
  run = runTool ("pcl_crf_run", bag + " -q");
  EXPECT_EQ (run.exit_code, 1);
  EXPECT_NE (run.output.find ("no topic /scan in the bag; it has: /base_scan"), std::string::npos) << run.output;
}

TEST_F (ToolRun, PairsWithoutReferencePosesAtBothScansAreToldApartFromALogWithout)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  if (!pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  // The room log as a bag whose pose track covers scans 0, 2 and 4 only (poses 2 s apart,
  // more than the 0.5 s gap that is interpolated).
  pcl_crf::LaserLog room = roomForBag ();
  for (std::size_t k = 0; k < room.scans.size (); ++k)
    room.scans[k].has_pose = k % 2 == 0;
  pcl_crf::RosbagReadOptions topics;
  topics.pose_topic = "/mocap";
  const std::string bag = (dir_ / "gaps.bag").string ();
  pcl_crf::writeRosbagLog (bag, room, topics);
  auto run = runTool ("pcl_crf_run", bag + " --pose-topic /mocap -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_EQ (run.output.find ("The log has no reference poses"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("No pair has reference poses at both of its scans (5 pairs run; the log has them for 3 "
                              "of its 6 scans; --start and --step choose the pairs): no ego-motion error to report."),
             std::string::npos)
      << run.output;
  run = runTool ("pcl_crf_run", bag + " --pose-topic /mocap --step 2 -q");
  EXPECT_NE (run.output.find ("Ego motion vs the reference poses (2 pairs)"), std::string::npos) << run.output;
  // Poses for scans 0 and 1 only, and scan 1 without a return: the one pair with both
  // poses is skipped, the pairs run have none.
  for (std::size_t k = 0; k < room.scans.size (); ++k)
    room.scans[k].has_pose = k < 2;
  room.scans[1].points.resize (2, 0);
  room.scans[1].beams.clear ();
  pcl_crf::writeRosbagLog (bag, room, topics);
  run = runTool ("pcl_crf_run", bag + " --pose-topic /mocap -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Every pair with reference poses at both scans was skipped (1 pair; see the warnings "
                              "above): no ego-motion error to report."),
             std::string::npos)
      << run.output;
  // A log without reference poses says so, as before.
  run = runTool ("pcl_crf_run", bag + " -q");
  EXPECT_NE (run.output.find ("The log has no reference poses: no ego-motion error to report."), std::string::npos)
      << run.output;
}

TEST_F (ToolRun, ABagsScansStampedAlikeAreLeftOutWithAWarning)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  if (!pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  pcl_crf::LaserLog room = roomForBag ();
  room.scans[3].stamp = room.scans[2].stamp;  // a copied stamp
  room.scans[3].has_pose = false;
  pcl_crf::RosbagReadOptions topics;
  topics.pose_topic = "/mocap";
  const std::string bag = (dir_ / "copied.bag").string ();
  pcl_crf::writeRosbagLog (bag, room, topics);
  const auto run = runTool ("pcl_crf_run", bag + " --pose-topic /mocap -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("copied.bag: 1 scan of /scan stamped like the scan before it was left out (the first at "
                              "102.500 s)"),
             std::string::npos)
      << run.output;
  EXPECT_NE (run.output.find ("Ran icp on 4 pairs"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("Ego motion vs the reference poses (4 pairs)"), std::string::npos) << run.output;
  EXPECT_EQ (run.output.find ("stamped at or before"), std::string::npos) << run.output;
}

TEST_F (ToolRun, ACorruptBagIsAnErrorNamingTheByteNotACrash)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  if (!pcl_crf::rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  pcl_crf::LaserLog room = roomForBag ();
  const fs::path bag = dir_ / "flipped.bag";
  pcl_crf::writeRosbagLog (bag.string (), room);
  std::string bytes;
  {
    std::ifstream in (bag, std::ios::binary);
    bytes.assign (std::istreambuf_iterator<char> (in), std::istreambuf_iterator<char> ());
  }
  // The chunk's index record (fields conn, count, op, ver): after ver's value and the data
  // length, each entry is a time (8 bytes) and the message's offset in the chunk (4).
  const std::size_t op = bytes.find (std::string ("op=\x04", 4));
  ASSERT_NE (op, std::string::npos);
  const std::size_t first_offset = bytes.find ("ver=", op) + 4 + 4 + 4 + 8;
  bytes[first_offset + 3] = static_cast<char> (bytes[first_offset + 3] ^ 0xff);  // 4 GB past the chunk
  std::ofstream (bag, std::ios::binary | std::ios::trunc) << bytes;
  const auto run = runTool ("pcl_crf_run", bag.string () + " -q");
  EXPECT_EQ (run.exit_code, 1) << run.output;  // librosbag read out of bounds: SIGSEGV
  EXPECT_NE (run.output.find ("flipped.bag: not a readable ROS bag (truncated or corrupted?): at byte " +
                              std::to_string (first_offset - 8) + ", an index entry's offset"),
             std::string::npos)
      << run.output;
}

TEST_F (ToolRun, OptionsForTheOtherKindOfLogAreNamed)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  // A bag's options given for a CARMEN log did nothing without a word.
  const auto run = runTool ("pcl_crf_run", log () + " --pose-delay 0.1 --max-pairs 1 -q");
  EXPECT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("--pose-delay applies to ROS bags only"), std::string::npos) << run.output;
  const auto plain = runTool ("pcl_crf_run", log () + " --max-range 25 --max-pairs 1 -q");
  EXPECT_EQ (plain.output.find ("applies to"), std::string::npos) << plain.output;
}

TEST_F (ToolRun, BadArgumentsAndFilesAreClearErrors)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const struct
  {
    std::string arguments, message;
  } cases[] = {
      {(dir_ / "missing.log").string (), "missing.log: cannot read the log: no such file"},
      {dir_.string (), "cannot read the log: is a directory, not a file"},
      {log () + " --method nonsense", "unknown method 'nonsense'"},
      {log () + " --method kmeans", "method 'kmeans' clusters the pairs' true associations: give --label"},
      {log () + " --step 0", "--step needs a whole number >= 1"},
      {log () + " --step abc", "--step needs a decimal number, not 'abc'"},
      {log () + " --max-pairs -2", "--max-pairs needs a whole number >= 0"},
      {log () + " --start 99", "no scan pair"},
      {log () + " --laser-offset 1,2", "--laser-offset needs 3 comma-separated numbers"},
      {log () + " --laser-offset 1e20,0,0", "--laser-offset needs |X|, |Y| <= 100 m and |TH| <= 2 pi rad"},
      {log () + " --laser-offset 0,0,90", "(radians, not degrees)"},
      {log () + " --pose-delay 1e300", "--pose-delay needs a delay of at most 60 s either way"},
      {log () + " --object-topics ,", "--object-topics needs comma-separated topic names, got ','"},
      {log () + " --min-range 5 --max-range 1", "0 <= min < max"},
      {log () + " extra", "Expected one log file, got 2"},
      {log () + " -o", "-o needs a value"},
      {log () + " -o ''", "Option -o is given an empty value"},  // wrote nothing, exit 0
      {log () + " --bogus", "Unknown option '--bogus' (see "},
      {log () + " --csv --method icp", "Option --csv needs a value"},
      {log () + " --stationary", "has reference poses: give one or the other"},
  };
  for (const auto& c : cases) {
    const auto run = runTool ("pcl_crf_run", c.arguments);
    EXPECT_EQ (run.exit_code, 1) << c.arguments << "\n" << run.output;
    EXPECT_NE (run.output.find (c.message), std::string::npos) << c.arguments << "\n" << run.output;
  }
  std::ofstream (dir_ / "broken.log") << "FLASER 3 1 x 3 0 0 0 0 0 0 1 h 1\n";
  const auto run = runTool ("pcl_crf_run", (dir_ / "broken.log").string ());
  EXPECT_EQ (run.exit_code, 1);
  EXPECT_NE (run.output.find ("broken.log:1: FLASER record"), std::string::npos) << run.output;
}

}  // namespace
