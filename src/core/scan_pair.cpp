#include <pcl_crf/core/scan_pair.h>

#include <cmath>

namespace pcl_crf {

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

Eigen::Vector3d
toXYTheta (const Rigid2d& T)
{
  return {T.translation ().x (), T.translation ().y (), rotationAngle (T)};
}

}  // namespace pcl_crf
