// pcl_crf_viewer: shows scan pairs the way the CRF papers draw them - source and
// target scans, associations, clusters with boxes and motion arrows - for ground
// truth, a method's result, or both side by side. --screenshot renders without a
// display (under xvfb-run when DISPLAY is unset) and exits.

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/visualization/pair_scene.h>

#include "app_common.h"
#include "viewer/headless.h"
#include "viewer/log_arguments.h"
#include "viewer/pair_renderer.h"

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <vtkRenderWindow.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

using namespace pcl::console;
namespace fs = std::filesystem;
namespace vis = pcl_crf::visualization;

namespace {

struct ViewerArguments
{
  std::string input;
  std::string log;
  long scan = 0;
  std::string pair;
  std::string method;
  std::string model_dir;
  std::string prediction;
  std::string view;
  std::string screenshot;
  std::vector<double> size{1200, 800};
  bool no_lines = false;
  pcl_crf::apps::LogArguments log_args;
};

void
printHelp (const char* program)
{
  print_info ("Shows scan pairs like the CRF papers' figures: the source scan (red) moved onto the target\n"
              "scan (blue) by the static world's motion, association lines, every moving cluster in its own\n"
              "colour with a box and a motion arrow, and a legend with cluster ids, sizes and motions.\n\n"
              "Usage: %s PAIR_OR_DATASET_DIR [options]\n"
              "       %s --log LOG [--scan K] [options]\n\n", program, program);
  print_info (" Input:\n");
  print_info ("  PAIR_OR_DATASET_DIR    a pair folder (pair.txt, source.pcd, target.pcd) or a dataset folder\n");
  print_info ("  --pair NAME|INDEX      the pair of a dataset to show first (default: the first)\n");
  print_info ("  --log LOG              a CARMEN log or ROS bag instead: shows the pair (scan K, K+step)\n");
  print_info ("  --scan K               index of the source scan in --log (default: 0)\n");
  pcl_crf::apps::printLogOptionsHelp ();
  print_info (" What to show:\n");
  print_info ("  --method NAME          compute a method's result for the pair (default: none)\n");
  print_info ("  --models DIR           load a learned method from DIR/NAME.model (default: none)\n");
  print_info ("  --prediction DIR       load a saved result (pcl_crf_eval --save-predictions D/NAME,\n"
              "                         pcl_crf_run -o D): DIR/prediction.txt or DIR/<pair>/prediction.txt\n");
  print_info ("  --view V               truth | prediction | both (two viewports) (default: both when a\n"
              "                         result is given, else truth)\n");
  print_info ("  --no-lines             hide the association lines\n");
  print_info (" Output:\n");
  print_info ("  --screenshot FILE.png  render off-screen to FILE.png and exit (no display needed: runs\n"
              "                         itself under xvfb-run when DISPLAY is unset)\n");
  print_info ("  --size W,H             window / image size [pixels] (default: 1200,800)\n");
  print_info ("  -h                     this help\n");
  print_info (" Keys (interactive): n / p next / previous pair, a association lines on/off,\n"
              "  r reset the view, q quit (and PCL's usual keys).\n\n");
  print_info ("Example:\n  %s data/default/test/pair_0000 --method icp --screenshot pair0.png\n", program);
}

bool
parseArguments (int argc, char** argv, ViewerArguments& args)
{
  std::set<std::string> value_options = pcl_crf::apps::logValueOptions ();
  value_options.insert ({"--pair", "--log", "--scan", "--method", "--models", "--prediction", "--view",
                         "--screenshot", "--size"});
  if (!pcl_crf::apps::checkOptions (argc, argv, value_options, {"--no-lines", "--label"}))
    return false;
  const auto positional = pcl_crf::apps::positionalArguments (argc, argv, value_options);
  parse_argument (argc, argv, "--log", args.log);
  if (positional.size () > 1 || (positional.size () == 1 && !args.log.empty ()))
    return print_error ("Expected one pair or dataset folder, or --log LOG (see -h).\n"), false;
  if (positional.empty () && args.log.empty ())
    return print_error ("No input: give a pair or dataset folder, or --log LOG (see -h).\n"), false;
  if (!positional.empty ())
    args.input = positional.front ();
  parse_argument (argc, argv, "--pair", args.pair);
  parse_argument (argc, argv, "--method", args.method);
  parse_argument (argc, argv, "--models", args.model_dir);
  parse_argument (argc, argv, "--prediction", args.prediction);
  parse_argument (argc, argv, "--view", args.view);
  parse_argument (argc, argv, "--screenshot", args.screenshot);
  args.no_lines = find_switch (argc, argv, "--no-lines");
  if (!pcl_crf::apps::countOption (argc, argv, "--scan", args.scan, 0) ||
      !pcl_crf::apps::numberListOption (argc, argv, "--size", args.size, 2) ||
      !pcl_crf::apps::parseLogArguments (argc, argv, args.log_args))
    return false;
  if (args.size[0] < 200 || args.size[1] < 150 || args.size[0] > 8000 || args.size[1] > 8000)
    return print_error ("--size needs a width in [200, 8000] and a height in [150, 8000] pixels.\n"), false;
  if (!args.method.empty () && !args.prediction.empty ())
    return print_error ("Give --method or --prediction, not both.\n"), false;
  const bool has_result = !args.method.empty () || !args.prediction.empty ();
  if (args.view.empty ())
    args.view = has_result ? "both" : "truth";
  if (args.view != "truth" && args.view != "prediction" && args.view != "both")
    return print_error ("--view must be truth, prediction or both, not '%s'.\n", args.view.c_str ()), false;
  if (args.view != "truth" && !has_result)
    return print_error ("--view %s needs --method NAME or --prediction DIR.\n", args.view.c_str ()), false;
  if (!args.screenshot.empty () && fs::path (args.screenshot).extension () != ".png")
    return print_error ("--screenshot needs a .png file name, not '%s'.\n", args.screenshot.c_str ()), false;
  return true;
}

/** The pairs the viewer can step through: a dataset's folders or a log's scan pairs. */
class PairBrowser
{
public:
  explicit PairBrowser (const ViewerArguments& args) : args_ (args)
  {
    if (!args.log.empty ()) {
      pcl_crf::apps::warnAboutOptionsTheLogIgnores (args.log_args, pcl_crf::detectLaserLogFormat (args.log));
      log_ = pcl_crf::readLaserLog (args.log, args.log_args.read);
      pcl_crf::apps::printLogWarnings (*log_);
      if (args.log_args.pairs.label_points && !log_->has_reference_poses)
        throw std::invalid_argument ("--label needs reference poses, and " + args.log + " has none");
      count_ = pcl_crf::logPairCount (log_->scans.size (), args.log_args.pairs.step);
      if (static_cast<std::size_t> (args.scan) >= count_)
        throw std::invalid_argument ("--scan " + std::to_string (args.scan) + " has no pair: " + args.log +
                                     " holds " + std::to_string (log_->scans.size ()) + " scans");
      current_ = static_cast<std::size_t> (args.scan);
      return;
    }
    if (!fs::is_directory (args.input))
      throw std::invalid_argument (args.input + ": folder not found");
    if (fs::is_regular_file (fs::path (args.input) / "pair.txt")) {
      folders_ = {args.input};
      single_pair_ = true;
    }
    else {
      for (const auto& name : pcl_crf::listScanPairs (args.input))
        folders_.push_back ((fs::path (args.input) / name).string ());
    }
    count_ = folders_.size ();
    if (!args.pair.empty ())
      current_ = findPair (args.pair);
  }

