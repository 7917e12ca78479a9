// Tests of the pcl_crf_simulate command-line tool and of the shipped dataset.
// They run the built program, found through PCL_CRF_APPS_DIR (set by ctest).
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
namespace sim = pcl_crf::simulation;

/** The simulate program, or "" when PCL_CRF_APPS_DIR is not set. */
std::string
simulateProgram ()
{
  const char* dir = std::getenv ("PCL_CRF_APPS_DIR");
  return dir ? (fs::path (dir) / "pcl_crf_simulate").string () : std::string ();
}

#define REQUIRE_SIMULATE_PROGRAM()                                                                  \
  const std::string program = simulateProgram ();                                                   \
  if (program.empty ())                                                                             \
    GTEST_SKIP () << "PCL_CRF_APPS_DIR is not set (run through ctest)";                            \
  ASSERT_TRUE (fs::exists (program)) << program

std::string
quote (const std::string& text)
{
  std::string out = "'";
  for (char c : text)
    out += c == '\'' ? std::string ("'\\''") : std::string (1, c);
  return out + "'";
}

/** Runs a shell command; returns its exit code and fills \a output with stdout + stderr. */
int
run (const std::string& command, std::string* output = nullptr)
{
  const fs::path log = fs::temp_directory_path () / ("pcl_crf_tool_log_" + std::to_string (::getpid ()));
  const int status = std::system ((command + " > " + quote (log.string ()) + " 2>&1").c_str ());
  if (output) {
    std::ifstream in (log);
    std::stringstream text;
    text << in.rdbuf ();
    *output = text.str ();
  }
  fs::remove (log);
  return WIFEXITED (status) ? WEXITSTATUS (status) : -1;
}

fs::path
freshTempDir (const std::string& name)
{
  const fs::path dir = fs::temp_directory_path () / ("pcl_crf_" + name + "_" + std::to_string (::getpid ()));
  fs::remove_all (dir);
  fs::create_directories (dir);
  return dir;
}

std::string
readBytes (const fs::path& path)
{
  std::ifstream in (path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf ();
  return bytes.str ();
}

/** Relative paths of every regular file under \a root. */
std::set<std::string>
filesUnder (const fs::path& root)
{
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator (root))
    if (entry.is_regular_file ())
      files.insert (fs::relative (entry.path (), root).generic_string ());
  return files;
}

TEST (SimulatorTool, HelpListsEveryOption)
{
  REQUIRE_SIMULATE_PROGRAM ();
  std::string help;
  EXPECT_EQ (run (quote (program) + " -h", &help), 0);
  for (const char* option : {"-o DIR", "--pairs", "--first", "--seed", "--beams", "--fov", "--range", "--noise",
                             "--dropout", "--speed", "--yaw-rate", "--moving", "--object-speed", "--scene",
                             "--spacing", "--travel", "--scan-rate", "--odom-noise", "--legs", "--name-prefix"})
    EXPECT_NE (help.find (option), std::string::npos) << option;
  EXPECT_NE (help.find ("default 361"), std::string::npos);
  EXPECT_NE (help.find ("default 0.01"), std::string::npos);
}

TEST (SimulatorTool, RejectsBadOptions)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path dir = freshTempDir ("sim_bad_options");
  const std::string base = quote (program) + " -o " + quote ((dir / "out").string ()) + " ";
  for (const char* bad : {"--pairs 0", "--pairs -3", "--pairs abc", "--beams 1", "--beams 0", "--noise -0.1",
                          "--dropout 1", "--dropout -0.5", "--dropout 2", "--scene highway", "--spacing sometimes",
                          "--fov 0", "--range -1", "--speed 0", "--odom-noise 0.1,0.1", "--odom-noise 0.1,-1,0.1",
                          "--travel 4,2", "--scene static --moving 2", "--seed -1", "--frobnicate 3", "--pairs"}) {
    std::string output;
    EXPECT_NE (run (base + bad, &output), 0) << bad;
    EXPECT_NE (output.find ("pcl_crf_simulate"), std::string::npos) << bad << ": " << output;
  }
  std::string output;
  // An option given twice (parse_argument read the first: "--pairs 2 --pairs 3" wrote 2).
  EXPECT_NE (run (base + "--pairs 2 --seed 2 --pairs 3", &output), 0);
  EXPECT_NE (output.find ("option --pairs is given twice"), std::string::npos) << output;
  EXPECT_NE (run (quote (program) + " --pairs 2", &output), 0);  // no -o
  EXPECT_NE (output.find ("-o DIR"), std::string::npos);
  EXPECT_FALSE (fs::exists (dir / "out"));
  fs::remove_all (dir);
}

