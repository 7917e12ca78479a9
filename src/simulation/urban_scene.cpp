#include <pcl_crf/simulation/urban_scene.h>
#include <pcl_crf/simulation/rigid_math.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace simulation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------ street layout
// World frame: the ego starts at the origin heading +x in its lane (y = 0);
// left is +y. All values in metres.
constexpr double kPassingLaneY = 3.3;    // same direction as the ego, on its left
constexpr double kOppositeLaneY = 6.6;   // traffic towards -x

/** One side of the street: positions measured outward from the road edge. */
struct SideLayout
{
  double direction;       // -1 right side (negative y), +1 left side
  double parking_centre;  // |y| of the parking lane centre
  double pole_line;       // |y| of the poles
  double tree_line;       // |y| of the trees
  double sidewalk_inner;  // |y| range where pedestrians walk
  double sidewalk_outer;
  double facade_base;     // |y| of the nearest façade; blocks set back by up to kFacadeSetback
};
constexpr SideLayout kRightSide{-1.0, 2.75, 4.3, 5.2, 4.6, 6.9, 7.5};
constexpr SideLayout kLeftSide{+1.0, 9.35, 10.9, 11.8, 10.7, 13.6, 14.0};
constexpr double kFacadeSetback = 2.0;

// ------------------------------------------------------------ collision footprints
/** An oriented rectangle in some frame: centre/axes by pose, half extents. */
struct Footprint
{
  Rigid2d pose = Rigid2d::Identity ();
  double half_length = 0.0;
  double half_width = 0.0;
};

/** Separating-axis test of two rectangles grown by \a margin on every side. */
bool
overlaps (const Footprint& a, const Footprint& b, double margin)
{
  const Eigen::Vector2d d = b.pose.translation () - a.pose.translation ();
  const Eigen::Matrix2d Ra = a.pose.linear (), Rb = b.pose.linear ();
  const double ea[2] = {a.half_length + margin, a.half_width + margin};
  const double eb[2] = {b.half_length + margin, b.half_width + margin};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d axis = k < 2 ? Ra.col (k) : Rb.col (k - 2);
    const double ra = ea[0] * std::abs (dot2 (axis, Ra.col (0))) + ea[1] * std::abs (dot2 (axis, Ra.col (1)));
    const double rb = eb[0] * std::abs (dot2 (axis, Rb.col (0))) + eb[1] * std::abs (dot2 (axis, Rb.col (1)));
    if (std::abs (dot2 (axis, d)) > ra + rb)
      return false;
  }
  return true;
}

Footprint
moved (const Footprint& f, const Rigid2d& T)
{
  return {composeRigid (T, f.pose), f.half_length, f.half_width};
}

constexpr double kMovingMargin = 0.3;  // between moving bodies (and the ego) [m]
constexpr double kStaticMargin = 0.1;  // between a moving body and a static obstacle [m]
constexpr int kMaxPlacementAttempts = 30;  // proposals per moving object before it is skipped

// ------------------------------------------------------------ static world
/** The façade of one side: blocks with recesses, side walls, gaps with back walls. */
void
addFacades (const SideLayout& side, double x_min, double x_max, RandomStream& rng, Geometry& world)
{
  const double s = side.direction;
  double x = x_min;
  while (x < x_max) {
    const double length = rng.uniform (8.0, 30.0);
    const double depth = rng.uniform (6.0, 15.0);
    const double y = s * (side.facade_base + rng.uniform (0.0, kFacadeSetback));
    // Up to two recesses (doorways, shop windows) on the street face.
    std::vector<Eigen::Vector2d> outline{{x, y}};
    const int recesses = rng.uniformInt (0, 2);
    double cursor = x;
    for (int k = 0; k < recesses; ++k) {
      const double width = rng.uniform (1.5, 4.0);
      const double recess_depth = rng.uniform (0.3, 1.2);
      const double start = cursor + rng.uniform (1.0, 0.5 * length);
      if (start + width > x + length - 1.0)
        break;
      outline.emplace_back (start, y);
      outline.emplace_back (start, y + s * recess_depth);
      outline.emplace_back (start + width, y + s * recess_depth);
      outline.emplace_back (start + width, y);
      cursor = start + width;
    }
    outline.emplace_back (x + length, y);
    world.addPolyline (outline);
    // Side walls (seen through gaps and where neighbours are set back differently).
    world.addSegment ({x, y}, {x, y + s * depth});
    world.addSegment ({x + length, y}, {x + length, y + s * depth});
    x += length;
    if (rng.bernoulli (0.55)) {
      const double gap = rng.uniform (2.5, 10.0);
      const double back = rng.uniform (3.0, 8.0);
      if (rng.bernoulli (0.5))  // a wall or fence at the back of the gap
        world.addSegment ({x, y + s * back}, {x + gap, y + s * back});
      x += gap;
    }
  }
}

