#include <pcl_crf/metrics/motion_error.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using pcl_crf::makeRigid2d;

TEST (MetricsMotionError, RotationErrorOfKnownTransforms)
{
  // truth rotates 0.1 rad, estimate 0.08 rad: residual rotation 0.02 rad, same translation.
  const auto error =
      pcl_crf::computeMotionError (makeRigid2d (1.0, 0.0, 0.08), makeRigid2d (1.0, 0.0, 0.1));
  EXPECT_NEAR (error.rotation, 0.02, 1e-12);
  EXPECT_NEAR (error.translation, 0.0, 1e-12);
  // The error is an absolute value: swapping the two gives the same numbers.
  const auto swapped =
      pcl_crf::computeMotionError (makeRigid2d (0.0, 0.0, 0.1), makeRigid2d (0.0, 0.0, 0.08));
  EXPECT_NEAR (swapped.rotation, 0.02, 1e-12);
}

TEST (MetricsMotionError, TranslationErrorOfKnownTransforms)
{
  // identity against (3, 4, 0.3): 0.3 rad and a 3-4-5 triangle.
  const auto error =
      pcl_crf::computeMotionError (pcl_crf::Rigid2d::Identity (), makeRigid2d (3.0, 4.0, 0.3));
  EXPECT_NEAR (error.rotation, 0.3, 1e-12);
  EXPECT_NEAR (error.translation, 5.0, 1e-12);
  // Both rotated by pi/2, 1 m apart: T_est^-1 T_true = (R(-pi/2) (1, 0), 0) = ((0, -1), 0).
  const pcl_crf::Rigid2d T_estimated = makeRigid2d (0.0, 0.0, M_PI / 2);
  const pcl_crf::Rigid2d T_true = makeRigid2d (1.0, 0.0, M_PI / 2);
  const auto turned = pcl_crf::computeMotionError (T_estimated, T_true);
  EXPECT_NEAR (turned.rotation, 0.0, 1e-12);
  EXPECT_NEAR (turned.translation, 1.0, 1e-12);
}

TEST (MetricsMotionError, EgoMotionIsInverseOfStaticWorldMotion)
{
  pcl_crf::ScanPair pair;
  // The sensor turned +0.1 rad, so the world appears turned -0.1 rad.
  pair.objects.push_back ({0, true, makeRigid2d (0.0, 0.0, -0.1), "world"});
  const auto rotation = pcl_crf::computeEgoMotionError (pair, makeRigid2d (0.0, 0.0, 0.08));
  EXPECT_NEAR (rotation.rotation, 0.02, 1e-12);
  EXPECT_NEAR (rotation.translation, 0.0, 1e-12);

  // The sensor drove 1 m forward, so the world appears 1 m closer; estimate 1.2 m.
  pair.objects[0].T_target_source = makeRigid2d (-1.0, 0.0, 0.0);
  const auto translation = pcl_crf::computeEgoMotionError (pair, makeRigid2d (1.2, 0.0, 0.0));
  EXPECT_NEAR (translation.rotation, 0.0, 1e-12);
  EXPECT_NEAR (translation.translation, 0.2, 1e-12);

  // Exact inverse of a combined motion: no error.
  pair.objects[0].T_target_source = makeRigid2d (-1.0, 0.5, -0.1);
  const auto exact =
      pcl_crf::computeEgoMotionError (pair, makeRigid2d (-1.0, 0.5, -0.1).inverse ());
  EXPECT_NEAR (exact.rotation, 0.0, 1e-12);
  EXPECT_NEAR (exact.translation, 0.0, 1e-12);
}

TEST (MetricsMotionError, EgoMotionIsNanWithoutStaticWorld)
{
  pcl_crf::ScanPair pair;
  pair.objects.push_back ({1, false, makeRigid2d (1.0, 0.0, 0.0), "car"});
  const auto error = pcl_crf::computeEgoMotionError (pair, pcl_crf::Rigid2d::Identity ());
  EXPECT_TRUE (std::isnan (error.rotation));
  EXPECT_TRUE (std::isnan (error.translation));
}

}  // namespace
