#include <pcl_crf/simulation/shapes.h>
#include <pcl_crf/simulation/rigid_math.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace simulation {
namespace {

/** Hits closer than this to the ray origin are ignored [m]. */
constexpr double kMinHitDistance = 1e-9;

double
cross (const Eigen::Vector2d& u, const Eigen::Vector2d& v)
{
  return u.x () * v.y () - u.y () * v.x ();
}

}  // namespace

double
intersect (const Ray& ray, const Segment& segment)
{
  // origin + t d = a + s e  =>  t = (w x e) / (d x e),  s = (w x d) / (d x e),  w = a - origin
  const Eigen::Vector2d e = segment.b - segment.a;
  const Eigen::Vector2d w = segment.a - ray.origin;
  const double denominator = cross (ray.direction, e);
  if (std::abs (denominator) <= 1e-15 * std::sqrt (dot2 (e, e)))
    return kNoHit;
  const double t = cross (w, e) / denominator;
  const double s = cross (w, ray.direction) / denominator;
  if (t <= kMinHitDistance || s < 0.0 || s > 1.0)
    return kNoHit;
  return t;
}

double
intersect (const Ray& ray, const Circle& circle)
{
  // |origin + t d - c|^2 = r^2 with |d| = 1:  t = -b -+ sqrt(b^2 - f.f + r^2)
  const Eigen::Vector2d f = ray.origin - circle.centre;
  const double b = dot2 (f, ray.direction);
  const double c = dot2 (f, f) - circle.radius * circle.radius;
  if (c <= 0.0)
    return kNoHit;  // origin inside (or on) the disc
  const double discriminant = b * b - c;
  if (discriminant < 0.0)
    return kNoHit;
  const double t = -b - std::sqrt (discriminant);
  return t > kMinHitDistance ? t : kNoHit;
}

void
Geometry::addBox (double length, double width, const Rigid2d& pose)
{
  const double hl = 0.5 * length, hw = 0.5 * width;
  const std::vector<Eigen::Vector2d> corners = {
      transformPoint (pose, {hl, hw}), transformPoint (pose, {-hl, hw}), transformPoint (pose, {-hl, -hw}),
      transformPoint (pose, {hl, -hw}), transformPoint (pose, {hl, hw})};
  addPolyline (corners);
}

void
Geometry::addPolyline (const std::vector<Eigen::Vector2d>& vertices)
{
  for (std::size_t k = 1; k < vertices.size (); ++k)
    addSegment (vertices[k - 1], vertices[k]);
}

void
Geometry::addSegment (const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  segments.push_back ({a, b});
}

void
Geometry::addCircle (const Eigen::Vector2d& centre, double radius)
{
  circles.push_back ({centre, radius});
}

Geometry
Geometry::transformed (const Rigid2d& T) const
{
  Geometry out;
  out.segments.reserve (segments.size ());
  out.circles.reserve (circles.size ());
  for (const auto& s : segments)
    out.segments.push_back ({transformPoint (T, s.a), transformPoint (T, s.b)});
  for (const auto& c : circles)
    out.circles.push_back ({transformPoint (T, c.centre), c.radius});
  return out;
}

Circle
Geometry::boundingCircle () const
{
  if (empty ())
    return {};
  Eigen::Vector2d lo = Eigen::Vector2d::Constant (kNoHit), hi = -lo;
  auto grow = [&] (const Eigen::Vector2d& p, double r) {
    lo = lo.cwiseMin ((p.array () - r).matrix ());
    hi = hi.cwiseMax ((p.array () + r).matrix ());
  };
  for (const auto& s : segments) {
    grow (s.a, 0.0);
    grow (s.b, 0.0);
  }
  for (const auto& c : circles)
    grow (c.centre, c.radius);
  Circle bound;
  bound.centre = 0.5 * (lo + hi);
  for (const auto& s : segments)
    bound.radius = std::max ({bound.radius, std::sqrt (squaredDistance2 (s.a, bound.centre)),
                              std::sqrt (squaredDistance2 (s.b, bound.centre))});
  for (const auto& c : circles)
    bound.radius = std::max (bound.radius, std::sqrt (squaredDistance2 (c.centre, bound.centre)) + c.radius);
  return bound;
}

double
Geometry::intersect (const Ray& ray) const
{
  double best = kNoHit;
  for (const auto& s : segments)
    best = std::min (best, simulation::intersect (ray, s));
  for (const auto& c : circles)
    best = std::min (best, simulation::intersect (ray, c));
  return best;
}

}  // namespace simulation
}  // namespace pcl_crf