/** Parked cars along one side's parking lane. */
void
addParkedCars (const SideLayout& side, double x_min, double x_max, RandomStream& rng, Geometry& world,
               std::vector<Footprint>& obstacles)
{
  double x = x_min + rng.uniform (0.0, 5.0);
  while (x < x_max) {
    if (rng.bernoulli (0.6)) {
      const double length = rng.uniform (4.2, 4.9);
      const double width = rng.uniform (1.7, 1.9);
      const double y = side.direction * side.parking_centre + rng.uniform (-0.15, 0.15);
      const Rigid2d pose = makeRigid2d (x + 0.5 * length, y, rng.uniform (-0.05, 0.05));
      world.addBox (length, width, pose);
      obstacles.push_back ({pose, 0.5 * length, 0.5 * width});
      x += length + rng.uniform (0.8, 3.0);
    }
    else
      x += rng.uniform (3.0, 12.0);
  }
}

/** Poles at the curb and trees on the sidewalk of one side. */
void
addPolesAndTrees (const SideLayout& side, double x_min, double x_max, RandomStream& rng, Geometry& world,
                  std::vector<Footprint>& obstacles)
{
  auto add_disc = [&] (double x, double y, double radius) {
    world.addCircle ({x, y}, radius);
    obstacles.push_back ({makeRigid2d (x, y, 0.0), radius, radius});
  };
  for (double x = x_min + rng.uniform (0.0, 10.0); x < x_max; x += rng.uniform (12.0, 30.0))
    add_disc (x, side.direction * side.pole_line, rng.uniform (0.08, 0.2));
  for (double x = x_min + rng.uniform (0.0, 8.0); x < x_max; x += rng.uniform (7.0, 18.0)) {
    const double y = side.direction * side.tree_line + rng.uniform (-0.3, 0.3);
    const double radius = rng.uniform (0.25, 0.6);
    if (rng.bernoulli (0.7))
      add_disc (x, y, radius);
  }
}

// ------------------------------------------------------------ moving objects
/** A proposed moving object and its body-frame footprint. */
struct Candidate
{
  SceneObject object;
  Footprint footprint;
};

class TrafficBuilder
{
public:
  TrafficBuilder (const UrbanSceneSpec& spec, std::vector<Footprint> obstacles, RandomStream& rng)
  : spec_ (spec), obstacles_ (std::move (obstacles)), rng_ (rng)
  {
    ego_travel_ = std::abs (spec.ego.speed) * spec.duration;
  }

  /** Places up to spec.moving_count objects into \a scene with ids 1, 2, ... */
  void
  build (Scene& scene)
  {
    const std::vector<SceneType> pool{SceneType::Crossing, SceneType::Overtaking, SceneType::Opposite,
                                      SceneType::Pedestrians};
    int next_id = 1;
    for (int k = 0; k < spec_.moving_count; ++k) {
      SceneType type = spec_.type;
      if (type == SceneType::Static || type == SceneType::Mixed)
        break;
      if (k > 0 && (type == SceneType::Outline || (spec_.mix_types && rng_.bernoulli (0.5))))
        type = pool[static_cast<std::size_t> (rng_.uniformInt (0, static_cast<int> (pool.size ()) - 1))];
      for (int attempt = 0; attempt < kMaxPlacementAttempts; ++attempt) {
        Candidate candidate = propose (type);
        if (collides (candidate))
          continue;
        candidate.object.id = next_id++;
        if (type == SceneType::Overtaking)
          ++overtaking_placed_;
        placed_.push_back (candidate);
        scene.addObject (candidate.object);
        break;
      }
    }
  }

private:
  // Every random draw is its own statement: the order in which C++ evaluates
  // function arguments or the operands of + is unspecified, and the draws
  // must come in the same order with every compiler.

  /** \a first or \a second (probability 0.5 each) plus uniform jitter in +-\a jitter [rad]. */
  double
  pickHeading (double first, double second, double jitter)
  {
    const bool use_first = rng_.bernoulli (0.5);
    const double noise = rng_.uniform (-jitter, jitter);
    return (use_first ? first : second) + noise;
  }

  double
  speed (double low, double high)
  {
    const double drawn = rng_.uniform (low, high);
    return spec_.traffic.object_speed >= 0.0 ? spec_.traffic.object_speed : drawn;
  }

