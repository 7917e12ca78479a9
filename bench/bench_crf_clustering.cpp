// Speed of CRF-Clustering on one 361-beam scan pair (and of the baselines).
// Run: build/bench/pcl_crf_bench_crf_clustering [--benchmark_filter=...]

#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/motion_kmeans.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/crf_clusterer.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <benchmark/benchmark.h>

namespace {

using namespace pcl_crf;

/** Pair 0 of the simulator's default configuration (mixed urban scene, 361 beams). */
const ScanPair&
benchPair ()
{
  static const ScanPair pair = simulation::ScanPairSimulator ().simulate (0);
  return pair;
}

/** Weights of the order of data/models/crf-t.model. */
Eigen::VectorXd
benchWeights ()
{
  Eigen::VectorXd w (clustering::kWeightCount);
  w << 0.0289, -3.28, 0.0606, 4.47, -0.724;
  return w;
}

void
BM_CrfClusteringPointPairs (benchmark::State& state)
{
  const ScanPair& pair = benchPair ();
  const clustering::PointPairs pairs = clustering::makePointPairs (pair.source, pair.target, pair.source_match);
  const Eigen::VectorXd w = benchWeights ();
  clustering::CrfClusteringParameters parameters;
  parameters.max_states = static_cast<int> (state.range (0));
  int iterations = 0, clusters = 0;
  for (auto _ : state)
  {
    const clustering::CrfClusteringResult result = clustering::clusterPointPairs (pairs, w, parameters, &pair.odometry);
    iterations = result.iterations;
    clusters = static_cast<int> (result.motions.size ());
    benchmark::DoNotOptimize (result.labels.data ());
  }
  state.counters["nodes"] = static_cast<double> (pairs.size ());
  state.counters["rounds"] = iterations;
  state.counters["clusters"] = clusters;
}
BENCHMARK (BM_CrfClusteringPointPairs)->Arg (2)->Arg (5)->Arg (100)->Unit (benchmark::kMicrosecond);

void
BM_CrfClusteringWholeScan (benchmark::State& state)
{
  const ScanPair& pair = benchPair ();
  const Eigen::VectorXd w = benchWeights ();
  for (auto _ : state)
  {
    const clustering::ScanClustering result =
        clustering::clusterScan (pair.source, pair.target, pair.source_match, w, {}, &pair.odometry,
                                 clustering::UnpairedLabelling::NearestSegmentNeighbour);
    benchmark::DoNotOptimize (result.source_cluster.data ());
  }
  state.counters["points"] = static_cast<double> (pair.source.cols ());
}
BENCHMARK (BM_CrfClusteringWholeScan)->Unit (benchmark::kMicrosecond);

void
BM_CRFClustererPcl (benchmark::State& state)
{
  const ScanPair& pair = benchPair ();
  auto toCloud = [] (const Eigen::Matrix2Xd& xy) {
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZ>);
    for (Eigen::Index i = 0; i < xy.cols (); ++i)
      cloud->push_back (pcl::PointXYZ (static_cast<float> (xy (0, i)), static_cast<float> (xy (1, i)), 0.0f));
    return cloud;
  };
  const auto source = toCloud (pair.source), target = toCloud (pair.target);
  pcl::CorrespondencesPtr correspondences (new pcl::Correspondences);
  for (std::size_t i = 0; i < pair.source_match.size (); ++i)
    if (pair.source_match[i] != kNoMatch)
      correspondences->emplace_back (static_cast<int> (i), pair.source_match[i], 0.0f);
  CRFClusterer<pcl::PointXYZ> clusterer;
  clusterer.setInputSource (source);
  clusterer.setInputTarget (target);
  clusterer.setCorrespondences (correspondences);
  clusterer.setWeights (benchWeights ());
  Eigen::Matrix4f odometry = Eigen::Matrix4f::Identity ();
  odometry.topLeftCorner<2, 2> () = pair.odometry.T_source_target.linear ().cast<float> ();
  odometry.topRightCorner<2, 1> () = pair.odometry.T_source_target.translation ().cast<float> ();
  clusterer.setOdometry (odometry, pair.odometry.covariance);
  std::vector<pcl::PointIndices> clusters;
  for (auto _ : state)
  {
    clusterer.extract (clusters);
    benchmark::DoNotOptimize (clusters.data ());
  }
}
BENCHMARK (BM_CRFClustererPcl)->Unit (benchmark::kMicrosecond);

void
BM_KMeans (benchmark::State& state)
{
  const ScanPair& pair = benchPair ();
  const clustering::PointPairs pairs = clustering::makePointPairs (pair.source, pair.target, pair.source_match);
  clustering::MotionKMeansParameters parameters;
  parameters.cluster_count = 5;
  for (auto _ : state)
    benchmark::DoNotOptimize (clustering::clusterKMeans (pairs, parameters).labels.data ());
}
BENCHMARK (BM_KMeans)->Unit (benchmark::kMicrosecond);

void
BM_ConsistencyDetection (benchmark::State& state)
{
  const ScanPair& pair = benchPair ();
  const Rigid2d T = pair.odometry.T_source_target.inverse ();
  for (auto _ : state)
    benchmark::DoNotOptimize (
        clustering::detectDynamicSegments (pair.source, pair.target, pair.sensor, T, {}, &pair.odometry.covariance)
            .data ());
}
BENCHMARK (BM_ConsistencyDetection)->Unit (benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN ();
