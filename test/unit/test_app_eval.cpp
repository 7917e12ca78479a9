#include <pcl_crf/io/dataset_io.h>

#include "app_runner.h"
#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using pcl_crf::test::runTool;

namespace {

class EvalTool : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    // One folder per test: ctest runs tests in parallel.
    dir_ = fs::temp_directory_path () /
           ("pcl_crf_eval_tool_" + std::string (::testing::UnitTest::GetInstance ()->current_test_info ()->name ()));
    fs::remove_all (dir_);
    auto pair = pcl_crf::test::staticRoomPair (pcl_crf::makeRigid2d (0.3, 0.1, 0.05),
                                               pcl_crf::makeRigid2d (0.02, 0.0, 0.0), 0.02);
    pair.sensor.beam_count = 5000;
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

TEST_F (EvalTool, HelpListsOptionsWithDefaults)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", "-h");
  EXPECT_EQ (run.exit_code, 0);
  EXPECT_NE (run.output.find ("--method NAMES"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("default: 0.1"), std::string::npos) << run.output;
}

TEST_F (EvalTool, PrintsTableForIcp)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", (dir_ / "set").string () + " --method icp -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("association_accuracy [fraction]"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("pairs: icp=1"), std::string::npos) << run.output;
}

TEST_F (EvalTool, PrintsTheSmallObjectVCeilingWithoutRunningAMethod)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", (dir_ / "set").string () + " --v-ceiling --method joint -q");
  ASSERT_EQ (run.exit_code, 0) << run.output;  // joint would need --models: it does not run
  EXPECT_NE (run.output.find ("pairs with V >= 0.95 (of 1)"), std::string::npos) << run.output;
  // one static world: every oracle reaches V = 1
  EXPECT_NE (run.output.find ("1      1.000   1\n"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("20     1.000   1\n"), std::string::npos) << run.output;
  EXPECT_EQ (run.output.find ("association_accuracy"), std::string::npos) << run.output;
}

TEST_F (EvalTool, WritesCsvJsonAndPredictions)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const std::string set = (dir_ / "set").string ();
  const auto csv = runTool ("pcl_crf_eval", set + " --format csv -q");
  ASSERT_EQ (csv.exit_code, 0) << csv.output;
  EXPECT_NE (csv.output.find ("method,metric,unit,mean,std,count"), std::string::npos);
  EXPECT_NE (csv.output.find ("icp,ego_translation_error,m,"), std::string::npos);
  const std::string json_file = (dir_ / "out.json").string ();
  const auto json = runTool ("pcl_crf_eval", set + " --format json -q --output " + json_file +
                                                 " --save-predictions " + (dir_ / "pred").string ());
  ASSERT_EQ (json.exit_code, 0) << json.output;
  std::ifstream in (json_file);
  const std::string text ((std::istreambuf_iterator<char> (in)), std::istreambuf_iterator<char> ());
  EXPECT_EQ (text.rfind ("{\"methods\": [{\"method\": \"icp\", \"pairs\": 1,", 0), 0u) << text;
  EXPECT_TRUE (fs::is_regular_file (dir_ / "pred" / "icp" / "0000" / "prediction.pcd"));
  EXPECT_TRUE (fs::is_regular_file (dir_ / "pred" / "icp" / "0000" / "prediction.txt"));
}

