#pragma once
// Command-line options for reading real laser logs, shared by pcl_crf_run and
// pcl_crf_viewer (--log): which topics, which ranges, how scans are paired.

#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>

#include "../app_common.h"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pcl_crf {
namespace apps {

/** Parses "--name A,B,C" into exactly \a count numbers when present. */
inline bool
numberListOption (int argc, char** argv, const char* name, std::vector<double>& values, std::size_t count)
{
  std::string text;
  if (pcl::console::parse_argument (argc, argv, name, text) < 0)
    return pcl::console::find_argument (argc, argv, name) < 0 ||
           (pcl::console::print_error ("%s needs a value (see -h).\n", name), false);
  std::vector<double> parsed;
  std::stringstream in (text);
  std::string part;
  while (std::getline (in, part, ',')) {
    const std::optional<double> v = pcl_crf::parseDecimal (part);
    if (!v) {
      pcl::console::print_error ("%s needs %zu comma-separated numbers, not '%s'.\n", name, count, text.c_str ());
      return false;
    }
    parsed.push_back (*v);
  }
  if (parsed.size () != count) {
    pcl::console::print_error ("%s needs %zu comma-separated numbers, not '%s'.\n", name, count, text.c_str ());
    return false;
  }
  values = parsed;
  return true;
}

/** How a log is read and paired. */
struct LogArguments
{
  LaserLogReadOptions read;
  LogPairOptions pairs;
  /** the log options given on the command line. */
  std::set<std::string> given;
};

/** The options of LogArguments that take a value (for positionalArguments). */
inline std::set<std::string>
logValueOptions ()
{
  return {"--step", "--still-tolerance", "--min-range", "--max-range", "--scan-topic", "--pose-topic", "--object-topics",
          "--laser-offset", "--pose-delay"};
}

/** The help lines of the log options. */
inline void
printLogOptionsHelp ()
{
  using pcl::console::print_info;
  print_info ("  --step N               pair scan k with scan k+N (default: 1, consecutive scans)\n");
  print_info ("  --label                give every point an object label and a true match from the\n"
              "                         reference poses (default: off; unlabelled pairs)\n");
  print_info ("  --still-tolerance M    a tracked object no corner of whose footprint moves M or more\n"
              "                         against the static world between a pair's scans stands still:\n"
              "                         it is part of the static world there (default: 0.01 m, the\n"
              "                         range noise; 0 keeps every tracked object)\n");
  print_info (" CARMEN logs (.log, .log.gz; FLASER, ROBOTLASER1, ODOM):\n");
  print_info ("  --min-range M          shortest valid reading [m] (default: 0.01)\n");
  print_info ("  --max-range M          longest valid reading [m] (default: 30; 81.9, 50, 32.76 = no return;\n"
              "                         a ROBOTLASER1 record's own maximum range applies when shorter)\n");
  print_info (" ROS1 bags (.bag; sensor_msgs/LaserScan + geometry_msgs/PoseStamped) - %s:\n",
              rosbagSupported () ? "supported in this build"
                                 : "NOT supported in this build (needs librosbag-dev at configure time)");
  print_info ("  --scan-topic T         LaserScan topic (default: /scan)\n");
  print_info ("  --pose-topic T         ego reference pose topic (default: none, no reference motion)\n");
  print_info ("  --object-topics A,B    reference pose topics of other moving objects (default: none)\n");
  print_info ("  --laser-offset X,Y,TH  laser pose in the ego pose frame [m, m, rad] (default: 0,0,0;\n"
              "                         the datmo bags of shared/data: -0.166,0.019,0; |X|, |Y| <= 100,\n"
              "                         |TH| <= 2 pi)\n");
  print_info ("  --pose-delay S         use the pose stamped t+S for the scan stamped t [s] (default: 0;\n"
              "                         the datmo bags: 0.025; |S| <= 60)\n");
}

/** Warns about the log options given that \a format does not read: the range limits are
 *  CARMEN's (a bag's LaserScan carries its own range_min and range_max), the topics,
 *  laser offset and pose delay a bag's. */
inline void
warnAboutOptionsTheLogIgnores (const LogArguments& args, LaserLogFormat format)
{
  const bool bag = format == LaserLogFormat::Rosbag;
  const std::vector<std::string> ignored =
      bag ? std::vector<std::string>{"--min-range", "--max-range"}
          : std::vector<std::string>{"--scan-topic", "--pose-topic", "--object-topics", "--laser-offset", "--pose-delay"};
  for (const std::string& option : ignored)
    if (args.given.count (option))
      pcl::console::print_warn ("%s applies to %s only: %s.\n", option.c_str (), bag ? "CARMEN logs" : "ROS bags",
                                bag ? "a bag's LaserScans carry their own range_min and range_max"
                                    : "this CARMEN log does not read it");
}

/** Prints what the reader left out of \a log (LaserLog::warnings), one warning each. */
inline void
printLogWarnings (const LaserLog& log)
{
  for (const std::string& warning : log.warnings)
    pcl::console::print_warn ("%s.\n", warning.c_str ());
}

/** Reads the log options; false after a print_error. */
inline bool
parseLogArguments (int argc, char** argv, LogArguments& args)
{
  for (const std::string& option : logValueOptions ())
    if (pcl::console::find_argument (argc, argv, option.c_str ()) >= 0)
      args.given.insert (option);
  long step = 1;
  if (!countOption (argc, argv, "--step", step, 1))
    return false;
  args.pairs.step = static_cast<std::size_t> (step);
  args.pairs.label_points = pcl::console::find_switch (argc, argv, "--label");
  if (!numberOption (argc, argv, "--still-tolerance", args.pairs.still_tolerance))
    return false;
  if (!(args.pairs.still_tolerance >= 0.0)) {
    pcl::console::print_error ("--still-tolerance needs a distance of at least 0 [m].\n");
    return false;
  }
  CarmenReadOptions& carmen = args.read.carmen;
  if (!numberOption (argc, argv, "--min-range", carmen.min_range) ||
      !numberOption (argc, argv, "--max-range", carmen.max_range))
    return false;
  if (!(carmen.min_range >= 0.0) || !(carmen.max_range > carmen.min_range)) {
    pcl::console::print_error ("--min-range and --max-range need 0 <= min < max [m].\n");
    return false;
  }
  RosbagReadOptions& bag = args.read.rosbag;
  pcl::console::parse_argument (argc, argv, "--scan-topic", bag.scan_topic);
  pcl::console::parse_argument (argc, argv, "--pose-topic", bag.pose_topic);
  std::string objects;
  if (pcl::console::parse_argument (argc, argv, "--object-topics", objects) >= 0) {
    std::stringstream in (objects);
    std::string topic;
    while (std::getline (in, topic, ','))
      if (!topic.empty ())
        bag.object_topics.push_back (topic);
    if (bag.object_topics.empty ()) {
      pcl::console::print_error ("--object-topics needs comma-separated topic names, got '%s'.\n", objects.c_str ());
      return false;
    }
  }
  std::vector<double> offset{0.0, 0.0, 0.0};
  if (!numberListOption (argc, argv, "--laser-offset", offset, 3) ||
      !numberOption (argc, argv, "--pose-delay", bag.pose_delay))
    return false;
  // Bounds far beyond any mounting: they catch degrees given for radians and corrupt values.
  constexpr double kMostOffset = 100.0;  // [m]
  constexpr double kMostDelay = 60.0;    // [s]
  if (!(std::abs (offset[0]) <= kMostOffset) || !(std::abs (offset[1]) <= kMostOffset) ||
      !(std::abs (offset[2]) <= 2.0 * M_PI)) {
    pcl::console::print_error ("--laser-offset needs |X|, |Y| <= %g m and |TH| <= 2 pi rad (radians, not degrees).\n",
                               kMostOffset);
    return false;
  }
  if (!(std::abs (bag.pose_delay) <= kMostDelay)) {
    pcl::console::print_error ("--pose-delay needs a delay of at most %g s either way.\n", kMostDelay);
    return false;
  }
  bag.T_pose_laser = makeRigid2d (offset[0], offset[1], offset[2]);
  if (bag.scan_topic.empty ()) {
    pcl::console::print_error ("--scan-topic needs a topic name.\n");
    return false;
  }
  return true;
}

}  // namespace apps
}  // namespace pcl_crf
