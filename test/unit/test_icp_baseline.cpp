#include <pcl_crf/baselines/icp_baseline.h>

#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <limits>

namespace {

using pcl_crf::makeRigid2d;

TEST (IcpBaseline, RecoversKnownMotionFromPerturbedOdometry)
{
  const pcl_crf::Rigid2d truth = makeRigid2d (0.4, -0.2, 0.05);
  // Walls sampled every 2 cm; odometry 5.8 cm and 0.01 rad off. Point-to-point
  // ICP between identically sampled walls stalls within about half the sample
  // spacing along the walls (measured: 8.4 mm, 2.5 mrad), so the stated
  // tolerances are 1.5 cm and 5 mrad.
  const auto pair = pcl_crf::test::staticRoomPair (truth, makeRigid2d (0.05, -0.03, 0.01), 0.02);
  const pcl_crf::Prediction prediction = pcl_crf::runIcpBaseline (pair);
  const pcl_crf::Rigid2d error = prediction.cluster_motions[0].inverse () * truth;
  EXPECT_LT (std::abs (pcl_crf::rotationAngle (error)), 5e-3);
  EXPECT_LT (error.translation ().norm (), 1.5e-2);
  const pcl_crf::Rigid2d ego_error = prediction.T_source_target * truth;
  EXPECT_LT (ego_error.translation ().norm (), 1.5e-2);
  ASSERT_EQ (prediction.source_match.size (), static_cast<std::size_t> (pair.source.cols ()));
  // Every point finds a target point within 3 cm of its true correspondence.
  for (std::size_t i = 0; i < pair.source_match.size (); ++i) {
    ASSERT_NE (prediction.source_match[i], pcl_crf::kNoMatch);
    EXPECT_LT ((pair.target.col (prediction.source_match[i]) - pair.target.col (pair.source_match[i])).norm (), 0.03);
  }
  EXPECT_EQ (prediction.static_cluster, 0);
}

TEST (IcpBaseline, FarPointsAreOutliers)
{
  auto pair = pcl_crf::test::staticRoomPair (makeRigid2d (0.1, 0.0, 0.0));
  pair.source.col (0) << 100.0, 100.0;  // nowhere near the target scan
  const pcl_crf::Prediction prediction = pcl_crf::runIcpBaseline (pair);
  EXPECT_EQ (prediction.source_match[0], pcl_crf::kNoMatch);
}

TEST (IcpBaseline, RejectsEmptyScansAndNonsenseOptions)
{
  auto pair = pcl_crf::test::staticRoomPair (makeRigid2d (0.1, 0.0, 0.0));
  pcl_crf::IcpBaselineOptions options;
  options.max_iterations = 0;
  EXPECT_THROW (pcl_crf::runIcpBaseline (pair, options), std::invalid_argument);
  pair.target.resize (2, 0);
  EXPECT_THROW (pcl_crf::runIcpBaseline (pair), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  pair = pcl_crf::test::staticRoomPair (makeRigid2d (0.1, 0.0, 0.0));
  pair.odometry.T_source_target.translation ().y () = nan;  // once a failed assertion in PCL's kd-tree
  EXPECT_THROW (pcl_crf::runIcpBaseline (pair), std::invalid_argument);
  pair = pcl_crf::test::staticRoomPair (makeRigid2d (0.1, 0.0, 0.0));
  pair.source (0, 2) = nan;
  EXPECT_THROW (pcl_crf::runIcpBaseline (pair), std::invalid_argument);
  pair = pcl_crf::test::staticRoomPair (makeRigid2d (0.1, 0.0, 0.0));
  pair.odometry.T_source_target.translation ().x () = 1e38;  // finite in double, not in float arithmetic
  EXPECT_THROW (pcl_crf::runIcpBaseline (pair), std::invalid_argument);
}

}  // namespace
