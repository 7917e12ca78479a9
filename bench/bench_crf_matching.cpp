// Google Benchmark of CRF-Matching on one simulated 361-beam street pair, next to
// PCL ICP (the baseline) on the same pair.
//
//   build/bench/pcl_crf_bench_crf_matching [--benchmark_filter=...]
//
// The model is trained at start-up on 8 simulated pairs (default settings), so the
// program needs no data file.

#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/crf_matcher.h>
#include <pcl_crf/matching/matching_learner.h>
#include <pcl_crf/matching/scan_matching.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <benchmark/benchmark.h>

namespace {

namespace m = pcl_crf::matching;

/** The benchmark pair and a model trained on other pairs, built once. */
struct Fixture
{
  pcl_crf::ScanPair pair;
  m::CrfMatchingModel model;

  Fixture ()
  {
    pcl_crf::simulation::SimulatorConfig config;
    config.seed = 2002;
    pair = pcl_crf::simulation::ScanPairSimulator (config).simulate (0);
    config.seed = 1001;
    model = m::trainCrfMatching (pcl_crf::simulation::ScanPairSimulator (config).simulateDataset (0, 8), {});
  }
};

const Fixture&
fixture ()
{
  static const Fixture f;
  return f;
}

void
BM_CrfMatching_Pair (benchmark::State& state)
{
  const Fixture& f = fixture ();
  const m::MotionGuess guess = m::MotionGuess::fromOdometry (f.pair.odometry);
  for (auto _ : state)
    benchmark::DoNotOptimize (m::matchScans (f.pair.source, f.pair.target, guess, f.model));
  state.counters["source_points"] = static_cast<double> (f.pair.source.cols ());
}
BENCHMARK (BM_CrfMatching_Pair)->Unit (benchmark::kMicrosecond);

void
BM_CrfMatching_PairSinglePass (benchmark::State& state)
{
  const Fixture& f = fixture ();
  const m::MotionGuess guess = m::MotionGuess::fromOdometry (f.pair.odometry);
  m::CrfMatchingModel model = f.model;
  model.parameters.passes = 1;
  for (auto _ : state)
    benchmark::DoNotOptimize (m::matchScans (f.pair.source, f.pair.target, guess, model));
}
BENCHMARK (BM_CrfMatching_PairSinglePass)->Unit (benchmark::kMicrosecond);

void
BM_CrfMatching_PrepareTarget (benchmark::State& state)
{
  const Fixture& f = fixture ();
  for (auto _ : state)
    benchmark::DoNotOptimize (m::prepareTarget (f.pair.target, f.model.parameters.candidates));
}
BENCHMARK (BM_CrfMatching_PrepareTarget)->Unit (benchmark::kMicrosecond);

void
BM_CrfMatching_OnePass (benchmark::State& state)
{
  const Fixture& f = fixture ();
  const m::MotionGuess guess = m::MotionGuess::fromOdometry (f.pair.odometry);
  const m::PreparedTarget target = m::prepareTarget (f.pair.target, f.model.parameters.candidates);
  const m::ScanShape source = m::describeScan (f.pair.source);
  for (auto _ : state)
    benchmark::DoNotOptimize (
        m::runPass (source, target, guess, guess.T_target_source, f.model.stages[0], f.model.parameters));
}
BENCHMARK (BM_CrfMatching_OnePass)->Unit (benchmark::kMicrosecond);

void
BM_CrfMatching_Candidates (benchmark::State& state)
{
  const Fixture& f = fixture ();
  const pcl_crf::Rigid2d guess = f.pair.odometry.T_source_target.inverse ();
  const m::PreparedTarget target = m::prepareTarget (f.pair.target, f.model.parameters.candidates);
  const m::ScanShape source = m::describeScan (f.pair.source);
  for (auto _ : state)
    benchmark::DoNotOptimize (m::preparePass (source, target, guess, guess, f.model.parameters.candidates));
}
BENCHMARK (BM_CrfMatching_Candidates)->Unit (benchmark::kMicrosecond);

void
BM_CrfMatcher_Pcl (benchmark::State& state)
{
  const Fixture& f = fixture ();
  pcl::PointCloud<pcl::PointXYZ>::Ptr source (new pcl::PointCloud<pcl::PointXYZ>);
  pcl::PointCloud<pcl::PointXYZ>::Ptr target (new pcl::PointCloud<pcl::PointXYZ>);
  pcl_crf::fromMatrix2X (f.pair.source, *source);
  pcl_crf::fromMatrix2X (f.pair.target, *target);
  pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ> matcher;
  matcher.setModel (f.model);
  matcher.setInputSource (source);
  matcher.setInputTarget (target);
  matcher.setOdometry (f.pair.odometry);
  pcl::Correspondences correspondences;
  for (auto _ : state) {
    matcher.determineCorrespondences (correspondences);
    benchmark::DoNotOptimize (correspondences.data ());
  }
}
BENCHMARK (BM_CrfMatcher_Pcl)->Unit (benchmark::kMicrosecond);

void
BM_PclIcp_Pair (benchmark::State& state)
{
  const Fixture& f = fixture ();
  for (auto _ : state)
    benchmark::DoNotOptimize (pcl_crf::runIcpBaseline (f.pair));
}
BENCHMARK (BM_PclIcp_Pair)->Unit (benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN ();
