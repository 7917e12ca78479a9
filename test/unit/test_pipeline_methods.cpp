// The pipeline methods of the joint paper's comparison ("icp+kmeans",
// "crf-matching+kmeans", "crf-m"), their composite model files and leave-one-out.

#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/evaluation/clustering_methods.h>
#include <pcl_crf/evaluation/composite_model.h>
#include <pcl_crf/evaluation/evaluate.h>
#include <pcl_crf/evaluation/matching_methods.h>
#include <pcl_crf/evaluation/pipeline_methods.h>
#include <pcl_crf/clustering/scan_pair_clustering.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using namespace pcl_crf;

std::vector<ScanPair>
simulate (std::uint64_t seed, std::size_t count, simulation::SceneType scene = simulation::SceneType::Mixed,
          int moving = -1)
{
  simulation::SimulatorConfig config;
  config.seed = seed;
  config.scene = scene;
  config.moving_count = moving;
  return simulation::ScanPairSimulator (config).simulateDataset (0, count);
}

/** The three pipelines trained once on 4 simulated pairs (about 1 s), shared by the tests. */
class PipelineMethods : public ::testing::Test
{
protected:
  static void
  SetUpTestSuite ()
  {
    training_ = new std::vector<ScanPair> (simulate (31, 8));
    test_ = new std::vector<ScanPair> (simulate (32, 4, simulation::SceneType::Overtaking, 1));
    methods_ = new std::vector<std::unique_ptr<EvaluationMethod>> ();
    methods_->push_back (makeIcpKMeansMethod ());
    methods_->push_back (makeCrfMatchingKMeansMethod ());
    methods_->push_back (makeCrfMMethod ());
    for (auto& method : *methods_)
      method->train (*training_);
  }

  static void
  TearDownTestSuite ()
  {
    delete methods_;
    delete training_;
    delete test_;
  }

  void
  SetUp () override
  {
    // One folder per test: ctest runs tests in parallel.
    dir_ = fs::temp_directory_path () /
           ("pcl_crf_pipeline_" + std::string (::testing::UnitTest::GetInstance ()->current_test_info ()->name ()));
    fs::remove_all (dir_);
    fs::create_directories (dir_);
  }

  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }

  static EvaluationMethod&
  method (const std::string& name)
  {
    for (auto& method : *methods_)
      if (method->name () == name)
        return *method;
    throw std::invalid_argument (name);
  }

  static PairScores
  score (const std::string& name, const ScanPair& pair)
  {
    return scorePair (pair, method (name).predict (pair));
  }

  std::string
  file (const std::string& name) const
  {
    return (dir_ / name).string ();
  }

  static std::vector<ScanPair>* training_;
  static std::vector<ScanPair>* test_;
  static std::vector<std::unique_ptr<EvaluationMethod>>* methods_;
  fs::path dir_;
};

std::vector<ScanPair>* PipelineMethods::training_ = nullptr;
std::vector<ScanPair>* PipelineMethods::test_ = nullptr;
std::vector<std::unique_ptr<EvaluationMethod>>* PipelineMethods::methods_ = nullptr;

double
meanOf (const std::vector<double>& values)
{
  double sum = 0.0;
  for (const double value : values)
    sum += value;
  return sum / values.size ();
}

TEST_F (PipelineMethods, AreRegisteredInOrderAfterTheExistingMethods)
{
  const std::vector<std::string> names = availableEvaluationMethods ();
  const auto at = [&names] (const std::string& name) {
    return std::find (names.begin (), names.end (), name) - names.begin ();
  };
  ASSERT_LT (at ("crf-m"), static_cast<std::ptrdiff_t> (names.size ()));
  EXPECT_GT (at ("icp+kmeans"), at ("crf-t"));
  EXPECT_EQ (at ("crf-matching+kmeans"), at ("icp+kmeans") + 1);
  EXPECT_EQ (at ("crf-m"), at ("icp+kmeans") + 2);
  for (const char* name : {"icp+kmeans", "crf-matching+kmeans", "crf-m"}) {
    auto method = createEvaluationMethod (name);
    EXPECT_EQ (method->name (), name);
    EXPECT_TRUE (method->isLearned ());
    EXPECT_THROW (method->predict (test_->front ()), std::runtime_error) << name;  // not trained yet
  }
  // A given k: ICP + K-Means then learns nothing and predicts at once.
  MethodSettings settings;
  settings.cluster_count = 3;
  auto fixed = createEvaluationMethod ("icp+kmeans", settings);
  EXPECT_FALSE (fixed->isLearned ());
  EXPECT_LE (fixed->predict (test_->front ()).cluster_motions.size (), 3u);
  EXPECT_THROW (makeAssociationPipeline ("x", nullptr, {}), std::invalid_argument);
  EXPECT_THROW (makeKMeansMethod ("x", AssociationProvider (), true), std::invalid_argument);
}

