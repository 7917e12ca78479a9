#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/simulation/shapes.h>

#include <string>
#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief Planar motion at constant speed and yaw rate (a circular arc, or a
 *  straight line when the yaw rate is 0) starting from a pose at time 0.
 *  The body moves along its own x axis.
 */
struct Trajectory
{
  /** world pose of the body at time 0. */
  Rigid2d start = Rigid2d::Identity ();
  /** forward speed [m/s]. */
  double speed = 0.0;
  /** heading rate [rad/s], counter-clockwise positive. */
  double yaw_rate = 0.0;

  /** \brief The world pose of the body at time \a t [s]. */
  Rigid2d
  poseAt (double t) const;
};

/** \brief Two legs of a walking pedestrian: discs at body (x, +-half_width)
 *  whose x swings as +-amplitude * sin(2 pi frequency t + phase), in antiphase.
 *  Legs make the pedestrian non-rigid: its ground-truth motion is that of the
 *  body frame (the hips).
 */
struct LegGait
{
  double amplitude = 0.0;   ///< swing half-length along the walking direction [m]
  double frequency = 0.0;   ///< stride frequency [Hz]
  double phase = 0.0;       ///< [rad]
  double half_width = 0.1;  ///< lateral distance of each leg from the body axis [m]
  double radius = 0.08;     ///< leg radius [m]
};

/** \brief One object of a simulated scene: its outline in its body frame, how
 *  its body frame moves, and its ground-truth label.
 */
struct SceneObject
{
  /** label written on every point that hits this object. */
  int id = 0;
  /** "world", "car", "pedestrian", "cyclist", ... */
  std::string kind;
  /** true for the static world (its trajectory must not move). */
  bool is_static = false;
  /** the rigid outline in the body frame. */
  Geometry geometry;
  /** how the body frame moves. */
  Trajectory trajectory;
  /** swinging legs added to the geometry when \c has_legs. */
  bool has_legs = false;
  LegGait legs;

  /** \brief World pose of the body frame at time \a t [s]. */
  Rigid2d
  poseAt (double t) const { return trajectory.poseAt (t); }

  /** \brief The body-frame outline at time \a t (rigid geometry plus the legs). */
  Geometry
  geometryAt (double t) const;
};

/** \brief The result of casting one ray. */
struct RayHit
{
  /** distance to the first surface [m], kNoHit when nothing was hit in range. */
  double range = kNoHit;
  /** id of the object hit, -1 when nothing was hit. */
  int object_id = -1;

  bool
  valid () const { return object_id >= 0; }
};

/** \brief Every object of a scene frozen at one instant, in world coordinates,
 *  ready for ray casting.
 */
class SceneSnapshot
{
public:
  /** \brief Adds one object's world-frame outline. */
  void
  add (int object_id, Geometry world_geometry);

  /** \brief The first surface along \a ray no farther than \a max_range [m]
   *  (occlusion: the nearest hit over all objects wins).
   */
  RayHit
  castRay (const Ray& ray, double max_range) const;

private:
  struct Entry
  {
    int object_id;
    Geometry geometry;
    Circle bound;
  };
  std::vector<Entry> entries_;
};

/** \brief A set of static and moving objects.
 *
 *  \code
 *  pcl_crf::simulation::Scene scene;
 *  pcl_crf::simulation::SceneObject wall;
 *  wall.id = 0; wall.kind = "world"; wall.is_static = true;
 *  wall.geometry.addSegment ({10.0, -5.0}, {10.0, 5.0});
 *  scene.addObject (wall);
 *  const auto hit = scene.at (0.0).castRay ({{0.0, 0.0}, {1.0, 0.0}}, 30.0);  // range 10
 *  \endcode
 */
class Scene
{
public:
  /** \brief Adds an object; ids should be unique. */
  void
  addObject (SceneObject object);

  /** \brief The objects in insertion order. */
  const std::vector<SceneObject>&
  getObjects () const { return objects_; }

  /** \brief The object with this id, or nullptr. */
  const SceneObject*
  findObject (int id) const;

  /** \brief The scene at time \a t [s]. */
  SceneSnapshot
  at (double t) const;

private:
  std::vector<SceneObject> objects_;
};

}  // namespace simulation
}  // namespace pcl_crf
