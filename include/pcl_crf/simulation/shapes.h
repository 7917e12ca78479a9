#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace pcl_crf {
namespace simulation {

/** \brief "No intersection" distance returned by the ray tests. */
constexpr double kNoHit = std::numeric_limits<double>::infinity ();

/** \brief A half-line origin + t * direction, t > 0; \c direction has unit length. */
struct Ray
{
  Eigen::Vector2d origin = Eigen::Vector2d::Zero ();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX ();
};

/** \brief A line segment from \c a to \c b [m]; seen from both sides. */
struct Segment
{
  Eigen::Vector2d a = Eigen::Vector2d::Zero ();
  Eigen::Vector2d b = Eigen::Vector2d::Zero ();
};

/** \brief A solid disc (pole, tree trunk, pedestrian, leg) [m]. */
struct Circle
{
  Eigen::Vector2d centre = Eigen::Vector2d::Zero ();
  double radius = 0.0;
};

/** \brief Distance along \a ray to its crossing with \a segment, or kNoHit.
 *  Rays parallel to the segment never hit it.
 */
double
intersect (const Ray& ray, const Segment& segment);

/** \brief Distance along \a ray to where it enters \a circle, or kNoHit (also
 *  when the ray starts inside the circle).
 */
double
intersect (const Ray& ray, const Circle& circle);

/** \brief The outline of one rigid body: segments and discs in one frame.
 *
 *  \code
 *  pcl_crf::simulation::Geometry car;
 *  car.addBox (4.5, 1.8);                       // centred on the body frame
 *  const double t = car.intersect (ray);        // kNoHit when missed
 *  \endcode
 */
struct Geometry
{
  std::vector<Segment> segments;
  std::vector<Circle> circles;

  /** \brief Adds the 4 sides of a length x width rectangle [m] whose centre and
   *  long axis are given by \a pose (body x along the length).
   */
  void
  addBox (double length, double width, const Rigid2d& pose = Rigid2d::Identity ());

  /** \brief Adds the segments joining consecutive \a vertices. */
  void
  addPolyline (const std::vector<Eigen::Vector2d>& vertices);

  /** \brief Adds one segment. */
  void
  addSegment (const Eigen::Vector2d& a, const Eigen::Vector2d& b);

  /** \brief Adds one disc. */
  void
  addCircle (const Eigen::Vector2d& centre, double radius);

  /** \brief This geometry moved by \a T (every vertex and centre mapped by T). */
  Geometry
  transformed (const Rigid2d& T) const;

  /** \brief A disc holding every shape (for culling); radius 0 when empty. */
  Circle
  boundingCircle () const;

  /** \brief Distance along \a ray to the first shape it hits, or kNoHit. */
  double
  intersect (const Ray& ray) const;

  bool
  empty () const { return segments.empty () && circles.empty (); }
};

}  // namespace simulation
}  // namespace pcl_crf
