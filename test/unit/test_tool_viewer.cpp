// pcl_crf_viewer: the scene it draws (pcl_crf/visualization/pair_scene.h), its
// usage and errors, and a headless screenshot checked pixel by pixel.

#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/visualization/pair_scene.h>

#include "app_runner.h"
#include "synthetic_scene.h"

#include <boost/iostreams/copy.hpp>
#include <boost/iostreams/filter/zlib.hpp>
#include <boost/iostreams/filtering_stream.hpp>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
namespace vis = pcl_crf::visualization;
using pcl_crf::makeRigid2d;
using pcl_crf::test::runTool;

namespace {

/** The static room of synthetic_scene.h plus a 1 m x 0.5 m "car" (object 1)
 *  inside it that moves 0.8 m forward. */
pcl_crf::ScanPair
roomWithCar ()
{
  pcl_crf::ScanPair pair = pcl_crf::test::staticRoomPair (makeRigid2d (-0.3, 0.05, 0.02));
  const pcl_crf::Rigid2d world = pair.objects[0].T_target_source;
  const pcl_crf::Rigid2d car = makeRigid2d (0.8, 0.0, 0.0) * world;
  const Eigen::Matrix2Xd body = pcl_crf::test::roomOutline (1.0, 2.0, 0.5, 1.0, 0.1);
  const Eigen::Index n = pair.source.cols (), m = body.cols ();
  pair.source.conservativeResize (2, n + m);
  pair.source.rightCols (m) = body;
  pair.target.conservativeResize (2, n + m);
  pair.target.rightCols (m) = car * body;
  for (Eigen::Index i = 0; i < m; ++i) {
    pair.source_object.push_back (1);
    pair.target_object.push_back (1);
    pair.source_match.push_back (static_cast<int> (n + i));
  }
  pair.objects.push_back ({1, false, car, "car"});
  pair.sensor.beam_count = static_cast<int> (n + m);
  return pair;
}

/** Width, height and RGB pixels of an 8-bit RGB or RGBA PNG (no interlace). */
struct Png
{
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

std::uint32_t
bigEndian (const std::string& s, std::size_t at)
{
  return (std::uint32_t (std::uint8_t (s[at])) << 24) | (std::uint32_t (std::uint8_t (s[at + 1])) << 16) |
         (std::uint32_t (std::uint8_t (s[at + 2])) << 8) | std::uint8_t (s[at + 3]);
}

bool
readPng (const std::string& path, Png& png, std::string& problem)
{
  std::ifstream file (path, std::ios::binary);
  const std::string data ((std::istreambuf_iterator<char> (file)), std::istreambuf_iterator<char> ());
  if (data.size () < 8 || data.compare (0, 8, "\x89PNG\r\n\x1a\n") != 0)
    return problem = "not a PNG file", false;
  std::string idat;
  int channels = 0;
  for (std::size_t at = 8; at + 8 <= data.size ();) {
    const std::uint32_t length = bigEndian (data, at);
    const std::string type = data.substr (at + 4, 4);
    if (type == "IHDR") {
      png.width = static_cast<int> (bigEndian (data, at + 8));
      png.height = static_cast<int> (bigEndian (data, at + 12));
      const int depth = std::uint8_t (data[at + 16]), colour = std::uint8_t (data[at + 17]);
      if (depth != 8 || (colour != 2 && colour != 6) || data[at + 20] != 0)
        return problem = "unexpected PNG format", false;
      channels = colour == 2 ? 3 : 4;
    }
    else if (type == "IDAT")
      idat += data.substr (at + 8, length);
    at += 12 + length;
  }
  std::string raw;
  {
    boost::iostreams::filtering_istream in;
    in.push (boost::iostreams::zlib_decompressor ());
    std::istringstream compressed (idat);
    in.push (compressed);
    std::ostringstream out;
    boost::iostreams::copy (in, out);
    raw = out.str ();
  }
  const std::size_t stride = static_cast<std::size_t> (png.width) * channels;
  if (channels == 0 || raw.size () != (stride + 1) * png.height)
    return problem = "PNG data size does not match its header", false;
  std::vector<std::uint8_t> previous (stride, 0), row (stride);
  png.rgb.clear ();
  for (int y = 0; y < png.height; ++y) {
    const std::uint8_t filter = raw[y * (stride + 1)];
    for (std::size_t x = 0; x < stride; ++x) {
      const int a = x >= std::size_t (channels) ? row[x - channels] : 0, b = previous[x],
                c = x >= std::size_t (channels) ? previous[x - channels] : 0;
      int predictor = 0;
      if (filter == 1)
        predictor = a;
      else if (filter == 2)
        predictor = b;
      else if (filter == 3)
        predictor = (a + b) / 2;
      else if (filter == 4) {
        const int p = a + b - c, pa = std::abs (p - a), pb = std::abs (p - b), pc = std::abs (p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      row[x] = static_cast<std::uint8_t> (std::uint8_t (raw[y * (stride + 1) + 1 + x]) + predictor);
    }
    for (int x = 0; x < png.width; ++x)
      png.rgb.insert (png.rgb.end (), row.begin () + x * channels, row.begin () + x * channels + 3);
    previous = row;
  }
  return true;
}

/** true when the viewer exists and can render here (an X display or xvfb-run). */
bool
viewerCanRender (std::string& why)
{
  if (!fs::is_regular_file (fs::path (pcl_crf::test::appsDir ()) / "pcl_crf_viewer"))
    return why = "pcl_crf_viewer was not built (PCL visualization missing)", false;
  const char* display = std::getenv ("DISPLAY");
  if (display && *display)
    return true;
  if (std::system ("command -v xvfb-run >/dev/null 2>&1") != 0)
    return why = "no X display and no xvfb-run (Debian package xvfb)", false;
  return true;
}

#define PCL_CRF_SKIP_WITHOUT_VIEWER()                                                    \
  PCL_CRF_SKIP_WITHOUT_APPS ();                                                          \
  if (std::string why; !viewerCanRender (why))                                           \
  GTEST_SKIP () << why

class ToolViewer : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    dir_ = fs::temp_directory_path () / ("pcl_crf_tool_viewer_" + std::to_string (::getpid ()));
    fs::create_directories (dir_);
    pcl_crf::ScanPair pair = roomWithCar ();
    pair.name = "0000";
    pcl_crf::saveDataset ({pair}, (dir_ / "set").string ());
  }
  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }
  fs::path dir_;
};

TEST (ViewerScene, TruthSceneColoursClustersAndBoxesMovingOnes)
{
  const pcl_crf::ScanPair pair = roomWithCar ();
  const vis::PairScene scene = vis::makeTruthScene (pair);
  EXPECT_EQ (scene.source.cols (), pair.source.cols ());
  ASSERT_EQ (scene.clusters.size (), 2u);
  EXPECT_TRUE (scene.clusters[0].is_static);
  const vis::SceneCluster& car = scene.clusters[1];
  EXPECT_FALSE (car.is_static);
  EXPECT_TRUE (car.box.size () == 4u);
  EXPECT_NEAR (car.displacement, 0.8, 1e-9);
  EXPECT_NEAR (car.rotation, 0.0, 1e-9);
  EXPECT_NE (car.legend.find ("#1 car: 30 pts, moved 0.80 m"), std::string::npos) << car.legend;
  // the static world lands on the target (display frame = target frame)
  EXPECT_LT ((scene.source.col (0) - pair.target.col (0)).norm (), 1e-9);
  // static points are dimmed, the car has its own colour; every match is a line
  const vis::ScenePalette palette;
  EXPECT_EQ (scene.source_colours[0].r, palette.static_source.r);
  EXPECT_EQ (scene.source_colours.back ().g, vis::ScenePalette::moving (0).g);
  EXPECT_EQ (scene.lines.size (), pair.source_match.size ());
  EXPECT_EQ (scene.legend.size (), 2u);
}

TEST (ViewerScene, PredictionSceneAndFitCheck)
{
  const pcl_crf::ScanPair pair = roomWithCar ();
  pcl_crf::Prediction prediction;
  prediction.cluster_motions = {pair.objects[0].T_target_source, pair.objects[1].T_target_source};
  prediction.static_cluster = 0;
  prediction.source_cluster = pair.source_object;
  prediction.source_cluster[0] = pcl_crf::kOutlierCluster;
  prediction.T_source_target = pair.objects[0].T_target_source.inverse ();
  std::string problem;
  EXPECT_TRUE (vis::predictionFitsPair (pair, prediction, problem)) << problem;
  const vis::PairScene scene = vis::makePredictionScene (pair, prediction, "oracle");
  EXPECT_NE (scene.title.find ("oracle"), std::string::npos);
  EXPECT_TRUE (scene.lines.empty ());  // no associations predicted
  EXPECT_EQ (scene.source_colours[0].r, vis::ScenePalette ().outlier.r);
  prediction.source_cluster.pop_back ();
  EXPECT_FALSE (vis::predictionFitsPair (pair, prediction, problem));
  EXPECT_NE (problem.find ("cluster labels for"), std::string::npos);
}

TEST_F (ToolViewer, HelpAndErrors)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  if (!fs::is_regular_file (fs::path (pcl_crf::test::appsDir ()) / "pcl_crf_viewer"))
    GTEST_SKIP () << "pcl_crf_viewer was not built";
  auto run = runTool ("pcl_crf_viewer", "-h");
  EXPECT_EQ (run.exit_code, 0);
  for (const char* text : {"Usage:", "--screenshot FILE.png", "--size W,H", "(default: 1200,800)", "--method NAME",
                           "--prediction DIR", "--log LOG", "n / p", "Example:"})
    EXPECT_NE (run.output.find (text), std::string::npos) << text << "\n" << run.output;
  const std::string set = (dir_ / "set").string ();
  const struct
  {
    std::string arguments, message;
  } cases[] = {
      {(dir_ / "missing").string () + " --screenshot a.png", "folder not found"},
      {set + " --view prediction --screenshot a.png", "needs --method NAME or --prediction DIR"},
      {set + " --view sideways --method icp", "--view must be truth, prediction or both"},
      {set + " --method nonsense --screenshot a.png", "unknown method 'nonsense'"},
      {set + " --screenshot a.jpg", "needs a .png file name"},
      {set + " --size 10,10 --screenshot a.png", "--size needs a width"},
      {set + " --pair 7 --screenshot a.png", "no such pair"},
      {set + " --prediction " + (dir_ / "nothing").string () + " --screenshot a.png", "no saved result"},
      {"--log " + (dir_ / "missing.log").string () + " --screenshot a.png", "cannot read the log: no such file"},
      {set + " --log x.log", "Expected one pair or dataset folder, or --log LOG"},
      {set + " --bogus --screenshot a.png", "Unknown option '--bogus' (see "},
      {set + " --screenshot a.png --method", "Option --method needs a value"},
  };
  for (const auto& c : cases) {
    run = runTool ("pcl_crf_viewer", c.arguments);
    EXPECT_EQ (run.exit_code, 1) << c.arguments << "\n" << run.output;
    EXPECT_NE (run.output.find (c.message), std::string::npos) << c.arguments << "\n" << run.output;
  }
  const char* display = std::getenv ("DISPLAY");
  if (!display || !*display) {  // interactive viewing needs a display
    run = runTool ("pcl_crf_viewer", set);
    EXPECT_EQ (run.exit_code, 1);
    EXPECT_NE (run.output.find ("no X display"), std::string::npos) << run.output;
  }
}

