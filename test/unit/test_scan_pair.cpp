#include <pcl_crf/core/scan_pair.h>

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
