#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/simulation/random_stream.h>
#include <pcl_crf/simulation/scene.h>

#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief Parameters of the simulated 2D laser range finder. */
struct LaserConfig
{
  /** number of beams (181, 361, 1081, ... any value > 1). */
  int beam_count = 361;
  /** angular field of view centred on the sensor's x axis [rad] (default 180 deg);
   *  in (0, 2 pi]. */
  double field_of_view = 3.14159265358979323846;
  /** maximum range [m]; farther surfaces give no return. */
  double range_max = 30.0;
  /** standard deviation of the Gaussian range noise [m]. */
  double range_noise = 0.01;
  /** probability that a beam returns nothing although it hits a surface, in [0, 1). */
  double dropout_probability = 0.01;
  /** write every beam without a return as a point at range_max, labelled as the static
   *  world and never matched (ScanPairSimulator), as a converter that keeps such beams
   *  would; the dataset format leaves them out (data/README.md). */
  bool no_return_points = false;

  /** \brief The beam geometry: angle_min = -fov / 2 and angle_increment =
   *  fov / (beam_count - 1), or fov / beam_count for a full 2 pi turn (so the
   *  first and last beams do not coincide).
   */
  SensorInfo
  sensorInfo () const;
};

/** \brief One simulated scan in the sensor frame, in beam order. */
struct SimulatedScan
{
  /** (x, y) of every return [m], sensor frame, counter-clockwise beam order. */
  Eigen::Matrix2Xd points;
  /** id of the object each point lies on. */
  std::vector<int> object_ids;
  /** the beam index each point comes from. */
  std::vector<int> beams;
};

/** \brief Casts the beams of a 2D laser into a scene with occlusion, maximum
 *  range, Gaussian range noise and random dropouts.
 *
 *  Beam i points at angle_min + i * angle_increment in the sensor frame (x
 *  forward, y left). A beam returns the first surface it meets if that is no
 *  farther than range_max, unless it drops out; the measured range is the true
 *  range plus N(0, range_noise^2). Beams without a return are left out, the
 *  rest keep beam order. Each beam consumes exactly three raw numbers of the
 *  random stream (one uniform for the dropout, two for the noise) whether it
 *  hits or not. The stored coordinates are rounded to what the dataset writer
 *  keeps (float, 8 significant digits), so a simulated pair equals the pair read
 *  back from disk.
 *
 *  \code
 *  pcl_crf::simulation::LaserConfig config;
 *  config.beam_count = 181;
 *  pcl_crf::simulation::LaserScanner scanner (config);
 *  pcl_crf::simulation::RandomStream rng (1);
 *  const auto scan = scanner.scan (scene.at (0.0), pcl_crf::Rigid2d::Identity (), rng);
 *  \endcode
 */
class LaserScanner
{
public:
  LaserScanner () = default;
  explicit LaserScanner (const LaserConfig& config) : config_ (config) {}

  void
  setConfig (const LaserConfig& config) { config_ = config; }

  const LaserConfig&
  getConfig () const { return config_; }

  /** \brief Scans \a snapshot from the world pose \a sensor_pose.
   *  \param[in] snapshot the scene at the scan time
   *  \param[in] sensor_pose the sensor's world pose (x forward, y left)
   *  \param[in,out] rng noise and dropout draws (3 raw numbers per beam)
   */
  SimulatedScan
  scan (const SceneSnapshot& snapshot, const Rigid2d& sensor_pose, RandomStream& rng) const;

private:
  LaserConfig config_;
};

/** \brief The value a coordinate has after a round trip through the dataset
 *  files (PCD ASCII: float printed with 8 significant digits).
 */
double
storedCoordinate (double value);

}  // namespace simulation
}  // namespace pcl_crf