TEST_F (ToolViewer, ScreenshotOfGroundTruthAndIcpSideBySideIsNotBlank)
{
  PCL_CRF_SKIP_WITHOUT_VIEWER ();
  const std::string png_path = (dir_ / "shot.png").string ();
  const auto run = runTool ("pcl_crf_viewer", (dir_ / "set" / "0000").string () + " --method icp --size 800,500 " +
                                                  "--screenshot " + png_path);
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Wrote " + png_path), std::string::npos) << run.output;
  Png png;
  std::string problem;
  ASSERT_TRUE (readPng (png_path, png, problem)) << problem;
  EXPECT_EQ (png.width, 800);
  EXPECT_EQ (png.height, 500);
  std::set<std::uint32_t> colours;
  long foreground = 0, left = 0, right = 0, green = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const std::uint8_t* p = &png.rgb[(static_cast<std::size_t> (y) * png.width + x) * 3];
      colours.insert ((std::uint32_t (p[0]) << 16) | (std::uint32_t (p[1]) << 8) | p[2]);
      if (p[0] == 255 && p[1] == 255 && p[2] == 255)
        continue;
      ++foreground;
      (x < png.width / 2 ? left : right) += 1;
      const vis::Rgb car = vis::ScenePalette::moving (0);  // the car's colour in the truth view
      green += std::abs (p[0] - car.r) + std::abs (p[1] - car.g) + std::abs (p[2] - car.b) < 30 ? 1 : 0;
    }
  EXPECT_GT (colours.size (), 20u);                      // scans, clusters, text: many colours
  EXPECT_GT (foreground, 800L * 500 / 100);              // at least 1 % drawn
  EXPECT_LT (foreground, 800L * 500 / 2);                // and mostly white background
  EXPECT_GT (left, foreground / 5);                      // both viewports hold something
  EXPECT_GT (right, foreground / 5);
  EXPECT_GT (green, 50);                                 // the moving car is drawn in its colour
}