TEST_F (PipelineMethods, IcpKMeansClustersTheIcpAssociations)
{
  int k = 0;
  for (const ScanPair& pair : *training_)
    k = std::max (k, clustering::associatedObjectCount (pair));
  std::vector<double> accuracy, ego;
  for (const ScanPair& pair : *test_) {
    const Prediction prediction = method ("icp+kmeans").predict (pair);
    EXPECT_EQ (prediction.source_match, runIcpBaseline (pair).source_match);
    EXPECT_GE (prediction.cluster_motions.size (), 2u);
    EXPECT_LE (prediction.cluster_motions.size (), static_cast<std::size_t> (k));
    ASSERT_GE (prediction.static_cluster, 0);
    const Rigid2d& world = prediction.cluster_motions[prediction.static_cluster];
    EXPECT_TRUE (prediction.T_source_target.isApprox (world.inverse ()));
    const PairScores scores = scorePair (pair, prediction);
    accuracy.push_back (scores.association_accuracy);
    ego.push_back (scores.ego_translation_error);
  }
  // Measured: accuracy 0.547, ego error 0.043 m (ICP slides along the street).
  EXPECT_GT (meanOf (accuracy), 0.45);
  EXPECT_LT (meanOf (ego), 0.08);
}

TEST_F (PipelineMethods, CrfMatchingAssociationsBeatIcpsUnderKMeans)
{
  std::vector<double> icp, crf, ego;
  for (const ScanPair& pair : *test_) {
    icp.push_back (score ("icp+kmeans", pair).association_accuracy);
    const PairScores scores = score ("crf-matching+kmeans", pair);
    crf.push_back (scores.association_accuracy);
    ego.push_back (scores.ego_translation_error);
    EXPECT_EQ (method ("crf-matching+kmeans").predict (pair).source_match.size (),
               static_cast<std::size_t> (pair.source.cols ()));
  }
  // Measured: 0.755 against 0.547; ego error 0.018 m.
  EXPECT_GT (meanOf (crf), 0.70);
  EXPECT_GT (meanOf (crf), meanOf (icp) + 0.15);
  EXPECT_LT (meanOf (ego), 0.03);
}

TEST_F (PipelineMethods, CrfMClustersTheSameAssociationsBetterThanKMeans)
{
  std::vector<double> v_crf, v_kmeans, accuracy_crf, accuracy_kmeans, ego;
  for (const ScanPair& pair : *test_) {
    const Prediction prediction = method ("crf-m").predict (pair);
    // The same matcher, trained on the same pairs, feeds both clusterings.
    EXPECT_EQ (prediction.source_match, method ("crf-matching+kmeans").predict (pair).source_match);
    const PairScores crf = scorePair (pair, prediction), kmeans = score ("crf-matching+kmeans", pair);
    v_crf.push_back (crf.v_measure);
    v_kmeans.push_back (kmeans.v_measure);
    accuracy_crf.push_back (crf.cluster_accuracy);
    accuracy_kmeans.push_back (kmeans.cluster_accuracy);
    ego.push_back (crf.ego_translation_error);
  }
  // Measured: V 0.624 against 0.541 (1.0 on the first pair), motion-detection accuracy
  // 0.855 against 0.701, ego error 0.004 m.
  EXPECT_GT (v_crf.front (), 0.99);
  EXPECT_GT (meanOf (v_crf), meanOf (v_kmeans) + 0.05);
  EXPECT_GT (meanOf (accuracy_crf), 0.8);
  EXPECT_GT (meanOf (accuracy_crf), meanOf (accuracy_kmeans) + 0.1);
  EXPECT_LT (meanOf (ego), 0.01);
}

