#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <cmath>

namespace pcl_crf {

/** \brief The planar part of a 4x4 rigid transform (rotation about z, x/y
 *  translation), re-orthonormalised through its angle. */
template <typename Scalar> Rigid2d
toRigid2d (const Eigen::Matrix<Scalar, 4, 4>& M)
{
  const double theta = std::atan2 (static_cast<double> (M (1, 0)), static_cast<double> (M (0, 0)));
  return makeRigid2d (static_cast<double> (M (0, 3)), static_cast<double> (M (1, 3)), theta);
}

/** \brief A planar rigid motion as a 4x4 transform (PCL's form). */
template <typename Scalar> Eigen::Matrix<Scalar, 4, 4>
toMatrix4 (const Rigid2d& T)
{
  Eigen::Matrix<Scalar, 4, 4> M = Eigen::Matrix<Scalar, 4, 4>::Identity ();
  M.template topLeftCorner<2, 2> () = T.linear ().cast<Scalar> ();
  M.template block<2, 1> (0, 3) = T.translation ().cast<Scalar> ();
  return M;
}

}  // namespace pcl_crf