TEST_F (ToolViewer, ScreenshotOfASavedPredictionAndOfALog)
{
  PCL_CRF_SKIP_WITHOUT_VIEWER ();
  pcl_crf::ScanPair pair = roomWithCar ();
  pair.name = "0000";
  pcl_crf::Prediction prediction;
  prediction.cluster_motions = {pair.objects[0].T_target_source};
  prediction.static_cluster = 0;
  prediction.source_cluster.assign (pair.source.cols (), 0);
  prediction.T_source_target = pair.objects[0].T_target_source.inverse ();
  pcl_crf::savePrediction (pair, prediction, "oracle", (dir_ / "pred" / "0000").string ());
  const std::string png_path = (dir_ / "saved.png").string ();
  auto run = runTool ("pcl_crf_viewer", (dir_ / "set").string () + " --prediction " + (dir_ / "pred").string () +
                                            " --view prediction --size 400,300 --screenshot " + png_path);
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("oracle: 1 clusters"), std::string::npos) << run.output;
  Png png;
  std::string problem;
  ASSERT_TRUE (readPng (png_path, png, problem)) << problem;
  EXPECT_EQ (png.width, 400);
  // a result saved for another pair of the same size, in this pair's folder, is not
  // shown as this one's
  pcl_crf::ScanPair other = pair;
  other.name = "0001";
  pcl_crf::savePrediction (other, prediction, "oracle", (dir_ / "other" / "0000").string ());
  run = runTool ("pcl_crf_viewer", (dir_ / "set").string () + " --prediction " + (dir_ / "other").string () +
                                       " --view prediction --size 400,300 --screenshot " + png_path);
  EXPECT_EQ (run.exit_code, 1) << run.output;
  EXPECT_NE (run.output.find ("prediction.txt is the result of pair 0001, not of pair 0000"), std::string::npos)
      << run.output;

  // a CARMEN log of two scans of a square room, 181 beams, no ODOM
  std::ofstream log (dir_ / "tiny.log");
  for (int j = 0; j < 2; ++j) {
    log << "FLASER 181";
    for (int i = 0; i < 181; ++i) {
      const double a = -M_PI / 2 + i * M_PI / 180;
      log << ' ' << 3.0 / std::max (std::abs (std::cos (a)), std::abs (std::sin (a))) - 0.2 * j * std::cos (a);
    }
    log << ' ' << 0.2 * j << " 0 0 " << 0.2 * j << " 0 0 " << j << " h " << j << "\n";
  }
  log.close ();
  run = runTool ("pcl_crf_viewer", "--log " + (dir_ / "tiny.log").string () +
                                       " --scan 0 --size 400,300 --screenshot " + png_path);
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("Pair scan_000000 (1 of 1)"), std::string::npos) << run.output;
}

}  // namespace
