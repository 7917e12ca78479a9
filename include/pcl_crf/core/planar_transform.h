#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <string>

namespace pcl_crf {

/** \brief The planar part of a 4x4 rigid transform (rotation about z, x/y
 *  translation), re-orthonormalised through its angle. */
template <typename Scalar> Rigid2d
toRigid2d (const Eigen::Matrix<Scalar, 4, 4>& M)
{
  const double theta = std::atan2 (static_cast<double> (M (1, 0)), static_cast<double> (M (0, 0)));
  return makeRigid2d (static_cast<double> (M (0, 3)), static_cast<double> (M (1, 3)), theta);
}

/** \brief Why toRigid2d (\a M) loses part of \a M, or "" when it loses nothing: a
 *  finite \a M whose 3x3 part is a rotation about z (within \a tolerance) and whose
 *  bottom row is (0 0 0 1). Its z translation is never reported (a laser mounted above
 *  the origin). The adapters warn with this text and go on with the planar part.
 *  \code
 *  const std::string lost = pcl_crf::nonPlanarPart (guess);
 *  if (!lost.empty ())  // PCL_WARN: #include <pcl/console/print.h>
 *    PCL_WARN ("the guess %s: only its planar part is used\n", lost.c_str ());
 *  \endcode */
template <typename Scalar> std::string
nonPlanarPart (const Eigen::Matrix<Scalar, 4, 4>& M, double tolerance = 1e-3)
{
  const Eigen::Matrix4d D = M.template cast<double> ();
  if (!D.allFinite ())
    return "holds NaN or infinite values";
  if ((D.row (3) - Eigen::RowVector4d (0.0, 0.0, 0.0, 1.0)).cwiseAbs ().maxCoeff () > tolerance)
    return "is projective (its bottom row is not 0 0 0 1)";
  const Eigen::Matrix3d R = D.topLeftCorner<3, 3> ();
  if ((R.transpose () * R - Eigen::Matrix3d::Identity ()).cwiseAbs ().maxCoeff () > tolerance || R.determinant () < 0.0)
    return "is not a rotation (it scales, shears or mirrors)";
  const double tilt = std::atan2 (R.col (2).head<2> ().norm (), R (2, 2));  // between the z axes
  if (tilt > tolerance)
    return "rotates about the x or y axis (its z axis tilts by " + std::to_string (tilt) + " rad)";
  return "";
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
