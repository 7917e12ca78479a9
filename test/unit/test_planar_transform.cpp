#include <pcl_crf/core/planar_transform.h>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using pcl_crf::nonPlanarPart;

Eigen::Matrix4d
transform (const Eigen::Matrix3d& R, const Eigen::Vector3d& t)
{
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity ();
  M.topLeftCorner<3, 3> () = R;
  M.topRightCorner<3, 1> () = t;
  return M;
}

Eigen::Matrix3d
about (double angle, const Eigen::Vector3d& axis)
{
  return Eigen::AngleAxisd (angle, axis).toRotationMatrix ();
}

TEST (NonPlanarPart, ARotationAboutZWithAnyTranslationLosesNothing)
{
  // A laser 1.5 m above the origin: its z translation is not reported.
  const Eigen::Matrix4d M = transform (about (0.3, Eigen::Vector3d::UnitZ ()), Eigen::Vector3d (2.0, -1.0, 1.5));
  EXPECT_EQ (nonPlanarPart (M), "");
  EXPECT_EQ (nonPlanarPart (Eigen::Matrix4f (M.cast<float> ())), "");
  const pcl_crf::Rigid2d T = pcl_crf::toRigid2d (M);
  EXPECT_NEAR (std::atan2 (T.linear () (1, 0), T.linear () (0, 0)), 0.3, 1e-12);
  EXPECT_NEAR (T.translation ().x (), 2.0, 1e-12);
  EXPECT_NEAR (T.translation ().y (), -1.0, 1e-12);
}

TEST (NonPlanarPart, NamesATiltAboutXOrYWithItsAngle)
{
  const std::string about_x = nonPlanarPart (transform (about (0.2, Eigen::Vector3d::UnitX ()), Eigen::Vector3d::Zero ()));
  EXPECT_NE (about_x.find ("x or y axis"), std::string::npos) << about_x;
  EXPECT_NE (about_x.find ("tilts by 0.200000 rad"), std::string::npos) << about_x;
  // Half a turn about x mirrors y and z: its x-y block is a rotation, its z axis upside down.
  const std::string flipped = nonPlanarPart (transform (about (M_PI, Eigen::Vector3d::UnitX ()), Eigen::Vector3d::Zero ()));
  EXPECT_NE (flipped.find ("tilts by 3.141593 rad"), std::string::npos) << flipped;
  const Eigen::Matrix3d pitch_and_yaw = about (0.5, Eigen::Vector3d::UnitZ ()) * about (-0.1, Eigen::Vector3d::UnitY ());
  const std::string about_y = nonPlanarPart (transform (pitch_and_yaw, Eigen::Vector3d::Zero ()));
  EXPECT_NE (about_y.find ("x or y axis"), std::string::npos) << about_y;
  // Within the tolerance (1e-3): a float rotation about z that rounding tilted a hair.
  EXPECT_EQ (nonPlanarPart (transform (about (5e-4, Eigen::Vector3d::UnitX ()), Eigen::Vector3d::Zero ())), "");
}

TEST (NonPlanarPart, NamesScalesMirrorsProjectionsAndNaN)
{
  const std::string not_a_rotation = "is not a rotation (it scales, shears or mirrors)";
  EXPECT_EQ (nonPlanarPart (transform (1.1 * Eigen::Matrix3d::Identity (), Eigen::Vector3d::Zero ())), not_a_rotation);
  EXPECT_EQ (nonPlanarPart (transform (Eigen::Vector3d (1.0, -1.0, 1.0).asDiagonal (), Eigen::Vector3d::Zero ())),
             not_a_rotation);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity ();
  shear (0, 1) = 0.5;
  EXPECT_EQ (nonPlanarPart (transform (shear, Eigen::Vector3d::Zero ())), not_a_rotation);
  Eigen::Matrix4d projective = Eigen::Matrix4d::Identity ();
  projective (3, 0) = 0.2;
  EXPECT_EQ (nonPlanarPart (projective), "is projective (its bottom row is not 0 0 0 1)");
  Eigen::Matrix4d nan = Eigen::Matrix4d::Identity ();
  nan (1, 3) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_EQ (nonPlanarPart (nan), "holds NaN or infinite values");
}

}  // namespace