TEST (SimulatorTool, RejectsSizesThatWouldHangIt)
{
  // These used to run for minutes with memory growing (or quadratic time for --beams).
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path dir = freshTempDir ("sim_huge_options");
  const std::string base = quote (program) + " -o " + quote ((dir / "out").string ()) + " ";
  const std::pair<const char*, const char*> cases[] = {
      {"--range 1e9", "maximum range (--range) must be in (0, 1000] m, got 1e+09"},
      {"--travel 1e9,1e9", "MIN <= MAX <= 100 m, got 1e+09,1e+09"},
      {"--spacing consecutive --scan-rate 1e-300", "scan rate (--scan-rate) must be in [0.1, 1000] Hz, got 1e-300"},
      {"--spacing consecutive --speed 1e9", "the ego would travel 1.33333e+07 m between the scans"},
      {"--beams 20001", "--beams must be in 2..20000, got 20001"},
      // Moving objects labelled with the static world's motion (scans 1e-300 s apart).
      {"--speed 1e300", "the shortest time between the scans, travel / speed (--travel MIN / --speed), must be at "
                        "least 0.001 s, got 2e-300 s"},
      {"--object-speed 0", "object speed (--object-speed) must be in [0.01, 100] m/s"}};
  for (const auto& [bad, message] : cases) {
    std::string output;
    EXPECT_EQ (run ("timeout 60 " + base + bad, &output), 1) << bad;
    EXPECT_NE (output.find (message), std::string::npos) << bad << ": " << output;
  }
  EXPECT_FALSE (fs::exists (dir / "out"));
  std::string help;
  run (quote (program) + " -h", &help);
  EXPECT_NE (help.find ("2 <= B <= 20000"), std::string::npos) << help;
  EXPECT_NE (help.find ("(0, 1000]"), std::string::npos) << help;
  fs::remove_all (dir);
}

TEST (SimulatorTool, WritesTheLibrarysPairs)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path dir = freshTempDir ("sim_tool_output");
  ASSERT_EQ (run (quote (program) + " -q -o " + quote (dir.string ()) +
                  " --pairs 2 --first 3 --seed 5 --beams 181 --scene crossing --moving 2 --name-prefix run_"),
             0);
  EXPECT_TRUE (fs::exists (dir / "run_manifest.txt"));
  const auto loaded = pcl_crf::loadDataset (dir.string ());
  ASSERT_EQ (loaded.size (), 2u);
  EXPECT_EQ (loaded[0].name, "run_0003");
  EXPECT_EQ (loaded[1].name, "run_0004");
  sim::SimulatorConfig config;
  config.seed = 5;
  config.laser.beam_count = 181;
  config.scene = sim::SceneType::Crossing;
  config.moving_count = 2;
  config.name_prefix = "run_";
  const pcl_crf::ScanPair expected = sim::ScanPairSimulator (config).simulate (4);
  EXPECT_EQ (loaded[1].source, expected.source);
  EXPECT_EQ (loaded[1].target, expected.target);
  EXPECT_EQ (loaded[1].source_match, expected.source_match);
  EXPECT_EQ (loaded[1].objects.size (), expected.objects.size ());
  fs::remove_all (dir);
}

TEST (SimulatorTool, RegeneratesShippedDatasetByteIdentically)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path shipped = fs::path (PCL_CRF_SOURCE_DIR) / "data" / "default";
  const fs::path script = fs::path (PCL_CRF_SOURCE_DIR) / "data" / "generate_default.sh";
  ASSERT_TRUE (fs::is_directory (shipped)) << shipped;
  const fs::path dir = freshTempDir ("sim_regenerate");
  std::string output;
  ASSERT_EQ (run ("bash " + quote (script.string ()) + " " + quote (program) + " " + quote (dir.string ()), &output), 0)
      << output;
  const std::set<std::string> expected = filesUnder (shipped), produced = filesUnder (dir);
  EXPECT_EQ (produced, expected);
  EXPECT_GE (expected.size (), 2u * (30u * 3u + 1u));
  for (const auto& file : expected) {
    if (produced.count (file)) {
      EXPECT_TRUE (readBytes (shipped / file) == readBytes (dir / file)) << file << " differs";
    }
  }
  // The shipped splits load and validate.
  EXPECT_EQ (pcl_crf::loadDataset ((shipped / "train").string ()).size (), 30u);
  EXPECT_EQ (pcl_crf::loadDataset ((shipped / "test").string ()).size (), 30u);
  fs::remove_all (dir);
}

TEST (SimulatorTool, GeneratesFreshSplitsFromSeeds)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path script = fs::path (PCL_CRF_SOURCE_DIR) / "data" / "generate_default.sh";
  const fs::path dir = freshTempDir ("sim_fresh_split");
  std::string output;
  ASSERT_EQ (run ("SPLITS='fresh:7' bash " + quote (script.string ()) + " " + quote (program) + " " + quote (dir.string ()),
                  &output),
             0)
      << output;
  EXPECT_FALSE (fs::exists (dir / "train"));  // only the named split
  const auto fresh = pcl_crf::loadDataset ((dir / "fresh").string ());
  ASSERT_EQ (fresh.size (), 30u);
  const auto shipped = pcl_crf::loadDataset ((fs::path (PCL_CRF_SOURCE_DIR) / "data" / "default" / "test").string ());
  EXPECT_NE (fresh[0].source, shipped[0].source);  // a new draw, not a copy
  EXPECT_TRUE (fresh[0].source.cols () > 0 && fresh[0].source.cols () <= 361);

  EXPECT_EQ (run ("SPLITS='fresh' bash " + quote (script.string ()) + " " + quote (program) + " " + quote (dir.string ()),
                  &output),
             1);
  EXPECT_NE (output.find ("split 'fresh' is not NAME:SEED"), std::string::npos) << output;
  fs::remove_all (dir);
}