  std::size_t
  size () const
  {
    return count_;
  }
  std::size_t&
  current ()
  {
    return current_;
  }
  bool
  singlePair () const
  {
    return single_pair_;
  }

  pcl_crf::ScanPair
  load (std::size_t index) const
  {
    if (log_)
      return pcl_crf::makeLogPair (*log_, index, args_.log_args.pairs);
    return pcl_crf::loadScanPair (folders_.at (index));
  }

private:
  std::size_t
  findPair (const std::string& wanted) const
  {
    for (std::size_t k = 0; k < folders_.size (); ++k)
      if (fs::path (folders_[k]).filename () == wanted)
        return k;
    char* end = nullptr;
    const long index = std::strtol (wanted.c_str (), &end, 10);
    if (*end == '\0' && index >= 0 && static_cast<std::size_t> (index) < folders_.size ())
      return static_cast<std::size_t> (index);
    throw std::invalid_argument ("--pair " + wanted + ": no such pair in " + args_.input + " (" +
                                 std::to_string (folders_.size ()) + " pairs)");
  }

  const ViewerArguments& args_;
  std::optional<pcl_crf::LaserLog> log_;
  std::vector<std::string> folders_;
  std::size_t count_ = 0, current_ = 0;
  bool single_pair_ = false;
};

/** A pair and (optionally) a method's result for it. */
struct Frame
{
  pcl_crf::ScanPair pair;
  std::optional<pcl_crf::Prediction> prediction;
  std::string method;
};

class FrameLoader
{
public:
  explicit FrameLoader (const ViewerArguments& args) : args_ (args)
  {
    if (args.method.empty ())
      return;
    method_ = pcl_crf::createEvaluationMethod (args.method);
    if (method_->isLearned ()) {
      if (args.model_dir.empty ())
        throw std::invalid_argument ("method '" + args.method + "' learns its weights: give --models DIR");
      method_->loadModel ((fs::path (args.model_dir) / (args.method + ".model")).string ());
    }
  }

