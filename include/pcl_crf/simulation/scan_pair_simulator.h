#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/simulation/laser_scanner.h>
#include <pcl_crf/simulation/urban_scene.h>

#include <Eigen/Core>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief Thrown for an invalid simulator configuration or a pair that cannot
 *  be produced (e.g. a scan with no return); the message says what to change.
 */
class SimulationError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/** \brief How far apart in time the two scans of a pair are. */
enum class ScanSpacing
{
  Travel,      ///< the ego travels a distance drawn uniformly in [travel_min, travel_max]
  Consecutive  ///< one scan period, 1 / scan_rate
};

/** \brief Bounds of validateSimulatorConfig. They include every real 2D laser
 *  (180 to ~4000 beams, ranges up to ~300 m, scan rates of 5 to 100 Hz) with a wide
 *  margin, and keep one pair's simulation time and memory bounded: the cost grows
 *  with beams times scene objects, and the scene with the ego's travel and the range. */
constexpr int kMaxSimulatedBeams = 20000;        ///< beams per scan (--beams)
constexpr double kMaxSimulatedRange = 1000.0;    ///< maximum range [m] (--range)
constexpr double kMaxSimulatedTravel = 100.0;    ///< ego travel between the scans [m] (--travel, --speed / --scan-rate)
constexpr double kMinSimulatedScanRate = 0.1;    ///< scan rate [Hz] (--scan-rate)
constexpr double kMaxSimulatedObjectSpeed = 100.0;  ///< speed of a moving object [m/s] (--object-speed)
/** the slowest moving object [m/s] (--object-speed): with kMinSimulatedScanInterval, a
 *  moving object's motion differs from the static world's (a standing one is part of it). */
constexpr double kMinSimulatedObjectSpeed = 0.01;
/** the shortest time between the scans [s]: travel / speed (--travel, --speed), or one
 *  scan period (--scan-rate at most 1000 Hz). */
constexpr double kMinSimulatedScanInterval = 1e-3;

/** \brief Every setting of the scan-pair simulator, with defaults. */
struct SimulatorConfig
{
  /** the laser: beams, field of view, range, noise, dropout. */
  LaserConfig laser;

  // ---- ego vehicle
  /** forward speed of the ego vehicle [m/s], >= 0 (> 0 for Travel spacing). */
  double ego_speed = 10.0;
  /** yaw rate of the ego vehicle [rad/s]. */
  double ego_yaw_rate = 0.0;

  // ---- time between the scans
  ScanSpacing spacing = ScanSpacing::Travel;
  /** range of the ego travel between the scans for Travel spacing [m],
   *  0 < travel_min <= travel_max <= kMaxSimulatedTravel, travel_min / ego_speed >=
   *  kMinSimulatedScanInterval. */
  double travel_min = 2.0;
  double travel_max = 4.0;
  /** scan rate for Consecutive spacing [Hz], >= kMinSimulatedScanRate, <= 1 /
   *  kMinSimulatedScanInterval, and ego_speed / scan_rate <= kMaxSimulatedTravel. */
  double scan_rate = 75.0;

  // ---- scene
  SceneType scene = SceneType::Mixed;
  /** moving objects per pair; -1: drawn uniformly in 1..4 per pair (0 for Static). */
  int moving_count = -1;
  TrafficConfig traffic;

  // ---- odometry
  /** standard deviations of the odometry noise on (dx [m], dy [m], dtheta [rad]). */
  Eigen::Vector3d odometry_noise = Eigen::Vector3d (0.1, 0.05, 0.02);

  // ---- naming and randomness
  /** master seed; pair k uses streams derived from (seed, k). */
  std::uint64_t seed = 1;
  /** pair k is named name_prefix + k with at least 4 digits ("pair_0007"). */
  std::string name_prefix = "pair_";
};

/** \brief \throws SimulationError naming the first invalid setting. */
void
validateSimulatorConfig (const SimulatorConfig& config);

