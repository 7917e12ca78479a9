#include <pcl_crf/core/scan_pair.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {

bool
isRotation (const Rigid2d& T)
{
  const Eigen::Matrix2d R = T.linear ();
  return (R.transpose () * R - Eigen::Matrix2d::Identity ()).cwiseAbs ().maxCoeff () < 1e-6 && R.determinant () > 0.0;
}

std::string
scanPointsProblem (const Eigen::Matrix2Xd& points, const std::string& name)
{
  for (Eigen::Index i = 0; i < points.cols (); ++i)
    if (!points.col (i).allFinite ())
      return name + " point " + std::to_string (i) + " has a NaN or infinite coordinate";
    else if (points.col (i).cwiseAbs ().maxCoeff () > kMaxCoordinate)
      return name + " point " + std::to_string (i) + " has a coordinate beyond 1e18 m";
  return {};
}

std::string
odometryProblem (const Odometry& odometry)
{
  if (!odometry.T_source_target.matrix ().allFinite ())
    return "odometry has a NaN or infinite value";
  if (!isRotation (odometry.T_source_target))
    return "odometry's linear part is not a rotation";
  if (odometry.T_source_target.translation ().cwiseAbs ().maxCoeff () > kMaxCoordinate)
    return "odometry translation beyond 1e18 m";
  const Eigen::Matrix3d& C = odometry.covariance;
  if (!C.allFinite ())
    return "odometry covariance has a NaN or infinite value";
  if ((C - C.transpose ()).cwiseAbs ().maxCoeff () > 1e-9 * std::max (1.0, C.cwiseAbs ().maxCoeff ()))
    return "odometry covariance is not symmetric";
  if ((C.diagonal ().array () < 0.0).any ())
    return "odometry covariance has a negative variance on its diagonal";
  if (!std::isfinite (odometry.interval) || odometry.interval < 0.0)
    return "the interval between the scans must be a time >= 0 s (0: unknown), not " +
           std::to_string (odometry.interval);
  return {};
}

int
ScanPair::objectIndex (int id) const
{
  for (std::size_t k = 0; k < objects.size (); ++k)
    if (objects[k].id == id)
      return static_cast<int> (k);
  return -1;
}

int
ScanPair::staticObjectId () const
{
  for (const auto& object : objects)
    if (object.is_static)
      return object.id;
  return -1;
}

bool
ScanPair::hasTruth () const
{
  return source_object.size () == static_cast<std::size_t> (source.cols ()) &&
         source_match.size () == static_cast<std::size_t> (source.cols ()) &&
         target_object.size () == static_cast<std::size_t> (target.cols ()) &&
         !objects.empty ();
}

Rigid2d
makeRigid2d (double x, double y, double theta)
{
  Rigid2d T = Rigid2d::Identity ();
  T.linear () = Eigen::Rotation2Dd (theta).toRotationMatrix ();
  T.translation () = Eigen::Vector2d (x, y);
  return T;
}

double
rotationAngle (const Rigid2d& T)
{
  return std::atan2 (T.linear () (1, 0), T.linear () (0, 0));
}

double
yawOfQuaternion (double w, double x, double y, double z)
{
  // atan2 (2 (wz + xy), 1 − 2 (y² + z²)) for a unit quaternion, the 1 its squared norm:
  // both arguments scale with it.
  return std::atan2 (2.0 * (w * z + x * y), w * w + x * x - y * y - z * z);
}

Eigen::Vector3d
toXYTheta (const Rigid2d& T)
{
  return {T.translation ().x (), T.translation ().y (), rotationAngle (T)};
}

}  // namespace pcl_crf