  /** Loads pair \a index and its result (computed only when \a run_method). */
  Frame
  load (const PairBrowser& browser, std::size_t index, bool run_method = true)
  {
    Frame frame;
    frame.pair = browser.load (index);
    if (method_ && !run_method)
      return frame;
    if (method_) {
      pcl::console::TicToc timer;
      timer.tic ();
      frame.prediction = method_->predict (frame.pair);
      frame.prediction->seconds = timer.toc () / 1000.0;
      frame.method = args_.method;
    }
    else if (!args_.prediction.empty ()) {
      fs::path dir = args_.prediction;
      if (!fs::is_regular_file (dir / "prediction.txt") || !browser.singlePair ())
        dir /= frame.pair.name;
      if (!fs::is_regular_file (dir / "prediction.txt"))
        throw std::invalid_argument ("no saved result for pair " + frame.pair.name + ": " +
                                     (dir / "prediction.txt").string () + " not found");
      frame.prediction = pcl_crf::loadPrediction (dir.string ());
      frame.method = savedValue (dir, "method", "saved result");
      const std::string saved_pair = savedValue (dir, "pair", frame.pair.name);
      if (saved_pair != frame.pair.name)
        throw std::invalid_argument ((dir / "prediction.txt").string () + " is the result of pair " + saved_pair +
                                     ", not of pair " + frame.pair.name);
    }
    std::string problem;
    if (frame.prediction && !vis::predictionFitsPair (frame.pair, *frame.prediction, problem))
      throw std::invalid_argument ("the result does not fit pair " + frame.pair.name + ": " + problem);
    return frame;
  }

private:
  /** The value of the "\a key VALUE" line of a saved prediction.txt ("method", "pair"),
   *  or \a fallback without one. */
  static std::string
  savedValue (const fs::path& dir, const std::string& key, const std::string& fallback)
  {
    std::ifstream file (dir / "prediction.txt");
    std::string word, value;
    while (file >> word) {
      if (word == key && file >> value)
        return value;
      std::getline (file, value);
    }
    return fallback;
  }

  const ViewerArguments& args_;
  std::unique_ptr<pcl_crf::EvaluationMethod> method_;
};

std::vector<vis::PairScene>
makeScenes (const Frame& frame, const std::string& view)
{
  std::vector<vis::PairScene> scenes;
  if (view != "prediction")
    scenes.push_back (vis::makeTruthScene (frame.pair));
  if (view != "truth" && frame.prediction)
    scenes.push_back (vis::makePredictionScene (frame.pair, *frame.prediction, frame.method));
  return scenes;
}

/** The drawing side: one or two viewports, redrawn for every frame. */
class SceneView
{
public:
  SceneView (pcl::visualization::PCLVisualizer& viewer, const ViewerArguments& args)
  : viewer_ (viewer), width_ (static_cast<int> (args.size[0])), height_ (static_cast<int> (args.size[1]))
  {
    options_.lines = !args.no_lines;
    viewer_.setSize (width_, height_);
    const vis::ScenePalette palette;
    const double r = palette.background.r / 255.0, g = palette.background.g / 255.0,
                 b = palette.background.b / 255.0;
    if (args.view == "both") {
      viewports_.resize (2);
      viewer_.createViewPort (0.0, 0.0, 0.5, 1.0, viewports_[0]);
      viewer_.createViewPort (0.5, 0.0, 1.0, 1.0, viewports_[1]);
    }
    else
      viewports_ = {0};
    viewer_.setBackgroundColor (r, g, b);
    for (int viewport : viewports_)
      viewer_.setBackgroundColor (r, g, b, viewport);
  }

  void
  show (const std::vector<vis::PairScene>& scenes)
  {
    viewer_.removeAllPointClouds ();
    viewer_.removeAllShapes ();
    for (std::size_t k = 0; k < scenes.size () && k < viewports_.size (); ++k)
      vis::drawScene (viewer_, scenes[k], viewports_[k], "v" + std::to_string (k) + "_", options_, height_, 0);
    int top_margin = 0;
    for (const auto& scene : scenes)
      top_margin = std::max (top_margin, vis::legendHeight (scene, options_));
    vis::fitTopDownCamera (viewer_, scenes, width_ / static_cast<int> (viewports_.size ()), height_, top_margin);
    scenes_ = scenes;
  }