TEST (SimulatorTool, GeneratesHokuyoLikeSplits)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const fs::path script = fs::path (PCL_CRF_SOURCE_DIR) / "data" / "generate_default.sh";
  const fs::path dir = freshTempDir ("sim_hokuyo_split");
  std::string output;
  ASSERT_EQ (run ("SPLITS='fine:7' BEAMS=1081 FOV=270 bash " + quote (script.string ()) + " " + quote (program) + " " +
                      quote (dir.string ()),
                  &output),
             0)
      << output;
  const auto fine = pcl_crf::loadDataset ((dir / "fine").string ());
  ASSERT_EQ (fine.size (), 30u);
  EXPECT_EQ (fine[0].sensor.beam_count, 1081);
  EXPECT_NEAR (fine[0].sensor.angle_increment, 270.0 / 1080.0 * M_PI / 180.0, 1e-12);  // 0.25°
  EXPECT_GT (fine[0].source.cols (), 361);

  EXPECT_EQ (run ("SPLITS='fine:7' BEAMS=many bash " + quote (script.string ()) + " " + quote (program) + " " +
                      quote (dir.string ()),
                  &output),
             1);
  EXPECT_NE (output.find ("BEAMS and FOV must be positive integers, got 'many'"), std::string::npos) << output;
  fs::remove_all (dir);
}

/** The part of the script's output from "## <heading>" to the next heading (or the end). */
std::string
section (const std::string& output, const std::string& heading)
{
  const std::size_t begin = output.find ("## " + heading);
  if (begin == std::string::npos)
    return "";
  return output.substr (begin, output.find ("## ", begin + 3) - begin);
}

/** The number in a markdown table row "| name | a | b | ..." at column \a column (1 = a). */
double
tableValue (const std::string& table, const std::string& name, int column)
{
  std::istringstream lines (table);
  for (std::string line; std::getline (lines, line);) {
    if (line.rfind ("| " + name + " |", 0) != 0)
      continue;
    std::istringstream cells (line.substr (line.find ('|', 1) + 1));
    std::string cell;
    for (int c = 0; c < column; ++c)
      std::getline (cells, cell, '|');
    return std::stod (cell);
  }
  return -1.0;
}

TEST (HeldoutScript, ReportsWhatEvalMeasuresPerSeedAndPooled)
{
  REQUIRE_SIMULATE_PROGRAM ();
  const std::string apps = fs::path (program).parent_path ().string ();
  const fs::path out = freshTempDir ("heldout");
  const std::string script = (fs::path (PCL_CRF_SOURCE_DIR) / "scripts" / "heldout_table.sh").string ();
  std::string table;
  ASSERT_EQ (run ("PCL_CRF_BIN=" + quote (apps) + " SEEDS='7 8' METHODS=crf-matching OUT=" + quote (out.string ()) +
                      " bash " + quote (script),
                  &table),
             0)
      << table;
  EXPECT_NE (table.find ("## seed_7 (30 pairs)"), std::string::npos) << table;
  EXPECT_NE (table.find ("## pooled (60 pairs)"), std::string::npos) << table;
  // The seed_7 row is pcl_crf_eval's own number on that split.
  std::string eval;
  ASSERT_EQ (run (quote (apps + "/pcl_crf_eval") + " " + quote ((out / "seed_7").string ()) +
                      " --method crf-matching --models " +
                      quote ((fs::path (PCL_CRF_SOURCE_DIR) / "data" / "models").string ()) + " -q --format csv",
                  &eval),
             0)
      << eval;
  const std::string key = "crf-matching,association_accuracy,fraction,";
  const std::size_t at = eval.find (key);
  ASSERT_NE (at, std::string::npos) << eval;
  const double accuracy = std::stod (eval.substr (at + key.size ()));
  EXPECT_NEAR (tableValue (section (table, "seed_7"), "crf-matching", 1), accuracy, 0.0005);
  EXPECT_GT (accuracy, 0.5);
  const double pooled = tableValue (section (table, "pooled"), "crf-matching", 1);
  const double seed_8 = tableValue (section (table, "seed_8"), "crf-matching", 1);
  EXPECT_NEAR (pooled, (accuracy + seed_8) / 2.0, 0.001);  // 30 pairs each: the pooled mean is their mean
  std::string output;
  EXPECT_NE (run ("PCL_CRF_BIN=" + quote (apps) + " SEEDS=x bash " + quote (script), &output), 0);
  EXPECT_NE (output.find ("seed 'x' is not a non-negative integer"), std::string::npos) << output;
  fs::remove_all (out);
}

}  // namespace
