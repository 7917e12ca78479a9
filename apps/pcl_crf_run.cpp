// pcl_crf_run: runs a method over the scan pairs of a real laser log (CARMEN or
// ROS bag) and reports its ego motion against the log's reference poses.

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/metrics/motion_error.h>

#include "app_common.h"
#include "viewer/log_arguments.h"

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <unistd.h>

using namespace pcl::console;
namespace fs = std::filesystem;

namespace {

struct RunArguments
{
  std::string log;
  std::string method = "icp";
  std::string model_dir;
  std::string output;
  std::string csv;
  std::string save_pairs;
  long start = 0;
  long max_pairs = 0;
  bool quiet = false;
  bool stationary = false;  // the reference ego motion of every pair is the identity
  pcl_crf::apps::LogArguments log_args;
};

void
printHelp (const char* program)
{
  std::string methods;
  for (const auto& name : pcl_crf::availableEvaluationMethods ())
    methods += (methods.empty () ? "" : ", ") + name;
  print_info ("Runs a method over the scan pairs of a real laser log and compares its ego motion\n"
              "with the log's reference poses (CARMEN corrected poses, motion capture).\n\n"
              "Usage: %s LOG [options]\n\n"
              "  LOG                    a CARMEN log (.log or .log.gz) or a ROS1 bag (.bag)\n\n", program);
  print_info (" Method:\n");
  print_info ("  --method NAME          the method to run (default: icp); known: %s\n", methods.c_str ());
  print_info ("  --models DIR           load a learned method from DIR/NAME.model (default: none;\n"
              "                         data/models holds the shipped ones, installed in\n"
              "                         <prefix>/share/pcl_crf/models)\n");
  print_info (" Pairs:\n");
  print_info ("  --start K              index of the first source scan (default: 0)\n");
  print_info ("  --max-pairs N          stop after N pairs (default: 0 = all); pairs are\n"
              "                         (K, K+step), (K+step, K+2*step), ...; the time between a\n"
              "                         pair's scans (their stamps) bounds how far a moving object\n"
              "                         is sought (the models' segment_max_speed, 30 m/s)\n");
  pcl_crf::apps::printLogOptionsHelp ();
  print_info (" Reference:\n");
  print_info ("  --stationary           the sensor did not move: every pair's reference ego motion is\n"
              "                         the identity (for a log without reference poses from a robot\n"
              "                         standing still; default: off, the log's reference poses)\n");
  print_info (" Output:\n");
  print_info ("  -o DIR                 write DIR/<pair>/prediction.pcd + prediction.txt (see data/README.md)\n"
              "                         and DIR/ego_motion.csv, one row per pair (default: none)\n");
  print_info ("  --csv FILE             write only the per-pair CSV (the columns of ego_motion.csv) to FILE\n");
  print_info ("  --save-pairs DIR       write the pairs as a labelled dataset (implies --label; needs\n"
              "                         reference poses) for pcl_crf_eval and pcl_crf_viewer into DIR, a new\n"
              "                         or empty folder (default: none)\n");
  print_info ("  -q                     no progress bar\n");
  print_info ("  --list-methods         print the known methods, one per line, and exit\n");
  print_info ("  -h                     this help\n\n");
  print_info ("ego_motion.csv columns: pair, source_scan, target_scan, source_stamp, target_stamp [s],\n"
              "  source_points, target_points, clusters, moving_clusters, est_x, est_y [m], est_theta [rad]\n"
              "  (the method's T_source_target), odom_x, odom_y, odom_theta (the odometry guess),\n"
              "  ref_x, ref_y, ref_theta (reference motion, empty without one), translation_error [m],\n"
              "  rotation_error [rad], odom_translation_error [m], odom_rotation_error [rad], seconds [s].\n\n");
  print_info ("Example:\n  %s intel-corrected.log.gz --method icp -o intel_icp\n", program);
}

bool
parseArguments (int argc, char** argv, RunArguments& args)
{
  std::set<std::string> value_options = pcl_crf::apps::logValueOptions ();
  value_options.insert ({"--method", "--models", "--start", "--max-pairs", "-o", "--csv", "--save-pairs"});
  if (!pcl_crf::apps::checkOptions (argc, argv, value_options, {"-q", "--stationary", "--label", "--list-methods"}))
    return false;
  const auto positional = pcl_crf::apps::positionalArguments (argc, argv, value_options);
  if (positional.size () != 1)
    return print_error ("Expected one log file, got %zu arguments (see -h).\n", positional.size ()), false;
  args.log = positional.front ();
  parse_argument (argc, argv, "--method", args.method);
  parse_argument (argc, argv, "--models", args.model_dir);
  parse_argument (argc, argv, "-o", args.output);
  parse_argument (argc, argv, "--csv", args.csv);
  parse_argument (argc, argv, "--save-pairs", args.save_pairs);
  args.quiet = find_switch (argc, argv, "-q");
  args.stationary = find_switch (argc, argv, "--stationary");
  if (!pcl_crf::apps::countOption (argc, argv, "--start", args.start, 0) ||
      !pcl_crf::apps::countOption (argc, argv, "--max-pairs", args.max_pairs, 0) ||
      !pcl_crf::apps::parseLogArguments (argc, argv, args.log_args))
    return false;
  if (!args.save_pairs.empty ())
    args.log_args.pairs.label_points = true;
  return true;
}

std::unique_ptr<pcl_crf::EvaluationMethod>
prepareMethod (const RunArguments& args)
{
  // K-Means and CRF-Clustering alone cluster a pair's true associations (the joint
  // paper's oracle baselines): a log's pairs carry them only when labelled.
  if ((args.method == "kmeans" || args.method == "crf-t") && !args.log_args.pairs.label_points)
    throw std::invalid_argument ("method '" + args.method + "' clusters the pairs' true associations: give --label "
                                 "(the log needs reference poses), or a method that matches the scans itself");
  auto method = pcl_crf::createEvaluationMethod (args.method);
  if (!method->isLearned ())
    return method;
  if (args.model_dir.empty ())
    throw std::invalid_argument ("method '" + args.method + "' learns its weights: give --models DIR "
                                 "(data/models holds the shipped models, installed in <prefix>/share/pcl_crf/models)");
  method->loadModel ((fs::path (args.model_dir) / (args.method + ".model")).string ());
  return method;
}

/** A progress bar on a terminal, a line every 10 % otherwise. */
class ProgressBar
{
public:
  ProgressBar (bool quiet, std::size_t total) : quiet_ (quiet), total_ (total), terminal_ (isatty (STDERR_FILENO)) {}

