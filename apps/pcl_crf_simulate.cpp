// pcl_crf_simulate: writes a dataset of simulated, labelled 2D laser scan pairs
// of urban driving scenes (see data/SIMULATOR.md).
#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app_common.h"

using namespace pcl::console;
namespace sim = pcl_crf::simulation;

namespace {

constexpr double kPi = 3.14159265358979323846;

/** Thrown for a bad command line; main prints it with the usage hint. */
struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/** The options as typed, plus the values that are not part of SimulatorConfig. */
struct Options
{
  std::string output_dir;
  long long pairs = 10;
  long long first = 0;
  bool quiet = false;
  sim::SimulatorConfig config;
};

const std::vector<std::string> kValueOptions{
    "-o",          "--pairs",        "--first",      "--seed",     "--beams",   "--fov",
    "--range",     "--noise",        "--dropout",    "--speed",    "--yaw-rate", "--moving",
    "--object-speed", "--scene",     "--spacing",    "--travel",   "--scan-rate", "--odom-noise",
    "--legs",      "--name-prefix"};
const std::vector<std::string> kSwitches{"-h", "--help", "-q", "--no-return-points"};

std::string
fmt (double value)
{
  char text[64];
  std::snprintf (text, sizeof (text), "%g", value);
  return text;
}

void
printHelp (const char* program)
{
  const sim::SimulatorConfig d;
  print_error ("Syntax is: %s -o DIR [options]\n", program);
  print_info ("Simulates labelled 2D laser scan pairs of urban driving scenes and writes them\n"
              "as a pcl_crf dataset: DIR/<prefix>NNNN/{source.pcd,target.pcd,pair.txt} and a\n"
              "manifest DIR/<prefix>manifest.txt. The same options give byte-identical files.\n\n");
  auto line = [] (const char* option, const std::string& text) { print_info ("  %-22s %s\n", option, text.c_str ()); };
  line ("-o DIR", "output dataset folder (required; created if missing)");
  line ("--pairs N", "number of pairs, N > 0 (default 10)");
  line ("--first K", "index of the first pair (default 0); pair k only depends on (seed, k)");
  line ("--seed S", "master random seed, integer >= 0 (default " + std::to_string (d.seed) + ")");
  line ("--beams B", "laser beams per scan, 2 <= B <= " + std::to_string (sim::kMaxSimulatedBeams) + " (default " +
                         std::to_string (d.laser.beam_count) + ")");
  line ("--fov DEG", "field of view centred forward, (0, 360] degrees (default 180)");
  line ("--range M", "maximum range in metres, (0, " + fmt (sim::kMaxSimulatedRange) + "] (default " +
                         fmt (d.laser.range_max) + ")");
  line ("--noise M", "Gaussian range noise std in metres, >= 0 (default " + fmt (d.laser.range_noise) + ")");
  line ("--dropout P", "probability a beam returns nothing, in [0, 1) (default " + fmt (d.laser.dropout_probability) + ")");
  line ("--speed M/S", "ego speed in m/s, >= 0 (default " + fmt (d.ego_speed) + ")");
  line ("--yaw-rate RAD/S", "ego yaw rate in rad/s (default " + fmt (d.ego_yaw_rate) + ")");
  line ("--moving N", "moving objects per pair, 0 <= N <= 100; -1 = random 1..4 (default -1)");
  line ("--object-speed M/S", "speed of every moving object in m/s, in [" + fmt (sim::kMinSimulatedObjectSpeed) + ", " +
                                  fmt (sim::kMaxSimulatedObjectSpeed) + "]; -1 = drawn per kind (default -1)");
  line ("--scene TYPE", "mixed|outline|crossing|overtaking|opposite|pedestrians|static (default mixed)");
  line ("--spacing MODE", "travel (ego travels --travel metres) | consecutive (1/--scan-rate s) (default travel)");
  line ("--travel MIN,MAX", "ego travel between the scans in metres for travel spacing, 0 < MIN <= MAX <= " +
                                fmt (sim::kMaxSimulatedTravel) + ", MIN / --speed >= " +
                                fmt (sim::kMinSimulatedScanInterval) + " s (default " + fmt (d.travel_min) + "," +
                                fmt (d.travel_max) + ")");
  line ("--scan-rate HZ", "scan rate in Hz for consecutive spacing, in [" + fmt (sim::kMinSimulatedScanRate) +
                              ", " + fmt (1.0 / sim::kMinSimulatedScanInterval) + "], with --speed / HZ <= " + fmt (sim::kMaxSimulatedTravel) + " m (default " +
                              fmt (d.scan_rate) + ")");
  line ("--odom-noise SX,SY,ST", "odometry noise std: dx [m], dy [m], dtheta [rad] (default " +
                                     fmt (d.odometry_noise[0]) + "," + fmt (d.odometry_noise[1]) + "," +
                                     fmt (d.odometry_noise[2]) + ")");
  line ("--legs P", "fraction of pedestrians simulated as two swinging legs, [0, 1] (default " +
                        fmt (d.traffic.legged_pedestrian_fraction) + ")");
  line ("--name-prefix TEXT", "pair folder name prefix (default \"" + d.name_prefix + "\")");
  line ("--no-return-points", "write beams without a return as points at the maximum range (static world, no "
                              "match), as a converter that keeps them would; the dataset format leaves them out");
  line ("-q", "quiet: no per-pair progress");
  line ("-h, --help", "this help");
}

// ---------------------------------------------------------------- strict number parsing
double
toDouble (const std::string& option, const std::string& text)
{
  const std::optional<double> value = pcl_crf::parseDecimal (text);
  if (!value)
    throw UsageError (option + " expects a decimal number, got '" + text + "'");
  return *value;
}

long long
toInteger (const std::string& option, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll (text.c_str (), &end, 10);
  if (text.empty () || end != text.c_str () + text.size () || errno == ERANGE)
    throw UsageError (option + " expects an integer, got '" + text + "'");
  return value;
}

std::vector<double>
toList (const std::string& option, const std::string& text, std::size_t count)
{
  std::vector<double> values;
  std::stringstream in (text);
  std::string item;
  while (std::getline (in, item, ','))
    values.push_back (toDouble (option, item));
  if (values.size () != count)
    throw UsageError (option + " expects " + std::to_string (count) + " comma-separated numbers, got '" + text + "'");
  return values;
}

/** The value of a valued option when present. */
bool
value (int argc, char** argv, const std::string& option, std::string& text)
{
  return parse_argument (argc, argv, option.c_str (), text) >= 0;
}

Options
parseOptions (int argc, char** argv)
{
  // Every argument must be a known option (or the value of one), each given once
  // (parse_argument would read the first of two).
  std::set<std::string> given;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!given.insert (arg).second)  // every argument here is an option: values are skipped below
      throw UsageError ("option " + arg + " is given twice");
    if (std::find (kValueOptions.begin (), kValueOptions.end (), arg) != kValueOptions.end ()) {
      if (i + 1 >= argc)
        throw UsageError (arg + " needs a value");
      ++i;
    }
    else if (std::find (kSwitches.begin (), kSwitches.end (), arg) == kSwitches.end ())
      throw UsageError ("unknown option or stray argument '" + arg + "'");
  }

  Options o;
  sim::SimulatorConfig& c = o.config;
  std::string text;
  if (!value (argc, argv, "-o", o.output_dir) || o.output_dir.empty ())
    throw UsageError ("the output folder -o DIR is required");
  if (value (argc, argv, "--pairs", text))
    o.pairs = toInteger ("--pairs", text);
  if (o.pairs <= 0)
    throw UsageError ("--pairs must be positive, got " + std::to_string (o.pairs));
  if (value (argc, argv, "--first", text))
    o.first = toInteger ("--first", text);
  if (o.first < 0)
    throw UsageError ("--first must not be negative");
  if (value (argc, argv, "--seed", text)) {
    const long long seed = toInteger ("--seed", text);
    if (seed < 0)
      throw UsageError ("--seed must not be negative");
    c.seed = static_cast<std::uint64_t> (seed);
  }
  if (value (argc, argv, "--beams", text)) {
    const long long beams = toInteger ("--beams", text);
    if (beams <= 1 || beams > sim::kMaxSimulatedBeams)
      throw UsageError ("--beams must be in 2.." + std::to_string (sim::kMaxSimulatedBeams) + ", got " + text);
    c.laser.beam_count = static_cast<int> (beams);
  }
  if (value (argc, argv, "--fov", text))
    c.laser.field_of_view = toDouble ("--fov", text) * kPi / 180.0;
  if (value (argc, argv, "--range", text))
    c.laser.range_max = toDouble ("--range", text);
  if (value (argc, argv, "--noise", text))
    c.laser.range_noise = toDouble ("--noise", text);
  if (value (argc, argv, "--dropout", text))
    c.laser.dropout_probability = toDouble ("--dropout", text);
  if (value (argc, argv, "--speed", text))
    c.ego_speed = toDouble ("--speed", text);
  if (value (argc, argv, "--yaw-rate", text))
    c.ego_yaw_rate = toDouble ("--yaw-rate", text);
  if (value (argc, argv, "--moving", text)) {
    const long long moving = toInteger ("--moving", text);
    if (moving < -1 || moving > 100)
      throw UsageError ("--moving must be in 0..100, or -1 for a random count in 1..4");
    c.moving_count = static_cast<int> (moving);
  }
  if (value (argc, argv, "--object-speed", text))
    c.traffic.object_speed = toDouble ("--object-speed", text);
  if (value (argc, argv, "--scene", text) && !sim::parseSceneType (text, c.scene))
    throw UsageError ("unknown --scene '" + text + "' (mixed, outline, crossing, overtaking, opposite, pedestrians, static)");
  if (value (argc, argv, "--spacing", text)) {
    if (text == "travel")
      c.spacing = sim::ScanSpacing::Travel;
    else if (text == "consecutive")
      c.spacing = sim::ScanSpacing::Consecutive;
    else
      throw UsageError ("--spacing must be 'travel' or 'consecutive', got '" + text + "'");
  }
  if (value (argc, argv, "--travel", text)) {
    const auto travel = toList ("--travel", text, 2);
    c.travel_min = travel[0];
    c.travel_max = travel[1];
  }
  if (value (argc, argv, "--scan-rate", text))
    c.scan_rate = toDouble ("--scan-rate", text);
  if (value (argc, argv, "--odom-noise", text)) {
    const auto noise = toList ("--odom-noise", text, 3);
    c.odometry_noise = Eigen::Vector3d (noise[0], noise[1], noise[2]);
  }
  if (value (argc, argv, "--legs", text))
    c.traffic.legged_pedestrian_fraction = toDouble ("--legs", text);
  value (argc, argv, "--name-prefix", c.name_prefix);
  o.quiet = find_switch (argc, argv, "-q");
  o.config.laser.no_return_points = find_switch (argc, argv, "--no-return-points");
  try {
    sim::validateSimulatorConfig (c);
  }
  catch (const sim::SimulationError& e) {
    throw UsageError (e.what ());
  }
  return o;
}