TEST_F (PipelineMethods, CompositeModelRoundTripGivesIdenticalPredictions)
{
  for (const char* name : {"icp+kmeans", "crf-matching+kmeans", "crf-m"}) {
    const std::string path = file (std::string (name) + ".model");
    method (name).saveModel (path);
    auto loaded = createEvaluationMethod (name);
    loaded->loadModel (path);
    for (const ScanPair& pair : *test_) {
      const Prediction a = method (name).predict (pair), b = loaded->predict (pair);
      EXPECT_EQ (a.source_match, b.source_match) << name;
      EXPECT_EQ (a.source_cluster, b.source_cluster) << name;
      EXPECT_EQ (a.static_cluster, b.static_cluster) << name;
      ASSERT_EQ (a.cluster_motions.size (), b.cluster_motions.size ()) << name;
      for (std::size_t c = 0; c < a.cluster_motions.size (); ++c)
        EXPECT_EQ (a.cluster_motions[c].matrix (), b.cluster_motions[c].matrix ()) << name;
      EXPECT_EQ (a.T_source_target.matrix (), b.T_source_target.matrix ()) << name;
    }
  }
  std::ifstream in (file ("crf-m.model"));
  const std::string text ((std::istreambuf_iterator<char> (in)), std::istreambuf_iterator<char> ());
  EXPECT_EQ (text.rfind ("pcl_crf_composite_model 1\n", 0), 0u) << text.substr (0, 200);
  for (const char* line : {"\nmethod crf-m\n", "\nparts crf-matching crf-clustering\n", "\npart crf-matching\n",
                           "\nend_part crf-matching\npart crf-clustering\npcl_crf_crf_clustering_model 1\n"})
    EXPECT_NE (text.find (line), std::string::npos) << line;
  const std::string last = "end_part crf-clustering\n";
  EXPECT_EQ (text.size () - text.rfind (last), last.size ());  // the last line
}

/** The message loadModel gives for \a path, or "no error". */
std::string
loadError (EvaluationMethod& method, const std::string& path)
{
  try {
    method.loadModel (path);
  }
  catch (const std::runtime_error& error) {
    return error.what ();
  }
  return "no error";
}

TEST_F (PipelineMethods, CorruptOrTruncatedCompositeModelIsAClearError)
{
  const auto savedText = [this] (const std::string& name) {
    method (name).saveModel (file (name + ".model"));
    std::ifstream in (file (name + ".model"));
    return std::string ((std::istreambuf_iterator<char> (in)), std::istreambuf_iterator<char> ());
  };
  const std::string text = savedText ("crf-m"), bad = file ("bad.model");
  const auto expectError = [&] (EvaluationMethod& method, const std::string& content, const std::string& what) {
    std::ofstream (bad) << content;
    const std::string message = loadError (method, bad);
    EXPECT_NE (message.find (bad), std::string::npos) << message;
    EXPECT_NE (message.find (what), std::string::npos) << what << " in: " << message;
  };
  auto crf_m = makeCrfMMethod ();
  // Truncated inside the first part, inside the second part, between the parts.
  expectError (*crf_m, text.substr (0, text.size () / 2),
               "inside part 'crf-matching', missing 'end_part crf-matching' (the file is truncated)");
  expectError (*crf_m, text.substr (0, text.find ("end_part crf-clustering")),
               "inside part 'crf-clustering', missing 'end_part crf-clustering' (the file is truncated)");
  expectError (*crf_m, text.substr (0, text.find ("\npart crf-clustering\n") + 1),
               "unexpected end of file, missing 'part crf-clustering' (the file is truncated)");
  expectError (*crf_m, "", "line 1: not a composite model");
  expectError (*crf_m, "pcl_crf_composite_model 2\n", "line 1: unsupported composite model version '2'");
  std::string junk = text;  // trailing words after the version used to be ignored
  junk.insert (junk.find ('\n'), " junk");
  expectError (*crf_m, junk, "line 1: unexpected text 'junk' after the version");
  expectError (*crf_m, text + "part more\n", "unexpected 'part more' after the last part");
  // A part's own error names the file, the part and the line in the whole file.
  std::string corrupt = text;
  const std::size_t stages = corrupt.find ("\nstages ");
  corrupt.replace (stages, 9, "\nstages x");
  const auto line = std::count (text.begin (), text.begin () + stages + 1, '\n') + 1;
  expectError (*crf_m, corrupt, bad + " (part crf-matching): line " + std::to_string (line) + ": 'stages'");
  corrupt = text;
  corrupt.replace (corrupt.find ("\nstiffness "), 11, "\nstiffness nan");
  expectError (*crf_m, corrupt, bad + " (part crf-clustering)");
  corrupt = savedText ("crf-matching+kmeans");
  corrupt.replace (corrupt.find ("cluster_count "), 15, "cluster_count x");
  auto kmeans = makeCrfMatchingKMeansMethod ();
  expectError (*kmeans, corrupt, bad + " (part kmeans)' needs a line 'cluster_count K'");
  // Another method's composite model, a single part's model, no file.
  expectError (*crf_m, savedText ("icp+kmeans"),
               "line 3: a model of another method: expected 'method crf-m', found 'method icp+kmeans'");
  const std::string shipped = std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-t.model";
  EXPECT_NE (loadError (*crf_m, shipped).find ("not a composite model"), std::string::npos) << loadError (*crf_m, shipped);
  EXPECT_NE (loadError (*crf_m, file ("missing.model"))
                 .find ("cannot read the model file '" + file ("missing.model") + "': no such file"),
             std::string::npos);
  fs::create_directories (file ("folder.model"));  // once "truncated: expected the header"
  EXPECT_NE (loadError (*crf_m, file ("folder.model")).find ("': is a directory, not a file"), std::string::npos)
      << loadError (*crf_m, file ("folder.model"));
  // Nothing to save before training: an error, and no file.
  EXPECT_THROW (makeCrfMMethod ()->saveModel (file ("untrained.model")), std::runtime_error);
  EXPECT_FALSE (fs::exists (file ("untrained.model")));
}

