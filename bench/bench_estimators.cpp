// Times every registered method per scan pair, next to PCL ICP on the same pairs.
//
// Scenarios: the shipped 361-beam test split (2-4 m apart), simulated 1081-beam
// pairs over 270° (Hokuyo-like, 0.25° apart, 2-4 m apart) and consecutive 361-beam
// scans over 180° at 75 Hz (SICK-like).
// Learned methods load data/models/<name>.model. After Google Benchmark's own
// report, a table gives the median time per pair and the ratio to ICP.
//
// Usage: pcl_crf_bench_estimators [--methods a,b] [google benchmark flags]

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <cmath>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

namespace {

namespace fs = std::filesystem;

struct Scenario
{
  std::string name;
  std::vector<pcl_crf::ScanPair> pairs;
};

std::vector<pcl_crf::ScanPair>
simulatePairs (int beams, double field_of_view, pcl_crf::simulation::ScanSpacing spacing, std::size_t count)
{
  pcl_crf::simulation::SimulatorConfig config;
  config.laser.beam_count = beams;
  config.laser.field_of_view = field_of_view;
  config.spacing = spacing;
  config.seed = 4242;
  return pcl_crf::simulation::ScanPairSimulator (config).simulateDataset (0, count);
}

std::vector<Scenario>
makeScenarios ()
{
  std::vector<Scenario> scenarios;
  const fs::path shipped = fs::path (PCL_CRF_SOURCE_DIR) / "data" / "default" / "test";
  if (fs::is_directory (shipped))
    scenarios.push_back ({"361_beams_2-4m", pcl_crf::loadDataset (shipped.string ())});
  scenarios.push_back ({"361_beams_75Hz", simulatePairs (361, M_PI, pcl_crf::simulation::ScanSpacing::Consecutive, 20)});
  scenarios.push_back ({"1081_beams_270deg", simulatePairs (1081, 1.5 * M_PI, pcl_crf::simulation::ScanSpacing::Travel, 20)});
  return scenarios;
}

std::unique_ptr<pcl_crf::EvaluationMethod>
loadMethod (const std::string& name)
{
  auto method = pcl_crf::createEvaluationMethod (name);
  if (method->isLearned ())
    method->loadModel ((fs::path (PCL_CRF_SOURCE_DIR) / "data" / "models" / (name + ".model")).string ());
  return method;
}

/** Median over pairs of each pair's best-of-three time [ms]. */
double
medianMillisecondsPerPair (pcl_crf::EvaluationMethod& method, const std::vector<pcl_crf::ScanPair>& pairs)
{
  std::vector<double> times;
  for (const auto& pair : pairs) {
    double best = 1e30;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const auto start = std::chrono::steady_clock::now ();
      benchmark::DoNotOptimize (method.predict (pair));
      best = std::min (best, std::chrono::duration<double, std::milli> (std::chrono::steady_clock::now () - start).count ());
    }
    times.push_back (best);
  }
  std::nth_element (times.begin (), times.begin () + times.size () / 2, times.end ());
  return times[times.size () / 2];
}

std::vector<std::string>
chosenMethods (int& argc, char** argv)
{
  std::vector<std::string> methods;
  for (int i = 1; i < argc; ++i)
    if (std::strncmp (argv[i], "--methods=", 10) == 0) {
      std::stringstream in (argv[i] + 10);
      std::string name;
      while (std::getline (in, name, ','))
        methods.push_back (name);
      std::copy (argv + i + 1, argv + argc, argv + i);
      --argc;
      break;
    }
  if (methods.empty ())
    for (const auto& name : pcl_crf::availableEvaluationMethods ())
      methods.push_back (name);
  if (std::find (methods.begin (), methods.end (), "icp") == methods.end ())
    methods.insert (methods.begin (), "icp");
  return methods;
}

}  // namespace

int
main (int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::strcmp (argv[i], "--help") == 0)  // before Google Benchmark's own options
      std::printf ("pcl_crf_bench_estimators [--methods=NAME,NAME,...] [Google Benchmark options]\n"
                   "  --methods=...  the methods of pcl_crf_eval to time (default: all of them); PCL ICP is\n"
                   "                 always timed as well, and the table after the run gives each method's\n"
                   "                 median ms per pair and its speed-up over ICP\n\n");
  const std::vector<std::string> method_names = chosenMethods (argc, argv);
  const std::vector<Scenario> scenarios = makeScenarios ();
  std::map<std::string, std::shared_ptr<pcl_crf::EvaluationMethod>> methods;
  for (const auto& name : method_names) {
    try {
      methods[name] = loadMethod (name);
    }
    catch (const std::exception& error) {
      std::fprintf (stderr, "skipping %s: %s\n", name.c_str (), error.what ());
    }
  }
  for (const auto& scenario : scenarios)
    for (const auto& [name, method] : methods) {
      const auto* pairs = &scenario.pairs;
      auto shared = method;
      benchmark::RegisterBenchmark (("predict/" + name + "/" + scenario.name).c_str (),
                                    [pairs, shared] (benchmark::State& state) {
                                      std::size_t k = 0;
                                      for (auto _ : state)
                                        benchmark::DoNotOptimize (shared->predict ((*pairs)[k++ % pairs->size ()]));
                                    })
          ->Unit (benchmark::kMillisecond);
    }
  benchmark::Initialize (&argc, argv);
  benchmark::RunSpecifiedBenchmarks ();
  benchmark::Shutdown ();

  std::printf ("\nmedian time per pair [ms] (best of 3 per pair), one core; ratio = ICP time / method time\n");
  std::printf ("%-18s %-18s %12s %12s\n", "scenario", "method", "ms/pair", "x faster");
  for (const auto& scenario : scenarios) {
    double icp_ms = 0.0;
    if (methods.count ("icp"))
      icp_ms = medianMillisecondsPerPair (*methods.at ("icp"), scenario.pairs);
    for (const auto& name : method_names) {
      if (!methods.count (name))
        continue;
      const double ms = name == "icp" ? icp_ms : medianMillisecondsPerPair (*methods.at (name), scenario.pairs);
      std::printf ("%-18s %-18s %12.3f %12.2f\n", scenario.name.c_str (), name.c_str (), ms, icp_ms / ms);
    }
  }
  return 0;
}