  void
  toggleLines ()
  {
    options_.lines = !options_.lines;
    show (scenes_);
  }

private:
  pcl::visualization::PCLVisualizer& viewer_;
  int width_, height_;
  vis::RenderOptions options_;
  std::vector<int> viewports_;
  std::vector<vis::PairScene> scenes_;
};

void
printFrame (const Frame& frame, std::size_t index, std::size_t count)
{
  print_highlight ("Pair ");
  print_value ("%s", frame.pair.name.c_str ());
  print_info (" (%zu of %zu): ", index + 1, count);
  print_value ("%ld", static_cast<long> (frame.pair.source.cols ()));
  print_info (" + ");
  print_value ("%ld", static_cast<long> (frame.pair.target.cols ()));
  print_info (" points, %zu objects%s", frame.pair.objects.size (),
              frame.pair.hasTruth () ? "" : " (unlabelled)");
  if (frame.prediction) {
    print_info (", %s: ", frame.method.c_str ());
    print_value ("%zu", frame.prediction->cluster_motions.size ());
    print_info (" clusters");
  }
  print_info ("\n");
}

int
screenshot (const ViewerArguments& args, PairBrowser& browser, FrameLoader& loader)
{
  pcl::console::TicToc timer;
  timer.tic ();
  const Frame frame = loader.load (browser, browser.current ());
  printFrame (frame, browser.current (), browser.size ());
  pcl::visualization::PCLVisualizer viewer ("pcl_crf_viewer", false);
  viewer.getRenderWindow ()->SetOffScreenRendering (1);
  SceneView view (viewer, args);
  view.show (makeScenes (frame, args.view));
  const vis::ScenePalette palette;
  const unsigned char background[3] = {palette.background.r, palette.background.g, palette.background.b};
  vis::ScreenshotStats stats;
  if (!vis::writeScreenshot (viewer.getRenderWindow (), args.screenshot, background, stats))
    throw std::runtime_error ("cannot write " + args.screenshot);
  print_highlight ("Wrote ");
  print_value ("%s", args.screenshot.c_str ());
  print_info (" (%d x %d pixels, %ld foreground pixels, %ld colours) in ", stats.width, stats.height,
              stats.foreground_pixels, stats.distinct_colours);
  print_value ("%.0f", timer.toc ());
  print_info (" ms\n");
  return 0;
}

int
interactive (const ViewerArguments& args, PairBrowser& browser, FrameLoader& loader)
{
  pcl::visualization::PCLVisualizer viewer ("pcl_crf_viewer");
  SceneView view (viewer, args);
  const auto showCurrent = [&] () {
    const Frame frame = loader.load (browser, browser.current ());
    printFrame (frame, browser.current (), browser.size ());
    view.show (makeScenes (frame, args.view));
  };
  showCurrent ();
  viewer.registerKeyboardCallback ([&] (const pcl::visualization::KeyboardEvent& event) {
    if (!event.keyDown ())
      return;
    const std::string key = event.getKeySym ();
    try {
      if (key == "n" && browser.current () + 1 < browser.size ()) {
        ++browser.current ();
        showCurrent ();
      }
      else if (key == "p" && browser.current () > 0) {
        --browser.current ();
        showCurrent ();
      }
      else if (key == "a")
        view.toggleLines ();
    }
    catch (const std::exception& error) {
      print_error ("%s\n", error.what ());
    }
  });
  viewer.spin ();
  return 0;
}

}  // namespace

int
main (int argc, char** argv)
{
  if (const int code = pcl_crf::apps::helpExitCode (argc, argv, printHelp); code >= 0)
    return code;
  ViewerArguments args;
  if (!parseArguments (argc, argv, args))
    return 1;
  return pcl_crf::apps::exitCodeOf ([&] {
    PairBrowser browser (args);
    FrameLoader loader (args);
    if (!vis::hasDisplay ()) {
      if (args.screenshot.empty ())
        throw std::runtime_error ("no X display (DISPLAY is unset): give --screenshot FILE.png to render "
                                  "off-screen, or run under an X server");
      // Check the inputs here, where errors are plain, before starting an X server.
      loader.load (browser, browser.current (), false);
      std::string problem;
      vis::reexecUnderXvfb (argc, argv, static_cast<int> (args.size[0]), static_cast<int> (args.size[1]), problem);
      throw std::runtime_error (problem);
    }
    if (!args.screenshot.empty ())
      return screenshot (args, browser, loader);
    return interactive (args, browser, loader);
  });
}