  static Candidate
  makeBody (const std::string& kind, double length, double width, double x, double y, double heading,
            double body_speed)
  {
    Candidate c;
    c.object.kind = kind;
    c.object.geometry.addBox (length, width);
    c.object.trajectory.start = makeRigid2d (x, y, heading);
    c.object.trajectory.speed = body_speed;
    c.footprint = {Rigid2d::Identity (), 0.5 * length, 0.5 * width};
    return c;
  }

  Candidate
  makePedestrian (double x, double y, double heading, double body_speed)
  {
    Candidate c;
    c.object.kind = "pedestrian";
    c.object.trajectory.start = makeRigid2d (x, y, heading);
    c.object.trajectory.speed = body_speed;
    const double radius = rng_.uniform (0.2, 0.3);
    LegGait& legs = c.object.legs;
    legs.amplitude = rng_.uniform (0.15, 0.3);
    legs.half_width = rng_.uniform (0.09, 0.13);
    legs.radius = rng_.uniform (0.06, 0.09);
    legs.phase = rng_.uniform (0.0, 2.0 * kPi);
    // Mean |d swing / dt| = 4 * amplitude * frequency equals the walking speed.
    legs.frequency = body_speed / (4.0 * legs.amplitude);
    c.object.has_legs = rng_.bernoulli (spec_.traffic.legged_pedestrian_fraction);
    if (!c.object.has_legs)
      c.object.geometry.addCircle ({0.0, 0.0}, radius);
    c.footprint = {Rigid2d::Identity (), 0.35, 0.35};
    return c;
  }

  Candidate
  makeCar (double x, double y, double heading, double body_speed)
  {
    const double length = rng_.uniform (4.2, 4.9);
    const double width = rng_.uniform (1.7, 1.9);
    return makeBody ("car", length, width, x, y, heading, body_speed);
  }

  Candidate
  propose (SceneType type)
  {
    const double v_ego = std::abs (spec_.ego.speed);
    const double ahead = ego_travel_ + 4.0;  // nearest x ahead of the ego's path end
    switch (type) {
    case SceneType::Crossing: {
      const std::size_t kind = rng_.choose ({0.45, 0.3, 0.25});
      const double heading = pickHeading (0.5 * kPi, -0.5 * kPi, 0.15);
      const double x = rng_.uniform (ahead, ahead + 18.0);
      const double y = rng_.uniform (-1.0, 7.6);
      if (kind == 0) {
        const double body_speed = speed (0.8, 1.8);
        return makePedestrian (x, y, heading, body_speed);
      }
      if (kind == 1) {
        const double length = rng_.uniform (1.7, 1.9);
        const double width = rng_.uniform (0.55, 0.65);
        const double body_speed = speed (2.5, 6.0);
        return makeBody ("cyclist", length, width, x, y, heading, body_speed);
      }
      const double body_speed = speed (2.0, 7.0);
      return makeCar (x, y, heading, body_speed);
    }
    case SceneType::Overtaking: {
      const double x = overtaking_placed_ == 0 ? rng_.uniform (-1.0, 8.0) : rng_.uniform (-1.0, 30.0);
      const double y = kPassingLaneY + rng_.uniform (-0.3, 0.3);
      const double heading = rng_.uniform (-0.02, 0.02);
      const double body_speed = speed (v_ego + 1.5, v_ego + 5.0);
      return makeCar (x, y, heading, body_speed);
    }
    case SceneType::Opposite: {
      const double x = rng_.uniform (4.0, 30.0);
      const double y = kOppositeLaneY + rng_.uniform (-0.3, 0.3);
      const double heading = kPi + rng_.uniform (-0.02, 0.02);
      const double body_speed = speed (6.0, 14.0);
      return makeCar (x, y, heading, body_speed);
    }
    case SceneType::Pedestrians: {
      if (rng_.bernoulli (0.3)) {  // crossing the street
        const double heading = pickHeading (0.5 * kPi, -0.5 * kPi, 0.15);
        const double x = rng_.uniform (ahead, ahead + 18.0);
        const double y = rng_.uniform (-1.0, 7.6);
        const double body_speed = speed (0.8, 1.8);
        return makePedestrian (x, y, heading, body_speed);
      }
      const SideLayout& side = rng_.bernoulli (0.6) ? kRightSide : kLeftSide;
      const double y = side.direction * rng_.uniform (side.sidewalk_inner, side.sidewalk_outer);
      const double heading = pickHeading (0.0, kPi, 0.1);
      const double x = rng_.uniform (1.0, 25.0);
      const double body_speed = speed (0.8, 1.8);
      return makePedestrian (x, y, heading, body_speed);
    }
    case SceneType::Outline: {
      // A long vehicle (truck, bus) broadside in the next lane, moving slowly along
      // its long side. Its end nearest to the ego is behind the sensor at both
      // scans, so both see only the long side and, compensated for the ego motion,
      // the two outlines lie on the same line (Tipaldi & Ramos 2009, Fig. 4).
      const double length = rng_.uniform (12.0, 16.0);
      const double width = rng_.uniform (2.2, 2.5);
      const bool passing = rng_.bernoulli (0.6);
      const double y = (passing ? kPassingLaneY : kOppositeLaneY) + rng_.uniform (-0.2, 0.2);
      const double heading = (passing ? 0.0 : kPi) + rng_.uniform (-0.01, 0.01);
      const double body_speed = speed (3.0, 6.0);
      // World x of the near end at time 0; driving +x it advances by v * dt.
      const double advance = passing ? body_speed * spec_.duration : 0.0;
      const double near_end = std::min (0.0, ego_travel_ - advance) + rng_.uniform (-2.0, -0.5);
      return makeBody ("car", length, width, near_end + 0.5 * length, y, heading, body_speed);
    }
    case SceneType::Mixed:
    case SceneType::Static:
      break;
    }
    return {};
  }

