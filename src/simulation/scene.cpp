#include <pcl_crf/simulation/scene.h>
#include <pcl_crf/simulation/rigid_math.h>

#include <cmath>

namespace pcl_crf {
namespace simulation {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

/** Below this yaw rate [rad/s] the arc formula is replaced by the straight line. */
constexpr double kStraightYawRate = 1e-9;

}  // namespace

Rigid2d
Trajectory::poseAt (double t) const
{
  const double theta0 = rotationAngle (start);
  const Eigen::Vector2d p0 = start.translation ();
  double x, y;
  const double theta = theta0 + yaw_rate * t;
  if (std::abs (yaw_rate) < kStraightYawRate) {
    x = p0.x () + speed * t * std::cos (theta0);
    y = p0.y () + speed * t * std::sin (theta0);
  }
  else {
    // Integral of speed * (cos, sin)(theta0 + yaw_rate * s) ds over [0, t].
    const double radius = speed / yaw_rate;
    x = p0.x () + radius * (std::sin (theta) - std::sin (theta0));
    y = p0.y () - radius * (std::cos (theta) - std::cos (theta0));
  }
  return makeRigid2d (x, y, theta);
}

Geometry
SceneObject::geometryAt (double t) const
{
  if (!has_legs)
    return geometry;
  Geometry g = geometry;
  const double swing = legs.amplitude * std::sin (kTwoPi * legs.frequency * t + legs.phase);
  g.addCircle ({swing, legs.half_width}, legs.radius);
  g.addCircle ({-swing, -legs.half_width}, legs.radius);
  return g;
}

void
SceneSnapshot::add (int object_id, Geometry world_geometry)
{
  Entry entry{object_id, std::move (world_geometry), {}};
  entry.bound = entry.geometry.boundingCircle ();
  entries_.push_back (std::move (entry));
}

RayHit
SceneSnapshot::castRay (const Ray& ray, double max_range) const
{
  RayHit hit;
  for (const auto& entry : entries_) {
    // Cull objects whose bounding disc the ray misses or that lie beyond the best hit.
    const Eigen::Vector2d f = entry.bound.centre - ray.origin;
    const double along = dot2 (f, ray.direction);
    const double across2 = dot2 (f, f) - along * along;
    const double r = entry.bound.radius;
    if (dot2 (f, f) > r * r && (along < 0.0 || across2 > r * r))
      continue;
    if (along - r > std::min (hit.range, max_range))
      continue;
    const double t = entry.geometry.intersect (ray);
    if (t < hit.range) {
      hit.range = t;
      hit.object_id = entry.object_id;
    }
  }
  if (hit.range > max_range)
    return {};
  return hit;
}

void
Scene::addObject (SceneObject object)
{
  objects_.push_back (std::move (object));
}

const SceneObject*
Scene::findObject (int id) const
{
  for (const auto& object : objects_)
    if (object.id == id)
      return &object;
  return nullptr;
}

SceneSnapshot
Scene::at (double t) const
{
  SceneSnapshot snapshot;
  for (const auto& object : objects_)
    snapshot.add (object.id, object.geometryAt (t).transformed (object.poseAt (t)));
  return snapshot;
}

}  // namespace simulation
}  // namespace pcl_crf
