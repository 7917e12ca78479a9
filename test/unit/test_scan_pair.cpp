#include <pcl_crf/core/scan_pair.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

namespace {

TEST (Rigid2d, MakeAndDecomposeRoundTrip)
{
  const pcl_crf::Rigid2d T = pcl_crf::makeRigid2d (1.5, -2.0, 0.3);
  const Eigen::Vector3d v = pcl_crf::toXYTheta (T);
  EXPECT_NEAR (v.x (), 1.5, 1e-12);
  EXPECT_NEAR (v.y (), -2.0, 1e-12);
  EXPECT_NEAR (v.z (), 0.3, 1e-12);
  // A point at (1, 0) rotated by 0.3 rad then moved.
  const Eigen::Vector2d p = T * Eigen::Vector2d (1.0, 0.0);
  EXPECT_NEAR (p.x (), 1.5 + std::cos (0.3), 1e-12);
  EXPECT_NEAR (p.y (), -2.0 + std::sin (0.3), 1e-12);
}

TEST (Rigid2d, AngleWrapsIntoMinusPiPi)
{
  EXPECT_NEAR (pcl_crf::rotationAngle (pcl_crf::makeRigid2d (0, 0, 3 * M_PI / 2)), -M_PI / 2, 1e-12);
}

TEST (Rigid2d, TheYawOfAQuaternionOfAnyNorm)
{
  // A rotation of 0.3 rad about z, as a unit quaternion and scaled by 2 (a pose topic's
  // quaternion off unit length read 0.036 rad for 0.009 with the unit-length formula).
  const double w = std::cos (0.15), z = std::sin (0.15);
  EXPECT_NEAR (pcl_crf::yawOfQuaternion (w, 0.0, 0.0, z), 0.3, 1e-15);
  EXPECT_NEAR (pcl_crf::yawOfQuaternion (2.0 * w, 0.0, 0.0, 2.0 * z), 0.3, 1e-15);
  EXPECT_NEAR (pcl_crf::yawOfQuaternion (0.5 * w, 0.0, 0.0, 0.5 * z), 0.3, 1e-15);
  // A half turn (w = 0), scaled by 3.
  EXPECT_NEAR (std::abs (pcl_crf::yawOfQuaternion (0.0, 0.0, 0.0, 3.0)), M_PI, 1e-15);
}

TEST (ScanPair, LooksUpObjectsById)
{
  pcl_crf::ScanPair pair;
  pair.objects.push_back ({4, false, pcl_crf::Rigid2d::Identity (), "car"});
  pair.objects.push_back ({0, true, pcl_crf::Rigid2d::Identity (), "world"});
  EXPECT_EQ (pair.objectIndex (0), 1);
  EXPECT_EQ (pair.objectIndex (4), 0);
  EXPECT_EQ (pair.objectIndex (7), -1);
  EXPECT_EQ (pair.staticObjectId (), 0);
}

TEST (Odometry, EveryUnusableReadingIsNamed)
{
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  pcl_crf::Odometry good;
  good.T_source_target = pcl_crf::makeRigid2d (0.4, -0.1, 0.05);
  good.covariance = Eigen::Vector3d (0.01, 0.01, 0.002).asDiagonal ();
  good.interval = 0.1;
  EXPECT_EQ (pcl_crf::odometryProblem (good), "");
  pcl_crf::Odometry singular = good;  // no prior, but usable
  singular.covariance.setZero ();
  EXPECT_EQ (pcl_crf::odometryProblem (singular), "");

  const auto problemWith = [&] (const std::function<void (pcl_crf::Odometry&)>& spoil) {
    pcl_crf::Odometry odometry = good;
    spoil (odometry);
    return pcl_crf::odometryProblem (odometry);
  };
  EXPECT_EQ (problemWith ([&] (pcl_crf::Odometry& o) { o.T_source_target.translation ().x () = nan; }),
             "odometry has a NaN or infinite value");
  EXPECT_EQ (problemWith ([] (pcl_crf::Odometry& o) { o.T_source_target.linear () *= 2.0; }),
             "odometry's linear part is not a rotation");
  EXPECT_EQ (problemWith ([] (pcl_crf::Odometry& o) { o.T_source_target.linear ().col (0) *= -1.0; }),
             "odometry's linear part is not a rotation");  // a reflection
  EXPECT_EQ (problemWith ([&] (pcl_crf::Odometry& o) { o.covariance (2, 2) = nan; }),
             "odometry covariance has a NaN or infinite value");
  EXPECT_EQ (problemWith ([] (pcl_crf::Odometry& o) { o.covariance (0, 1) = 0.005; }),
             "odometry covariance is not symmetric");
  EXPECT_EQ (problemWith ([] (pcl_crf::Odometry& o) { o.covariance (1, 1) = -0.01; }),
             "odometry covariance has a negative variance on its diagonal");
  EXPECT_EQ (problemWith ([] (pcl_crf::Odometry& o) { o.interval = -0.1; }),
             "the interval between the scans must be a time >= 0 s (0: unknown), not -0.100000");
  EXPECT_EQ (problemWith ([&] (pcl_crf::Odometry& o) { o.interval = nan; }),
             "the interval between the scans must be a time >= 0 s (0: unknown), not nan");
}

}  // namespace