  /** true when the candidate overlaps the ego, a placed object or a static
   *  obstacle at the start, middle or end of the pair, or leaves the street. */
  bool
  collides (const Candidate& c) const
  {
    const Footprint ego_body{makeRigid2d (-2.3, 0.0, 0.0), 2.3, 0.95};  // behind the sensor
    for (double t : {0.0, 0.5 * spec_.duration, spec_.duration}) {
      const Footprint body = moved (c.footprint, c.object.trajectory.poseAt (t));
      if (overlaps (body, moved (ego_body, spec_.ego.poseAt (t)), kMovingMargin))
        return true;
      for (const auto& other : placed_)
        if (overlaps (body, moved (other.footprint, other.object.trajectory.poseAt (t)), kMovingMargin))
          return true;
      for (const auto& obstacle : obstacles_)
        if (overlaps (body, obstacle, kStaticMargin))
          return true;
      const double y = body.pose.translation ().y ();
      if (y < -kRightSide.facade_base + 0.5 || y > kLeftSide.facade_base - 0.5)
        return true;
    }
    return false;
  }

  const UrbanSceneSpec& spec_;
  std::vector<Footprint> obstacles_;
  RandomStream& rng_;
  double ego_travel_ = 0.0;
  std::vector<Candidate> placed_;
  int overtaking_placed_ = 0;
};

}  // namespace

std::string
sceneTypeName (SceneType type)
{
  switch (type) {
  case SceneType::Mixed: return "mixed";
  case SceneType::Outline: return "outline";
  case SceneType::Crossing: return "crossing";
  case SceneType::Overtaking: return "overtaking";
  case SceneType::Opposite: return "opposite";
  case SceneType::Pedestrians: return "pedestrians";
  case SceneType::Static: return "static";
  }
  return "unknown";
}

bool
parseSceneType (const std::string& name, SceneType& type)
{
  for (SceneType candidate : {SceneType::Mixed, SceneType::Outline, SceneType::Crossing, SceneType::Overtaking,
                              SceneType::Opposite, SceneType::Pedestrians, SceneType::Static})
    if (sceneTypeName (candidate) == name) {
      type = candidate;
      return true;
    }
  return false;
}

std::vector<SceneType>
concreteSceneTypes ()
{
  return {SceneType::Outline,  SceneType::Crossing,    SceneType::Overtaking,
          SceneType::Opposite, SceneType::Pedestrians, SceneType::Static};
}

Scene
generateUrbanScene (const UrbanSceneSpec& spec, RandomStream& world_rng, RandomStream& traffic_rng)
{
  SceneObject world;
  world.id = 0;
  world.kind = "world";
  world.is_static = true;
  std::vector<Footprint> obstacles;
  for (const SideLayout* side : {&kRightSide, &kLeftSide}) {
    addFacades (*side, spec.x_min, spec.x_max, world_rng, world.geometry);
    addParkedCars (*side, spec.x_min, spec.x_max, world_rng, world.geometry, obstacles);
    addPolesAndTrees (*side, spec.x_min, spec.x_max, world_rng, world.geometry, obstacles);
  }
  Scene scene;
  scene.addObject (std::move (world));
  TrafficBuilder (spec, std::move (obstacles), traffic_rng).build (scene);
  return scene;
}

}  // namespace simulation
}  // namespace pcl_crf