TEST_F (EvalTool, BadArgumentsAndFilesAreClearErrors)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const std::string set = (dir_ / "set").string ();
  auto run = runTool ("pcl_crf_eval", (dir_ / "missing").string ());
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("dataset folder not found"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", set + " --method nonsense");
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("unknown method 'nonsense'"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", set + " --format xml");
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("--format must be"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", set + " --tolerance -1");
  EXPECT_NE (run.exit_code, 0);
  std::ofstream (dir_ / "set" / "0000" / "pair.txt") << "garbage\n";
  run = runTool ("pcl_crf_eval", set);
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("pair.txt:1"), std::string::npos) << run.output;
}

TEST_F (EvalTool, UnknownOptionsAndMissingValuesAreErrors)
{
  // PCL's parse_argument skips both silently: "--bogus" and a bare "--tolerance" used to run
  // with the defaults.
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const std::string set = (dir_ / "set").string ();
  const struct
  {
    std::string tool, arguments, message;
  } cases[] = {
      {"pcl_crf_eval", set + " --bogus", "Unknown option '--bogus' (see "},
      {"pcl_crf_eval", set + " -x -q", "Unknown option '-x'"},
      {"pcl_crf_eval", set + " --tolerance", "Option --tolerance needs a value (see "},
      {"pcl_crf_eval", set + " --method --tolerance 0.2", "Option --method needs a value"},
      {"pcl_crf_eval", set + " --tolerance abc", "--tolerance needs a decimal number, not 'abc'"},
      {"pcl_crf_eval", set + " --max-pairs 1.5", "--max-pairs needs a whole number >= 0"},
      {"pcl_crf_eval", set + " --method icp,kmeans,icp", "--method names 'icp' twice"},
      {"pcl_crf_eval", set + " --tolerance 0x10", "--tolerance needs a decimal number, not '0x10'"},
      // parse_argument read the first of a repeated option: "--format csv --format json" wrote csv.
      {"pcl_crf_eval", set + " --format csv --format json", "Option --format is given twice"},
      {"pcl_crf_train", set + " --method crf-t -o " + (dir_ / "m").string () + " --bogus", "Unknown option '--bogus'"},
      {"pcl_crf_train", set + " -o " + (dir_ / "m").string () + " --method", "Option --method needs a value"},
  };
  for (const auto& c : cases) {
    const auto run = runTool (c.tool, c.arguments);
    EXPECT_EQ (run.exit_code, 1) << c.tool << " " << c.arguments << "\n" << run.output;
    EXPECT_NE (run.output.find (c.message), std::string::npos) << c.arguments << "\n" << run.output;
  }
  EXPECT_FALSE (fs::exists (dir_ / "m"));
}

TEST_F (EvalTool, TrainToolRejectsMethodsWithoutModels)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  auto run = runTool ("pcl_crf_train", "-h");
  EXPECT_EQ (run.exit_code, 0);
  EXPECT_NE (run.output.find ("--method NAME"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_train", (dir_ / "set").string () + " --method icp -o " + (dir_ / "m").string ());
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("learns nothing"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_train", (dir_ / "set").string ());
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("required"), std::string::npos) << run.output;
}

TEST_F (EvalTool, TrainingWithoutAMoverWarns)
{
  // K-Means trained on the static world alone learns one cluster, and scored V 0 after,
  // without a word.
  PCL_CRF_SKIP_WITHOUT_APPS ();
  pcl_crf::ScanPair pair = pcl_crf::loadDataset ((dir_ / "set").string ()).front ();
  const int world = pair.staticObjectId ();
  std::fill (pair.source_object.begin (), pair.source_object.end (), world);
  std::fill (pair.target_object.begin (), pair.target_object.end (), world);
  pair.objects.erase (std::remove_if (pair.objects.begin (), pair.objects.end (),
                                      [] (const pcl_crf::ObjectTruth& object) { return !object.is_static; }),
                      pair.objects.end ());
  pcl_crf::saveDataset ({pair}, (dir_ / "still").string ());
  const std::string model = " -o " + (dir_ / "m.model").string ();
  auto run = runTool ("pcl_crf_train", (dir_ / "still").string () + " --method kmeans" + model);
  EXPECT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("No training pair has a point on a moving object: kmeans learns its clusters from the "
                              "static world alone"),
             std::string::npos)
      << run.output;
  run = runTool ("pcl_crf_train", std::string (PCL_CRF_SOURCE_DIR) + "/data/default/test --method kmeans" + model);
  EXPECT_EQ (run.exit_code, 0) << run.output;
  EXPECT_EQ (run.output.find ("No training pair has a point on a moving object"), std::string::npos) << run.output;
}

TEST_F (EvalTool, TrainedModelIsUsedByEval)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const std::string set = (dir_ / "set").string ();
  fs::create_directories (dir_ / "models");
  auto run = runTool ("pcl_crf_train", set + " --method kmeans -o " + (dir_ / "models" / "kmeans.model").string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  std::ifstream model (dir_ / "models" / "kmeans.model");
  std::string header;
  std::getline (model, header);
  EXPECT_EQ (header, "pcl_crf_kmeans_model 1");
  run = runTool ("pcl_crf_eval", set + " --method kmeans -q --models " + (dir_ / "models").string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("pairs: kmeans=1"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", set + " --method kmeans -q");
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("give --train DIR or --models DIR"), std::string::npos) << run.output;
}

}  // namespace
