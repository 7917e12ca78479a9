#pragma once

#include <pcl_crf/simulation/random_stream.h>
#include <pcl_crf/simulation/scene.h>

#include <string>
#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief What the moving objects of a simulated urban scene do. */
enum class SceneType
{
  Mixed,        ///< per pair, one of the others at random, plus a random mix of traffic
  Outline,      ///< a long vehicle seen broadside moving along its own visible outline
  Crossing,     ///< pedestrians, cyclists and cars crossing the street ahead
  Overtaking,   ///< cars overtaking the ego vehicle in the adjacent lane
  Opposite,     ///< cars in the opposite lane
  Pedestrians,  ///< pedestrians on the sidewalks or crossing
  Static        ///< no moving object
};

/** \brief The lower-case name used on the command line ("mixed", "outline", ...). */
std::string
sceneTypeName (SceneType type);

/** \brief Parses a scene name; false (type untouched) for an unknown name. */
bool
parseSceneType (const std::string& name, SceneType& type);

/** \brief The scene types a Mixed scene draws from (every type but Mixed). */
std::vector<SceneType>
concreteSceneTypes ();

/** \brief Settings of the moving objects. */
struct TrafficConfig
{
  /** speed of every moving object [m/s]; negative: drawn per kind and scene
   *  (see data/SIMULATOR.md). */
  double object_speed = -1.0;
  /** fraction of pedestrians simulated as two swinging legs instead of one disc. */
  double legged_pedestrian_fraction = 0.5;
};

/** \brief What to build for one scan pair. */
struct UrbanSceneSpec
{
  /** a concrete type (not Mixed): the first moving object follows it. */
  SceneType type = SceneType::Static;
  /** when true, objects after the first may follow other types (a Mixed pair). */
  bool mix_types = false;
  /** number of moving objects to place; fewer are placed when no free spot is found. */
  int moving_count = 0;
  /** the ego sensor's motion (world frame; the street runs along +x from the
   *  ego's start at the origin). */
  Trajectory ego;
  /** time between the two scans [s]. */
  double duration = 0.0;
  /** extent of the generated street along x [m]. */
  double x_min = -40.0;
  double x_max = 40.0;
  TrafficConfig traffic;
};

/** \brief Builds a street scene: object 0 ("world", static) holds the façades
 *  (with gaps, recesses and side walls), back walls, parked cars, poles and
 *  trees; moving objects 1..N ("car", "pedestrian", "cyclist") follow
 *  \a spec.type. Objects never overlap each other, the ego vehicle or the
 *  static obstacles at the start, middle and end of the pair.
 *  \param[in] spec what to build
 *  \param[in,out] world_rng draws of the static street only
 *  \param[in,out] traffic_rng draws of the moving objects only
 *  \code
 *  pcl_crf::simulation::UrbanSceneSpec spec;
 *  spec.type = pcl_crf::simulation::SceneType::Crossing;
 *  spec.moving_count = 2;
 *  spec.ego.speed = 10.0;
 *  spec.duration = 0.3;
 *  pcl_crf::simulation::RandomStream world_rng (1, 0, 1), traffic_rng (1, 0, 2);
 *  const auto scene = pcl_crf::simulation::generateUrbanScene (spec, world_rng, traffic_rng);
 *  \endcode
 */
Scene
generateUrbanScene (const UrbanSceneSpec& spec, RandomStream& world_rng, RandomStream& traffic_rng);

}  // namespace simulation
}  // namespace pcl_crf