/** A learned method that remembers what it was trained on. */
class RecordingMethod : public EvaluationMethod
{
public:
  explicit RecordingMethod (bool learned, std::vector<std::vector<std::string>>* trained)
    : learned_ (learned), trained_ (trained)
  {}

  std::string
  name () const override { return "recording"; }

  bool
  isLearned () const override { return learned_; }

  void
  train (const std::vector<ScanPair>& pairs) override
  {
    trained_->emplace_back ();
    for (const ScanPair& pair : pairs)
      trained_->back ().push_back (pair.name);
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    Prediction prediction;
    prediction.source_match = pair.source_match;
    prediction.source_cluster.assign (pair.source_match.size (), 0);
    prediction.cluster_motions = {pair.objects.front ().T_target_source};
    prediction.static_cluster = 0;
    prediction.T_source_target = pair.odometry.T_source_target;
    return prediction;
  }

private:
  bool learned_;
  std::vector<std::vector<std::string>>* trained_;
};

TEST (LeaveOneOut, TrainsAFreshMethodOnEveryOtherPairPerFold)
{
  std::vector<ScanPair> pairs;
  for (const char* name : {"a", "b", "c", "d"}) {
    pairs.push_back (test::staticRoomPair (makeRigid2d (0.2, 0.0, 0.01), Rigid2d::Identity (), 0.5));
    pairs.back ().name = name;
  }
  std::vector<std::vector<std::string>> trained;
  int made = 0;
  std::vector<std::string> progress;
  const MethodEvaluation evaluation = evaluateLeaveOneOut (
      [&] { return ++made, std::make_unique<RecordingMethod> (true, &trained); }, pairs, 2, {},
      [&progress] (const FoldStatus& fold) {
        progress.push_back (std::to_string (fold.fold) + "/" + std::to_string (fold.folds) + " " + fold.held_out + " " +
                            std::to_string (fold.training_pairs) + (fold.finished ? " done" : ""));
      });
  EXPECT_EQ (made, 2);
  ASSERT_EQ (trained.size (), 2u);
  EXPECT_EQ (trained[0], (std::vector<std::string>{"b", "c", "d"}));
  EXPECT_EQ (trained[1], (std::vector<std::string>{"a", "c", "d"}));
  EXPECT_EQ (progress, (std::vector<std::string>{"1/2 a 3", "1/2 a 3 done", "2/2 b 3", "2/2 b 3 done"}));
  EXPECT_EQ (evaluation.method, "recording");
  EXPECT_EQ (evaluation.pair_names, (std::vector<std::string>{"a", "b"}));
  ASSERT_EQ (evaluation.scores.size (), 2u);
  EXPECT_DOUBLE_EQ (evaluation.scores[1].association_accuracy, 1.0);

  // A method that learns nothing is built once and never trained; 0 holds out every pair.
  trained.clear ();
  made = 0;
  const MethodEvaluation fixed = evaluateLeaveOneOut (
      [&] { return ++made, std::make_unique<RecordingMethod> (false, &trained); }, pairs);
  EXPECT_EQ (made, 1);
  EXPECT_TRUE (trained.empty ());
  EXPECT_EQ (fixed.scores.size (), 4u);
  try {
    evaluateLeaveOneOut ([&] { return std::make_unique<RecordingMethod> (true, &trained); }, {pairs.front ()});
    ADD_FAILURE () << "no exception";
  }
  catch (const std::invalid_argument& error) {
    EXPECT_NE (std::string (error.what ()).find ("at least 2 pairs"), std::string::npos) << error.what ();
  }
}

}  // namespace