  void
  update (std::size_t done, double seconds)
  {
    if (quiet_ || total_ == 0)
      return;
    std::fflush (stdout);
    const double rate = seconds > 0.0 ? done / seconds : 0.0;
    if (terminal_) {
      const int width = 30, filled = static_cast<int> (width * done / total_);
      std::fprintf (stderr, "\r[%s%s] %zu/%zu pairs, %.1f pairs/s ", std::string (filled, '#').c_str (),
                    std::string (width - filled, '.').c_str (), done, total_, rate);
      if (done == total_)
        std::fprintf (stderr, "\n");
    }
    else if (done == total_ || (done * 10 / total_) != ((done - 1) * 10 / total_))
      std::fprintf (stderr, "%zu/%zu pairs, %.1f pairs/s\n", done, total_, rate);
    std::fflush (stderr);
  }

private:
  bool quiet_;
  std::size_t total_;
  bool terminal_;
};

struct ErrorStats
{
  std::vector<double> translation, rotation;

  void
  add (const pcl_crf::MotionError& e)
  {
    translation.push_back (e.translation);
    rotation.push_back (e.rotation);
  }
  static double
  mean (const std::vector<double>& v)
  {
    double sum = 0.0;
    for (double x : v)
      sum += x;
    return v.empty () ? std::numeric_limits<double>::quiet_NaN () : sum / v.size ();
  }
  /** the middle value, or the mean of the two middle values of an even count. */
  static double
  median (std::vector<double> v)
  {
    if (v.empty ())
      return std::numeric_limits<double>::quiet_NaN ();
    const auto middle = v.begin () + static_cast<std::ptrdiff_t> (v.size () / 2);
    std::nth_element (v.begin (), middle, v.end ());
    if (v.size () % 2 == 1)
      return *middle;
    return 0.5 * (*middle + *std::max_element (v.begin (), middle));
  }
};

/** true when every odometry step from scan k to scan k + step is known. */
bool
odometryCovers (const pcl_crf::LaserLog& log, std::size_t k, std::size_t step)
{
  for (std::size_t j = k + 1; j <= k + step; ++j)
    if (!log.scans[j].has_odometry_step)
      return false;
  return true;
}

std::string
csvMotion (const pcl_crf::Rigid2d& T)
{
  const Eigen::Vector3d v = pcl_crf::toXYTheta (T);
  char text[96];
  std::snprintf (text, sizeof (text), "%.6f,%.6f,%.6f", v.x (), v.y (), v.z ());
  return text;
}

void
writeCsvHeader (std::ostream& csv)
{
  csv << "pair,source_scan,target_scan,source_stamp,target_stamp,source_points,target_points,clusters,"
         "moving_clusters,est_x,est_y,est_theta,odom_x,odom_y,odom_theta,ref_x,ref_y,ref_theta,"
         "translation_error,rotation_error,odom_translation_error,odom_rotation_error,seconds\n";
}

/** Why none of the pairs run had a reference ego motion: the log has no reference poses,
 *  no pair has one at both of its scans (--start and --step choose the pairs, and a
 *  bag's pose track may not cover every scan), or the pairs that have were skipped. */
std::string
whyNoReference (const pcl_crf::LaserLog& log, const std::vector<std::size_t>& firsts, std::size_t step)
{
  if (!log.has_reference_poses)
    return "The log has no reference poses";
  std::size_t with_pose = 0, covered = 0;
  for (const auto& scan : log.scans)
    with_pose += scan.has_pose ? 1 : 0;
  for (const std::size_t k : firsts)
    covered += log.scans[k].has_pose && log.scans[k + step].has_pose ? 1 : 0;
  const auto count = [] (std::size_t n) { return std::to_string (n) + (n == 1 ? " pair" : " pairs"); };
  if (covered > 0)
    return "Every pair with reference poses at both scans was skipped (" + count (covered) +
           "; see the warnings above)";
  return "No pair has reference poses at both of its scans (" + count (firsts.size ()) + " run; the log has them for " +
         std::to_string (with_pose) + " of its " + std::to_string (log.scans.size ()) +
         " scans; --start and --step choose the pairs)";
}

void
printSummary (const RunArguments& args, std::size_t pairs, std::size_t skipped, double predict_seconds,
              double wall_seconds, const ErrorStats& method, const ErrorStats& odometry,
              const std::string& why_no_reference)
{
  print_highlight ("Ran ");
  print_value ("%s", args.method.c_str ());
  print_info (" on ");
  print_value ("%zu", pairs);
  print_info (" pairs of %s in ", args.log.c_str ());
  print_value ("%.2f", wall_seconds);
  print_info (" s (");
  print_value ("%.1f", predict_seconds > 0.0 ? pairs / predict_seconds : 0.0);
  print_info (" pairs/s in the method, ");
  print_value ("%.1f", wall_seconds > 0.0 ? pairs / wall_seconds : 0.0);
  print_info (" pairs/s overall)\n");
  if (skipped > 0)
    print_warn ("Skipped %zu pairs (see the warnings above).\n", skipped);
  if (method.translation.empty ()) {
    print_info ("%s: no ego-motion error to report.\n", why_no_reference.c_str ());
    return;
  }
  const auto row = [] (const char* name, const ErrorStats& s) {
    print_info ("  %-10s translation error mean ", name);
    print_value ("%.4f", ErrorStats::mean (s.translation));
    print_info (" m, median ");
    print_value ("%.4f", ErrorStats::median (s.translation));
    print_info (" m; rotation error mean ");
    print_value ("%.5f", ErrorStats::mean (s.rotation));
    print_info (" rad, median ");
    print_value ("%.5f", ErrorStats::median (s.rotation));
    print_info (" rad\n");
  };
  print_highlight (args.stationary ? "Ego motion vs the identity (" : "Ego motion vs the reference poses (");
  print_value ("%zu", method.translation.size ());
  print_info (" pairs):\n");
  row (args.method.c_str (), method);
  if (!odometry.translation.empty ())
    row ("odometry", odometry);
}

int
run (const RunArguments& args)
{
  pcl::console::TicToc wall;
  wall.tic ();
  pcl_crf::apps::warnAboutOptionsTheLogIgnores (args.log_args, pcl_crf::detectLaserLogFormat (args.log));
  const pcl_crf::LaserLog log = pcl_crf::readLaserLog (args.log, args.log_args.read);
  if (!args.quiet) {
    print_highlight ("Read ");
    print_value ("%zu", log.scans.size ());
    print_info (" scans from %s in ", args.log.c_str ());
    print_value ("%.0f", wall.toc ());
    print_info (" ms (reference poses: %s, odometry: %s)\n", log.has_reference_poses ? "yes" : "no",
                log.has_odometry ? "yes" : "no");
  }
  pcl_crf::apps::printLogWarnings (log);
  const std::size_t unordered = pcl_crf::countStampsNotAfterTheLast (log);
  if (unordered > 0)
    print_warn ("%zu of the %zu scans are stamped at or before the scan before them: the pairs they end have no "
                "known time interval, so the search for moving objects is not bounded by it.\n",
                unordered, log.scans.size ());
  if (args.stationary && log.has_reference_poses)
    throw std::invalid_argument ("--stationary makes the identity every pair's reference ego motion, but " + args.log +
                                 " has reference poses: give one or the other");
  const pcl_crf::LogPairOptions& pair_options = args.log_args.pairs;
  if (pair_options.label_points && !log.has_reference_poses)
    throw std::invalid_argument ("--label and --save-pairs need reference poses, and " + args.log +
                                 " has none (give --pose-topic for a bag)");
  const std::size_t step = pair_options.step, start = static_cast<std::size_t> (args.start);
  std::vector<std::size_t> firsts;
  for (std::size_t k = start; k + step < log.scans.size (); k += step)
    if (args.max_pairs == 0 || firsts.size () < static_cast<std::size_t> (args.max_pairs))
      firsts.push_back (k);
  if (firsts.empty ())
    throw std::invalid_argument ("no scan pair: the log has " + std::to_string (log.scans.size ()) +
                                 " scans, --start is " + std::to_string (start) + " and --step " +
                                 std::to_string (step));
  if (!args.save_pairs.empty () && fs::exists (args.save_pairs) &&
      (!fs::is_directory (args.save_pairs) || !fs::is_empty (args.save_pairs)))
    throw std::invalid_argument ("--save-pairs " + args.save_pairs + " is not a new or empty folder: pcl_crf_eval "
                                 "would score the pairs already there with this log's");
  auto method = prepareMethod (args);

  std::ofstream csv;
  std::string csv_path = args.csv;
  if (!args.output.empty ()) {
    fs::create_directories (args.output);
    if (csv_path.empty ())
      csv_path = (fs::path (args.output) / "ego_motion.csv").string ();
  }
  if (!csv_path.empty ()) {
    csv.open (csv_path);
    if (!csv)
      throw std::runtime_error ("cannot write " + csv_path);
    writeCsvHeader (csv);
  }
  ProgressBar progress (args.quiet, firsts.size ());
  ErrorStats method_errors, odometry_errors;
  double predict_seconds = 0.0;
  std::size_t done = 0, skipped = 0;
  for (const std::size_t k : firsts) {
    pcl_crf::ScanPair pair;
    pcl_crf::Prediction prediction;
    try {
      pair = pcl_crf::makeLogPair (log, k, pair_options);
      pcl::console::TicToc timer;
      timer.tic ();
      prediction = method->predict (pair);
      prediction.seconds = timer.toc () / 1000.0;
    }
    catch (const std::exception& error) {
      print_warn ("\nPair %zu-%zu skipped: %s\n", k, k + step, error.what ());
      ++skipped;
      progress.update (++done, predict_seconds);
      continue;
    }
    predict_seconds += prediction.seconds;
    pcl_crf::Rigid2d reference = pcl_crf::Rigid2d::Identity ();
    const bool has_reference = args.stationary || pcl_crf::referenceEgoMotion (pair, reference);
    pcl_crf::MotionError error, odometry_error;
    if (has_reference) {
      error = pcl_crf::computeMotionError (prediction.T_source_target, reference);
      method_errors.add (error);
      if (odometryCovers (log, k, step)) {
        odometry_error = pcl_crf::computeMotionError (pair.odometry.T_source_target, reference);
        odometry_errors.add (odometry_error);
      }
    }
    if (!args.output.empty ())
      pcl_crf::savePrediction (pair, prediction, args.method, (fs::path (args.output) / pair.name).string ());
    if (csv.is_open ()) {
      int moving = 0;
      for (std::size_t c = 0; c < prediction.cluster_motions.size (); ++c)
        moving += static_cast<int> (c) != prediction.static_cluster ? 1 : 0;
      csv << pair.name << ',' << k << ',' << k + step << ',' << std::fixed;
      csv.precision (6);
      csv << log.scans[k].stamp << ',' << log.scans[k + step].stamp << ',' << pair.source.cols () << ','
          << pair.target.cols () << ',' << prediction.cluster_motions.size () << ',' << moving << ','
          << csvMotion (prediction.T_source_target) << ',' << csvMotion (pair.odometry.T_source_target) << ',';
      if (has_reference) {
        csv << csvMotion (reference) << ',' << error.translation << ',' << error.rotation << ',';
        if (odometryCovers (log, k, step))
          csv << odometry_error.translation << ',' << odometry_error.rotation;
        else
          csv << ',';
      }
      else
        csv << ",,,,,,";
      csv << ',' << prediction.seconds << '\n';
    }
    if (!args.save_pairs.empty ())
      pcl_crf::saveScanPair (pair, (fs::path (args.save_pairs) / pair.name).string ());
    progress.update (++done, predict_seconds);
  }
  if (done == skipped)
    throw std::runtime_error ("every pair failed (see the warnings above)");
  printSummary (args, done - skipped, skipped, predict_seconds, wall.toc () / 1000.0, method_errors, odometry_errors,
                whyNoReference (log, firsts, step));
  if (!args.output.empty () && !args.quiet)
    print_info ("Wrote %zu predictions to %s\n", done - skipped, args.output.c_str ());
  if (!csv_path.empty () && !args.quiet)
    print_info ("Wrote the per-pair ego motion to %s\n", csv_path.c_str ());
  return 0;
}

}  // namespace

int
main (int argc, char** argv)
{
  if (const int code = pcl_crf::apps::helpExitCode (argc, argv, printHelp); code >= 0)
    return code;
  if (find_switch (argc, argv, "--list-methods")) {
    for (const auto& name : pcl_crf::availableEvaluationMethods ())
      std::cout << name << '\n';
    return 0;
  }
  RunArguments args;
  if (!parseArguments (argc, argv, args))
    return 1;
  return pcl_crf::apps::exitCodeOf ([&] { return run (args); });
}