// ---------------------------------------------------------------- output
std::string
describeConfig (const Options& o)
{
  const sim::SimulatorConfig& c = o.config;
  std::ostringstream out;
  out << "seed " << c.seed << " first " << o.first << " pairs " << o.pairs << " beams " << c.laser.beam_count
      << " fov_deg " << fmt (c.laser.field_of_view * 180.0 / kPi) << " range " << fmt (c.laser.range_max)
      << " noise " << fmt (c.laser.range_noise) << " dropout " << fmt (c.laser.dropout_probability) << " speed "
      << fmt (c.ego_speed) << " yaw_rate " << fmt (c.ego_yaw_rate) << " scene " << sim::sceneTypeName (c.scene)
      << " moving " << c.moving_count << " object_speed " << fmt (c.traffic.object_speed) << " spacing "
      << (c.spacing == sim::ScanSpacing::Travel ? "travel" : "consecutive") << " travel " << fmt (c.travel_min)
      << "," << fmt (c.travel_max) << " scan_rate " << fmt (c.scan_rate) << " odom_noise "
      << fmt (c.odometry_noise[0]) << "," << fmt (c.odometry_noise[1]) << "," << fmt (c.odometry_noise[2])
      << " legs " << fmt (c.traffic.legged_pedestrian_fraction) << " name_prefix \"" << c.name_prefix << "\"";
  if (c.laser.no_return_points)  // only when set: the default manifests stay as they were
    out << " no_return_points 1";
  return out.str ();
}