/** \brief What was simulated for one pair (for logs and manifests). */
struct PairSummary
{
  std::string name;
  /** the concrete scene type of the pair (Mixed is resolved per pair). */
  SceneType scene = SceneType::Static;
  /** time between the scans [s] and the ego's path length in that time [m]. */
  double duration = 0.0;
  double ego_travel = 0.0;
  /** moving objects placed in the scene / seen by at least one point. */
  int moving_placed = 0;
  int moving_visible = 0;
  /** kinds of the visible moving objects, ids 1, 2, ... in order. */
  std::vector<std::string> moving_kinds;
  int source_points = 0;
  int target_points = 0;
  /** source points with a true match. */
  int matched = 0;
};

/** \brief The world behind one simulated pair, with object ids as in the pair
 *  (moving objects that no point hit are left out).
 */
struct PairScene
{
  Scene scene;
  /** world poses of the sensor at the source and target scans. */
  Rigid2d sensor_pose_source = Rigid2d::Identity ();
  Rigid2d sensor_pose_target = Rigid2d::Identity ();
  /** time between the scans [s]; the source scan is at time 0. */
  double duration = 0.0;
};

/** \brief The association tolerance of the ground truth [m]: about two beam
 *  spacings at \a range plus the noise:
 *  tol = 2 * range * angle_increment + 3 * range_noise + 0.02.
 */
double
matchTolerance (double range, double angle_increment, double range_noise);

/** \brief Fills pair.source_match with the true association rule: source point
 *  p of object o maps to q = T_o * p (T_o = o's T_target_source); its match is
 *  the nearest target point of object o (lowest index on ties) if that lies
 *  within matchTolerance(|q|, ...) of q, otherwise kNoMatch. Several source
 *  points may match the same target point.
 *  \param[in,out] pair a pair with points, labels and objects
 *  \param[in] range_noise the laser's range noise [m]
 */
void
assignTrueMatches (ScanPair& pair, double range_noise);

/** \brief Simulates labelled 2D laser scan pairs of urban driving scenes.
 *
 *  Pair k is a pure function of (config, k): it draws from random streams
 *  derived from (seed, k), so it does not depend on how many pairs are made,
 *  and the same configuration gives byte-identical datasets everywhere.
 *  See data/SIMULATOR.md for the scene layout and the ground-truth rules.
 *
 *  \code
 *  pcl_crf::simulation::SimulatorConfig config;
 *  config.seed = 7;
 *  config.scene = pcl_crf::simulation::SceneType::Overtaking;
 *  pcl_crf::simulation::ScanPairSimulator simulator (config);
 *  pcl_crf::ScanPair pair = simulator.simulate (0);
 *  pcl_crf::saveDataset (simulator.simulateDataset (0, 10), "out");
 *  \endcode
 */
class ScanPairSimulator
{
public:
  /** \brief A simulator with the default configuration. */
  ScanPairSimulator () = default;

  /** \brief \throws SimulationError for an invalid configuration. */
  explicit ScanPairSimulator (const SimulatorConfig& config);

  /** \brief Sets the configuration. \throws SimulationError when invalid
   *  (the previous configuration is kept).
   */
  void
  setConfig (const SimulatorConfig& config);

  const SimulatorConfig&
  getConfig () const { return config_; }

  /** \brief Simulates pair \a index. \throws SimulationError when a scan has no
   *  return at all.
   *  \param[in] index the pair's index k (its name and random streams)
   *  \param[out] summary what was simulated, when not null
   *  \param[out] scene the scene and sensor poses behind the pair, when not null
   */
  ScanPair
  simulate (std::size_t index, PairSummary* summary = nullptr, PairScene* scene = nullptr) const;

  /** \brief Simulates pairs first .. first + count - 1. */
  std::vector<ScanPair>
  simulateDataset (std::size_t first, std::size_t count, std::vector<PairSummary>* summaries = nullptr) const;

  /** \brief The name of pair \a index: name_prefix followed by at least 4 digits. */
  std::string
  pairName (std::size_t index) const;

private:
  SimulatorConfig config_;
};

}  // namespace simulation
}  // namespace pcl_crf
