// pcl_crf_eval --leave-one-out and the pipeline methods through the tools.

#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include "app_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using pcl_crf::test::runTool;

namespace {

class LeaveOneOutTool : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    // One folder per test: ctest runs tests in parallel.
    dir_ = fs::temp_directory_path () /
           ("pcl_crf_loo_tool_" + std::string (::testing::UnitTest::GetInstance ()->current_test_info ()->name ()));
    fs::remove_all (dir_);
    pcl_crf::simulation::SimulatorConfig config;
    config.seed = 41;
    const auto pairs = pcl_crf::simulation::ScanPairSimulator (config).simulateDataset (0, 3);
    pcl_crf::saveDataset (pairs, set ());
    pcl_crf::saveDataset ({pairs.front ()}, (dir_ / "one").string ());
  }

  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }

  std::string
  set () const
  {
    return (dir_ / "set").string ();
  }

  fs::path dir_;
};

TEST_F (LeaveOneOutTool, HelpMentionsTheProtocolAndTheNewMethods)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", "-h");
  EXPECT_EQ (run.exit_code, 0);
  EXPECT_NE (run.output.find ("--leave-one-out"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("icp+kmeans, crf-matching+kmeans, crf-m"), std::string::npos) << run.output;
}

TEST_F (LeaveOneOutTool, TrainsOnTheOtherPairsAndReportsEveryFold)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", set () + " --leave-one-out --method icp,kmeans,crf-m");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  for (const char* line :
       {"[kmeans] fold 1/3 pair_0000: training on 2 pairs", "[kmeans] fold 3/3 pair_0002: training on 2 pairs",
        "[crf-m] fold 2/3 pair_0001: training on 2 pairs", "[icp] fold 3/3 pair_0002"})
    EXPECT_NE (run.output.find (line), std::string::npos) << line << "\n" << run.output;
  EXPECT_NE (run.output.find ("association_accuracy [fraction]"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("v_measure"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("pairs: icp=3 kmeans=3 crf-m=3"), std::string::npos) << run.output;
}

TEST_F (LeaveOneOutTool, MaxPairsLimitsTheHeldOutPairsNotTheTrainingPairs)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  const auto run = runTool ("pcl_crf_eval", set () + " --leave-one-out --max-pairs 1 --method icp+kmeans --format csv");
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("[icp+kmeans] fold 1/1 pair_0000: training on 2 pairs"), std::string::npos) << run.output;
  EXPECT_NE (run.output.find ("icp+kmeans,association_accuracy,fraction,"), std::string::npos) << run.output;
  EXPECT_EQ (run.output.find ("fold 2/"), std::string::npos) << run.output;
}

TEST_F (LeaveOneOutTool, ConflictingOptionsAndTooFewPairsAreClearErrors)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  auto run = runTool ("pcl_crf_eval", set () + " --leave-one-out --method kmeans --models " + set ());
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("drop --train / --models"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", set () + " --leave-one-out --method kmeans --train " + set ());
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("drop --train / --models"), std::string::npos) << run.output;
  run = runTool ("pcl_crf_eval", (dir_ / "one").string () + " --leave-one-out --method kmeans");
  EXPECT_NE (run.exit_code, 0);
  EXPECT_NE (run.output.find ("at least 2 pairs"), std::string::npos) << run.output;
}

TEST_F (LeaveOneOutTool, TrainToolWritesACompositeModelThatEvalLoads)
{
  PCL_CRF_SKIP_WITHOUT_APPS ();
  fs::create_directories (dir_ / "models");
  const std::string model = (dir_ / "models" / "icp+kmeans.model").string ();
  auto run = runTool ("pcl_crf_train", set () + " --method icp+kmeans -o " + model);
  ASSERT_EQ (run.exit_code, 0) << run.output;
  std::ifstream in (model);
  std::string header;
  std::getline (in, header);
  EXPECT_EQ (header, "pcl_crf_composite_model 1");
  run = runTool ("pcl_crf_eval", set () + " -q --method icp+kmeans --models " + (dir_ / "models").string ());
  ASSERT_EQ (run.exit_code, 0) << run.output;
  EXPECT_NE (run.output.find ("pairs: icp+kmeans=3"), std::string::npos) << run.output;
}

}  // namespace