void
writeManifest (const Options& o, const std::vector<sim::PairSummary>& summaries)
{
  const std::string path =
      (std::filesystem::path (o.output_dir) / (o.config.name_prefix + "manifest.txt")).string ();
  std::ofstream file (path);
  file << "# pcl_crf_simulate manifest (one line per pair folder written)\n"
       << "# config " << describeConfig (o) << "\n"
       << "# name scene duration_s ego_travel_m moving_placed moving_visible source_points target_points "
          "matched_source_points moving_kinds\n";
  char text[256];
  for (const auto& s : summaries) {
    std::string kinds;
    for (const auto& kind : s.moving_kinds)
      kinds += (kinds.empty () ? "" : ",") + kind;
    std::snprintf (text, sizeof (text), "%s %s %.6g %.6g %d %d %d %d %d %s\n", s.name.c_str (),
                   sim::sceneTypeName (s.scene).c_str (), s.duration, s.ego_travel, s.moving_placed,
                   s.moving_visible, s.source_points, s.target_points, s.matched, kinds.empty () ? "-" : kinds.c_str ());
    file << text;
  }
  if (!file)
    throw pcl_crf::DatasetError (path + ": cannot write the manifest");
}

int
compute (const Options& o)
{
  const sim::ScanPairSimulator simulator (o.config);
  TicToc total;
  total.tic ();
  std::vector<sim::PairSummary> summaries;
  int moving = 0, source_points = 0, matched = 0;
  for (long long k = o.first; k < o.first + o.pairs; ++k) {
    TicToc timer;
    timer.tic ();
    sim::PairSummary summary;
    const pcl_crf::ScanPair pair = simulator.simulate (static_cast<std::size_t> (k), &summary);
    pcl_crf::saveScanPair (pair, (std::filesystem::path (o.output_dir) / pair.name).string ());
    if (!o.quiet) {
      print_highlight ("Wrote %s ", pair.name.c_str ());
      print_info ("[%s, ", sim::sceneTypeName (summary.scene).c_str ());
      print_value ("%d", summary.moving_visible);
      print_info (" moving, ");
      print_value ("%d/%d", summary.source_points, summary.target_points);
      print_info (" points, ");
      print_value ("%d", summary.matched);
      print_info (" matched] in ");
      print_value ("%g", timer.toc ());
      print_info (" ms\n");
    }
    moving += summary.moving_visible;
    source_points += summary.source_points;
    matched += summary.matched;
    summaries.push_back (summary);
  }
  writeManifest (o, summaries);
  print_highlight ("Simulated ");
  print_value ("%lld", o.pairs);
  print_info (" pairs into %s: ", o.output_dir.c_str ());
  print_value ("%d", moving);
  print_info (" moving objects, ");
  print_value ("%.1f%%", source_points > 0 ? 100.0 * (source_points - matched) / source_points : 0.0);
  print_info (" source points without a true match; ");
  print_value ("%g", total.toc ());
  print_info (" ms\n");
  return 0;
}

}  // namespace

int
main (int argc, char** argv)
{
  if (const int code = pcl_crf::apps::helpExitCode (argc, argv, printHelp); code >= 0)
    return code;
  try {
    return compute (parseOptions (argc, argv));
  }
  catch (const UsageError& e) {
    print_error ("[pcl_crf_simulate] %s (see %s -h)\n", e.what (), argv[0]);
  }
  catch (const std::exception& e) {
    print_error ("[pcl_crf_simulate] %s\n", e.what ());
  }
  return 1;
}
