#pragma once
// Simulated street pairs seen by a Hokuyo-like laser, 1081 beams over 270° (0.25° apart,
// twice as fine as the shipped models' 0.5°), for the tests of thinning and lifting.

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_crf {
namespace test {

/** The simulator's settings for Hokuyo-like pairs of seed \a seed. */
inline simulation::SimulatorConfig
hokuyoConfig (std::uint64_t seed)
{
  simulation::SimulatorConfig config;
  config.seed = seed;
  config.laser.beam_count = 1081;
  config.laser.field_of_view = 1.5 * M_PI;
  return config;
}

/** Pairs \a first … \a first + \a count − 1 of seed \a seed. */
inline std::vector<ScanPair>
hokuyoPairs (std::uint64_t seed, std::size_t count, std::size_t first = 0)
{
  return simulation::ScanPairSimulator (hokuyoConfig (seed)).simulateDataset (first, count);
}

/** Pair \a index of seed \a seed. */
inline ScanPair
hokuyoPair (std::uint64_t seed, std::size_t index)
{
  return simulation::ScanPairSimulator (hokuyoConfig (seed)).simulate (index);
}

}  // namespace test
}  // namespace pcl_crf
