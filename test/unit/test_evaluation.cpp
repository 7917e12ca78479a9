#include <pcl_crf/evaluation/evaluate.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/evaluation/report.h>
#include <pcl_crf/io/dataset_io.h>

#include "file_edits.h"
#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace fs = std::filesystem;

namespace {

/** A method that always answers the truth: every score must then be perfect. */
class OracleMethod : public pcl_crf::EvaluationMethod
{
public:
  std::string
  name () const override
  {
    return "oracle";
  }

  pcl_crf::Prediction
  predict (const pcl_crf::ScanPair& pair) override
  {
    pcl_crf::Prediction prediction;
    prediction.source_match = pair.source_match;
    prediction.source_cluster = pair.source_object;
    prediction.cluster_motions = {pair.objects[0].T_target_source};
    prediction.static_cluster = 0;
    prediction.T_source_target = pair.objects[0].T_target_source.inverse ();
    return prediction;
  }
};

double
summaryMean (const pcl_crf::MethodEvaluation& evaluation, const std::string& name)
{
  for (const auto& row : evaluation.summary)
    if (row.name == name)
      return row.mean;
  ADD_FAILURE () << "no metric " << name;
  return 0.0;
}

TEST (Evaluation, OracleScoresPerfectly)
{
  const auto pair = pcl_crf::test::staticRoomPair (pcl_crf::makeRigid2d (0.2, 0.1, 0.05));
  OracleMethod oracle;
  std::size_t calls = 0;
  const auto evaluation = pcl_crf::evaluateMethod (oracle, {pair, pair}, {},
                                                   [&] (std::size_t done, std::size_t total, const std::string&) {
                                                     ++calls;
                                                     EXPECT_EQ (total, 2u);
                                                     EXPECT_EQ (done, calls);
                                                   });
  EXPECT_EQ (calls, 2u);
  EXPECT_DOUBLE_EQ (summaryMean (evaluation, "association_accuracy"), 1.0);
  EXPECT_DOUBLE_EQ (summaryMean (evaluation, "v_measure"), 1.0);
  EXPECT_NEAR (summaryMean (evaluation, "ego_translation_error"), 0.0, 1e-12);
  EXPECT_GE (evaluation.scores[0].seconds, 0.0);
}

TEST (Evaluation, IcpMethodIsRegisteredAndUnknownNamesAreErrors)
{
  const auto names = pcl_crf::availableEvaluationMethods ();
  ASSERT_FALSE (names.empty ());
  EXPECT_EQ (names.front (), "icp");
  auto icp = pcl_crf::createEvaluationMethod ("icp");
  EXPECT_FALSE (icp->isLearned ());
  EXPECT_THROW (icp->saveModel ("/tmp/x.model"), std::runtime_error);
  try {
    pcl_crf::createEvaluationMethod ("no-such-method");
    FAIL ();
  }
  catch (const std::invalid_argument& error) {
    EXPECT_NE (std::string (error.what ()).find ("known: icp"), std::string::npos);
  }
}

TEST (Evaluation, ReportsPrintEveryFormat)
{
  const auto pair = pcl_crf::test::staticRoomPair (pcl_crf::makeRigid2d (0.2, 0.1, 0.05));
  OracleMethod oracle;
  const std::vector<pcl_crf::MethodEvaluation> evaluations = {pcl_crf::evaluateMethod (oracle, {pair})};
  std::ostringstream table, csv, json;
  pcl_crf::printEvaluationTable (table, evaluations);
  pcl_crf::writeEvaluationCsv (csv, evaluations);
  pcl_crf::writeEvaluationJson (json, evaluations);
  EXPECT_NE (table.str ().find ("association_accuracy [fraction]"), std::string::npos) << table.str ();
  EXPECT_NE (table.str ().find ("1.0000 ± 0.0000"), std::string::npos) << table.str ();
  EXPECT_NE (csv.str ().find ("oracle,association_accuracy,fraction,1,0,1"), std::string::npos) << csv.str ();
  EXPECT_NE (json.str ().find ("\"association_accuracy\": {\"mean\": 1,"), std::string::npos) << json.str ();
  // found_outlier_pct has no true outliers here: JSON null, not nan.
  EXPECT_EQ (json.str ().find ("nan"), std::string::npos);
}

TEST (Evaluation, PredictionRoundTripsThroughFiles)
{
  const auto pair = pcl_crf::test::staticRoomPair (pcl_crf::makeRigid2d (0.2, 0.1, 0.05));
  OracleMethod oracle;
  pcl_crf::Prediction prediction = oracle.predict (pair);
  prediction.source_match[3] = pcl_crf::kNoMatch;
  prediction.source_cluster[4] = pcl_crf::kOutlierCluster;
  prediction.seconds = 0.25;
  const fs::path dir = fs::temp_directory_path () / "pcl_crf_prediction_io";
  fs::remove_all (dir);
  pcl_crf::savePrediction (pair, prediction, "oracle", dir.string ());
  const pcl_crf::Prediction loaded = pcl_crf::loadPrediction (dir.string ());
  EXPECT_EQ (loaded.source_match, prediction.source_match);
  EXPECT_EQ (loaded.source_cluster, prediction.source_cluster);
  ASSERT_EQ (loaded.cluster_motions.size (), 1u);
  EXPECT_TRUE (loaded.cluster_motions[0].isApprox (prediction.cluster_motions[0], 1e-15));
  EXPECT_TRUE (loaded.T_source_target.isApprox (prediction.T_source_target, 1e-15));
  EXPECT_EQ (loaded.static_cluster, 0);
  EXPECT_DOUBLE_EQ (loaded.seconds, 0.25);
  // Recomputing the scores from the files gives the same numbers.
  EXPECT_DOUBLE_EQ (pcl_crf::scorePair (pair, loaded).association_accuracy,
                    pcl_crf::scorePair (pair, prediction).association_accuracy);
  fs::remove (dir / "prediction.pcd");
  EXPECT_THROW (pcl_crf::loadPrediction (dir.string ()), pcl_crf::DatasetError);
  fs::remove_all (dir);
}

using pcl_crf::test::replaceInFile;

TEST (Evaluation, LoadPredictionIsStrict)
{
  // An empty prediction.txt, any version and out-of-range labels used to load.
  const auto pair = pcl_crf::test::staticRoomPair (pcl_crf::makeRigid2d (0.2, 0.1, 0.05));
  OracleMethod oracle;
  const pcl_crf::Prediction prediction = oracle.predict (pair);
  const fs::path dir = fs::temp_directory_path () / "pcl_crf_prediction_strict";
  const fs::path text = dir / "prediction.txt", cloud = dir / "prediction.pcd";
  const std::pair<std::function<void ()>, std::string> cases[] = {
      {[&] { std::ofstream (text, std::ios::trunc); }, "prediction.txt: empty file"},
      {[&] { replaceInFile (text, "pcl_crf_prediction 1", "pcl_crf_prediction 2"); }, "expected the header"},
      {[&] { replaceInFile (text, "pcl_crf_prediction 1", "pcl_crf_prediction 1abc"); }, "expected the header"},
      {[&] { replaceInFile (text, "has_match 1", "has_match 7"); }, "'has_match' must be 0 or 1, got '7'"},
      {[&] { replaceInFile (text, "has_cluster 1\n", ""); }, "missing 'has_cluster' line"},
      {[&] { replaceInFile (text, "seconds", "second"); }, "unknown key 'second'"},
      {[&] { replaceInFile (text, "cluster 0 static", "cluster 1 static"); }, "expected cluster 0, got '1'"},
      {[&] { replaceInFile (cloud, " 0 -1\n", " 5 -1\n"); }, "has cluster 5, out of range [0, 1) and not -1"},
      {[&] { replaceInFile (cloud, " 0 -1\n", " 0 -7\n"); }, "has match -7, negative and not -1"},
      {[&] { replaceInFile (text, "cluster 0 static ", "cluster 0 static 1e300 "); }, "a translation beyond 1e18 m"},
  };
  for (const auto& [corrupt, message] : cases) {
    fs::remove_all (dir);
    pcl_crf::Prediction saved = prediction;
    saved.source_match[3] = pcl_crf::kNoMatch;
    pcl_crf::savePrediction (pair, saved, "oracle", dir.string ());
    corrupt ();
    try {
      pcl_crf::loadPrediction (dir.string ());
      ADD_FAILURE () << "accepted a prediction corrupted for: " << message;
    }
    catch (const pcl_crf::DatasetError& error) {
      EXPECT_NE (std::string (error.what ()).find (message), std::string::npos) << error.what ();
    }
  }
  fs::remove_all (dir);
}

}  // namespace
