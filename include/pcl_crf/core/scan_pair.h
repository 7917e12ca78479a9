#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace pcl_crf {

/** \brief A 2D rigid motion. Throughout pcl_crf a motion called
 *  \c T_target_source maps a point expressed in the source scan's sensor frame
 *  into the target scan's sensor frame: p_target = T_target_source * p_source.
 */
using Rigid2d = Eigen::Isometry2d;

/** \brief Index value meaning "no corresponding target point" (outlier). */
constexpr int kNoMatch = -1;

/** \brief The largest coordinate [m] a scan point, odometry or object motion may have:
 *  squared distances between such points, (4 · 1e18)² < FLT_MAX ≈ 3.4e38, stay finite
 *  in PCL's single precision (PCL's kd-tree aborts on coordinates near 1e37). */
constexpr double kMaxCoordinate = 1e18;

/** \brief Largest sensor beam count a dataset may declare (data/README.md) and the
 *  estimators' sensor checks. Real 2D
 *  lasers have ~180 to ~4000 beams (a SICK LMS at 0.25 deg: 1081, a Hokuyo UTM-30LX:
 *  1081, 0.1 deg over 360 deg: 3600); the bound only stops a corrupt count from making
 *  methods that allocate per beam (cbd, range profiles) take gigabytes. */
constexpr int kMaxBeamCount = 100000;

/** \brief Why \a points cannot be scan points: "" when every coordinate is finite
 *  and within ±kMaxCoordinate, else a message naming the first point that is not,
 *  "<name> point <i> has a NaN or infinite coordinate" or "... a coordinate beyond 1e18 m".
 *
 *  \code
 *  const std::string problem = pcl_crf::scanPointsProblem (source, "source");
 *  if (!problem.empty ())
 *    throw std::invalid_argument (problem);
 *  \endcode
 */
std::string
scanPointsProblem (const Eigen::Matrix2Xd& points, const std::string& name);


/** \brief Metadata of the laser that produced a scan. Angles in radians,
 *  ranges in metres. Beam i points at angle_min + i * angle_increment.
 */
struct SensorInfo
{
  int beam_count = 0;
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double range_max = 0.0;

  double angleMax () const { return angle_min + (beam_count - 1) * angle_increment; }
};

/** \brief Ground truth of one rigidly moving object (or of the static world). */
struct ObjectTruth
{
  int id = 0;
  /** true for the static world: its motion is the inverse of the ego motion. */
  bool is_static = false;
  /** maps the object's source points into the target sensor frame. */
  Rigid2d T_target_source = Rigid2d::Identity ();
  /** free-form kind ("world", "car", "pedestrian", "cyclist", ...). */
  std::string kind;
};

/** \brief Odometry measurement of the sensor's own motion between the two scans.
 *
 *  \c T_source_target is the pose of the sensor at the target time expressed in
 *  the source sensor frame (forward driving gives a positive x). The covariance
 *  is over (dx [m], dy [m], dtheta [rad]) of that pose change.
 */
struct Odometry
{
  Rigid2d T_source_target = Rigid2d::Identity ();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity ();
  /** time from the source scan to the target scan [s]; 0 when unknown. With it the
   *  estimators bound how far an object can have moved (SegmentMotionParameters::max_speed). */
  double interval = 0.0;
};

/** \brief Two consecutive laser scans in beam order plus their ground truth.
 *
 *  Points are columns (x, y) in each scan's own sensor frame, ordered by beam.
 *  Invalid beams (no return) are not stored, so a scan may hold fewer points
 *  than sensor.beam_count; the order of the remaining points is the beam order.
 */
struct ScanPair
{
  std::string name;
  SensorInfo sensor;
  Eigen::Matrix2Xd source;
  Eigen::Matrix2Xd target;
  /** ground-truth object id of every source / target point. */
  std::vector<int> source_object;
  std::vector<int> target_object;
  /** index of the corresponding target point of every source point, or kNoMatch. */
  std::vector<int> source_match;
  std::vector<ObjectTruth> objects;
  Odometry odometry;

  /** \brief Index into \c objects of the object with this id, or -1. */
  int objectIndex (int id) const;
  /** \brief Id of the static-world object, or -1 when there is none. */
  int staticObjectId () const;
  /** \brief true when the pair carries ground truth (labels for every point). */
  bool hasTruth () const;
};

/** \brief true when the linear part of \a T is a rotation (orthonormal to 1e-6,
 *  determinant +1), as every motion pcl_crf takes must be. */
bool
isRotation (const Rigid2d& T);

/** \brief What makes an odometry reading unusable, or an empty string when nothing does:
 *  a NaN or infinite pose, a pose whose linear part is not a rotation, a translation
 *  beyond kMaxCoordinate, a covariance with
 *  a NaN or infinite entry, one that is not symmetric or has a negative variance, or an
 *  interval that is negative or not finite. A singular covariance (the zero matrix, say)
 *  is usable: it gives the estimators no prior (matching::MotionGuess::fromOdometry).
 *
 *  \code
 *  const std::string problem = pcl_crf::odometryProblem (odometry);
 *  if (!problem.empty ())
 *    throw std::invalid_argument (problem);
 *  \endcode
 */
std::string
odometryProblem (const Odometry& odometry);

/** \brief A 2D pose (x [m], y [m], theta [rad]) as a rigid motion. */
Rigid2d
makeRigid2d (double x, double y, double theta);

/** \brief The (x, y, theta) of a rigid motion, theta in (-pi, pi]. */
Eigen::Vector3d
toXYTheta (const Rigid2d& T);

/** \brief Rotation angle in (-pi, pi] of a rigid motion. */
double
rotationAngle (const Rigid2d& T);

/** \brief The yaw [rad] of the rotation given by the quaternion (w, x, y, z) of any
 *  non-zero norm (a pose message's quaternion may be rounded, or scaled, off unit
 *  length: the unit-length formula then read 0.036 rad for 0.009). */
double
yawOfQuaternion (double w, double x, double y, double z);

}  // namespace pcl_crf
