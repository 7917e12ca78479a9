// The clustering evaluation methods ("crf-t", "kmeans", "cbd") on simulated pairs and
// on the shipped default split.

#include <pcl_crf/evaluation/clustering_methods.h>
#include <pcl_crf/evaluation/evaluate.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

namespace {

using namespace pcl_crf;

std::vector<ScanPair>
simulate (std::uint64_t seed, std::size_t count)
{
  simulation::SimulatorConfig config;
  config.seed = seed;
  return simulation::ScanPairSimulator (config).simulateDataset (0, count);
}

double
meanOf (const MethodEvaluation& evaluation, const std::string& metric)
{
  for (const MetricSummary& row : evaluation.summary)
    if (row.name == metric)
      return row.mean;
  return -1.0;
}

TEST (ClusteringMethods, CrfClusteringBeatsTheBaselinesOnSimulatedPairs)
{
  // 20 training pairs: cross-validating the prior on fewer is too noisy (measured: 9
  // pairs V 0.75, 20 pairs V 0.91 on these 8 test pairs).
  const std::vector<ScanPair> training = simulate (101, 20), test = simulate (202, 8);
  auto crf = makeCrfClusteringTrueAssociationsMethod ();
  auto kmeans = makeKMeansMethod ();
  auto cbd = makeConsistencyMethod ();
  EXPECT_EQ (crf->name (), "crf-t");
  EXPECT_EQ (kmeans->name (), "kmeans");
  EXPECT_EQ (cbd->name (), "cbd");
  EXPECT_TRUE (crf->isLearned ());
  EXPECT_TRUE (kmeans->isLearned ());
  EXPECT_FALSE (cbd->isLearned ());
  EXPECT_FALSE (makeKMeansMethod (4)->isLearned ());
  EXPECT_THROW (crf->predict (test[0]), std::runtime_error);  // not trained yet
  crf->train (training);
  kmeans->train (training);
  const double v_crf = meanOf (evaluateMethod (*crf, test), "v_measure");
  const double v_kmeans = meanOf (evaluateMethod (*kmeans, test), "v_measure");
  const double v_cbd = meanOf (evaluateMethod (*cbd, test), "v_measure");
  EXPECT_GT (v_crf, 0.85);
  EXPECT_GT (v_crf, v_kmeans + 0.2);
  EXPECT_GT (v_crf, v_cbd + 0.2);
}

TEST (ClusteringMethods, ModelFilesRoundTrip)
{
  const std::vector<ScanPair> training = simulate (101, 6);
  const std::string dir = ::testing::TempDir ();
  auto crf = makeCrfClusteringTrueAssociationsMethod ();
  EXPECT_THROW (crf->saveModel (dir + "/untrained.model"), std::runtime_error);
  crf->train (training);
  crf->saveModel (dir + "/crf-t.model");
  auto loaded = makeCrfClusteringTrueAssociationsMethod ();
  loaded->loadModel (dir + "/crf-t.model");
  const Prediction a = crf->predict (training[0]), b = loaded->predict (training[0]);
  EXPECT_EQ (a.source_cluster, b.source_cluster);
  ASSERT_EQ (a.cluster_motions.size (), b.cluster_motions.size ());
  EXPECT_TRUE (a.cluster_motions[0].isApprox (b.cluster_motions[0], 1e-12));
  EXPECT_TRUE (a.source_match.empty ());  // crf-t reports no association of its own

  auto kmeans = makeKMeansMethod ();
  kmeans->train (training);
  kmeans->saveModel (dir + "/kmeans.model");
  auto kmeans_loaded = makeKMeansMethod ();
  kmeans_loaded->loadModel (dir + "/kmeans.model");
  EXPECT_EQ (kmeans->predict (training[1]).source_cluster, kmeans_loaded->predict (training[1]).source_cluster);
  EXPECT_THROW (kmeans_loaded->loadModel (dir + "/crf-t.model"), std::runtime_error);
  EXPECT_THROW (loaded->loadModel (dir + "/kmeans.model"), std::runtime_error);
  std::remove ((dir + "/crf-t.model").c_str ());
  std::remove ((dir + "/kmeans.model").c_str ());
}

TEST (ClusteringMethods, AnyAssociationProviderCanFeedTheClusterer)
{
  const std::vector<ScanPair> training = simulate (101, 4);
  // Associations from elsewhere (here: the truth with every third match dropped).
  auto provider = [] (const ScanPair& pair) {
    std::vector<int> matches = pair.source_match;
    for (std::size_t i = 0; i < matches.size (); i += 3)
      matches[i] = kNoMatch;
    return matches;
  };
  auto method = makeCrfClusteringMethod ("crf-x", provider, true);
  EXPECT_EQ (method->name (), "crf-x");
  method->train (training);
  const Prediction prediction = method->predict (training[2]);
  EXPECT_EQ (prediction.source_match, provider (training[2]));
  EXPECT_EQ (prediction.source_cluster.size (), static_cast<std::size_t> (training[2].source.cols ()));
  EXPECT_THROW (makeCrfClusteringMethod ("none", AssociationProvider (), false), std::invalid_argument);
}

TEST (ClusteringMethods, ShippedModelMeetsTheTargetOnTheDefaultTestSplit)
{
  const std::string root = PCL_CRF_SOURCE_DIR;
  if (!std::filesystem::exists (root + "/data/default/test") ||
      !std::filesystem::exists (root + "/data/models/crf-t.model"))
    GTEST_SKIP () << "data/default/test or data/models/crf-t.model is missing";
  auto crf = makeCrfClusteringTrueAssociationsMethod ();
  crf->loadModel (root + "/data/models/crf-t.model");
  const MethodEvaluation evaluation = evaluateMethod (*crf, loadDataset (root + "/data/default/test"));
  EXPECT_GE (meanOf (evaluation, "v_measure"), 0.95);
}

}  // namespace
