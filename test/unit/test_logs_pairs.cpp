#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/metrics/motion_error.h>

#include <gtest/gtest.h>

#include <cmath>

using pcl_crf::makeRigid2d;
using pcl_crf::Rigid2d;

namespace {

/** A scan of a few points in beam order with the given reference pose. */
pcl_crf::LaserScanRecord
makeScan (double stamp, const Rigid2d& pose, const Eigen::Matrix2Xd& world_points)
{
  pcl_crf::LaserScanRecord scan;
  scan.stamp = stamp;
  scan.sensor = {360, -M_PI, M_PI / 180, 10.0};
  scan.points = pose.inverse () * world_points;
  for (Eigen::Index i = 0; i < world_points.cols (); ++i)
    scan.beams.push_back (static_cast<int> (i));
  scan.has_pose = true;
  scan.pose = pose;
  return scan;
}

/** Walls around the origin plus a small car at (cx, 2). */
Eigen::Matrix2Xd
worldPoints (double car_x)
{
  Eigen::Matrix2Xd points (2, 14);
  for (int i = 0; i < 10; ++i)
    points.col (i) << -3.0 + 0.6 * i, 4.0;
  points.col (10) << car_x - 0.2, 2.0;
  points.col (11) << car_x - 0.1, 2.0;
  points.col (12) << car_x, 2.0;
  points.col (13) << car_x + 0.1, 2.0;
  return points;
}

pcl_crf::LaserLog
threeScanLog ()
{
  pcl_crf::LaserLog log;
  log.path = "synthetic";
  log.has_reference_poses = true;
  log.has_odometry = true;
  const Rigid2d poses[3] = {makeRigid2d (0, 0, 0), makeRigid2d (0.5, 0.1, 0.1), makeRigid2d (1.0, 0.3, 0.15)};
  for (int k = 0; k < 3; ++k) {
    log.scans.push_back (makeScan (10.0 + k, poses[k], worldPoints (1.0 + 0.3 * k)));
    if (k > 0) {
      log.scans[k].has_odometry_step = true;
      log.scans[k].odometry_step = poses[k - 1].inverse () * poses[k] * makeRigid2d (0.02, 0.0, 0.01);
    }
  }
  pcl_crf::TrackedObject car;
  car.name = "/car_pose";
  car.half_extent = Eigen::Vector2d (0.2, 0.1);
  for (int k = 0; k <= 20; ++k)  // moves +x at 0.3 m/s, stamps 10 .. 12
    car.track.append (10.0 + 0.1 * k, makeRigid2d (0.95 + 0.03 * k, 2.0, 0.0));
  log.objects.push_back (car);
  return log;
}

TEST (LogPairs, UnlabelledPairCarriesReferenceMotionAndOdometry)
{
  const pcl_crf::LaserLog log = threeScanLog ();
  EXPECT_EQ (pcl_crf::logPairCount (3, 1), 2u);
  EXPECT_EQ (pcl_crf::logPairCount (3, 2), 1u);
  EXPECT_EQ (pcl_crf::logPairCount (3, 3), 0u);
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 1);
  EXPECT_EQ (pair.name, "scan_000001");
  EXPECT_FALSE (pair.hasTruth ());
  EXPECT_TRUE (pair.source_object.empty ());
  EXPECT_EQ (pair.source.cols (), 14);
  ASSERT_EQ (pair.objects.size (), 2u);  // the world and the tracked car
  Rigid2d reference;
  ASSERT_TRUE (pcl_crf::referenceEgoMotion (pair, reference));
  EXPECT_TRUE (reference.isApprox (log.scans[1].pose.inverse () * log.scans[2].pose, 1e-12));
  EXPECT_TRUE (pair.odometry.T_source_target.isApprox (log.scans[2].odometry_step, 1e-12));
  EXPECT_DOUBLE_EQ (pair.odometry.interval, 1.0);  // stamps 11 and 12
  // the static world maps source points onto target points
  const Rigid2d world = pair.objects[0].T_target_source;
  EXPECT_LT ((world * pair.source.col (3) - pair.target.col (3)).norm (), 1e-9);
  // the car moved 0.3 m in x between the scans
  const Rigid2d car = pair.objects[1].T_target_source;
  EXPECT_LT ((car * pair.source.col (12) - pair.target.col (12)).norm (), 1e-9);
  EXPECT_EQ (pair.objects[1].kind, "car");
}

TEST (LogPairs, OdometryComposesOverStepsWithTheNoiseModel)
{
  const pcl_crf::LaserLog log = threeScanLog ();
  pcl_crf::LogPairOptions options;
  options.step = 2;
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 0, options);
  EXPECT_TRUE (pair.odometry.T_source_target.isApprox (log.scans[1].odometry_step * log.scans[2].odometry_step));
  const Eigen::Matrix3d expected =
      options.noise.covariance (log.scans[1].odometry_step) + options.noise.covariance (log.scans[2].odometry_step);
  EXPECT_TRUE (pair.odometry.covariance.isApprox (expected));
  EXPECT_DOUBLE_EQ (pair.odometry.interval, 2.0);
  EXPECT_NO_THROW (pcl_crf::makeLogPair (log, 0, options));
  EXPECT_THROW (pcl_crf::makeLogPair (log, 1, options), pcl_crf::LogError);  // 1 + 2 is past the end
}

TEST (LogPairs, NoiseModelGrowsWithTravelAndTurn)
{
  const pcl_crf::OdometryNoiseModel model;
  const Eigen::Matrix3d still = model.covariance (Rigid2d::Identity ());
  EXPECT_NEAR (std::sqrt (still (0, 0)), model.min_translation_std, 1e-12);
  EXPECT_NEAR (std::sqrt (still (2, 2)), model.min_rotation_std, 1e-12);
  const Eigen::Matrix3d metre = model.covariance (makeRigid2d (2.0, 0.0, 0.5));
  EXPECT_NEAR (std::sqrt (metre (0, 0)), 0.1 * 2.0, 1e-12);
  EXPECT_NEAR (std::sqrt (metre (1, 1)), 0.1 * 2.0, 1e-12);
  EXPECT_NEAR (std::sqrt (metre (2, 2)), 0.2 * 0.5 + 0.05 * 2.0, 1e-12);
  EXPECT_DOUBLE_EQ (metre (0, 1), 0.0);
}

TEST (LogPairs, WithoutOdometryTheGuessIsIdentityWithAWeakPrior)
{
  pcl_crf::LaserLog log = threeScanLog ();
  log.scans[2].has_odometry_step = false;
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 1);
  EXPECT_TRUE (pair.odometry.T_source_target.isApprox (Rigid2d::Identity ()));
  EXPECT_DOUBLE_EQ (pair.odometry.covariance (0, 0), 1.0);
  EXPECT_DOUBLE_EQ (pair.odometry.covariance (2, 2), 0.25);
}

TEST (LogPairs, LabelsFollowFootprintsAndTheTrueAssociationRule)
{
  const pcl_crf::LaserLog log = threeScanLog ();
  pcl_crf::LogPairOptions options;
  options.label_points = true;
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 0, options);
  ASSERT_TRUE (pair.hasTruth ());
  EXPECT_NO_THROW (pcl_crf::validateScanPair (pair, "labelled log pair"));
  for (int i = 0; i < 10; ++i)
    EXPECT_EQ (pair.source_object[i], 0) << i;
  for (int i = 10; i < 14; ++i) {
    EXPECT_EQ (pair.source_object[i], 1) << i;
    EXPECT_EQ (pair.target_object[i], 1) << i;
  }
  // each point's counterpart has the same index in this synthetic log
  for (int i = 0; i < 14; ++i)
    EXPECT_EQ (pair.source_match[i], i) << i;
}

/** threeScanLog with the car's track replaced: pose (x, 2, theta (stamp)) from stamp 10 to 12. */
pcl_crf::LaserLog
logWithCarTrack (double speed, double turn_rate)
{
  pcl_crf::LaserLog log = threeScanLog ();
  log.objects.front ().track = {};
  for (int k = 0; k <= 20; ++k)
    log.objects.front ().track.append (10.0 + 0.1 * k, makeRigid2d (0.95 + speed * 0.1 * k, 2.0, turn_rate * 0.1 * k));
  return log;
}

TEST (LogPairs, ACarStandingStillIsPartOfTheStaticWorld)
{
  pcl_crf::LogPairOptions options;
  options.label_points = true;
  // parked: the world only, its points labelled static
  const pcl_crf::ScanPair parked = pcl_crf::makeLogPair (logWithCarTrack (0.0, 0.0), 0, options);
  ASSERT_EQ (parked.objects.size (), 1u);
  EXPECT_TRUE (parked.objects[0].is_static);
  for (int i = 10; i < 14; ++i)
    EXPECT_EQ (parked.source_object[i], 0) << i;
  EXPECT_NO_THROW (pcl_crf::validateScanPair (parked, "parked car"));
  // 9 mm in the 1 s between the scans: below the 1 cm tolerance; 11 mm: a mover
  EXPECT_EQ (pcl_crf::makeLogPair (logWithCarTrack (0.009, 0.0), 0, options).objects.size (), 1u);
  const pcl_crf::ScanPair creeping = pcl_crf::makeLogPair (logWithCarTrack (0.011, 0.0), 0, options);
  ASSERT_EQ (creeping.objects.size (), 2u);
  EXPECT_EQ (creeping.source_object[12], 1);
  // turning in place by 0.05 rad swings the grown footprint's corners (0.25 x 0.15 m) by
  // 0.05 * 0.29 = 15 mm: a mover, though its centre stays put
  EXPECT_EQ (pcl_crf::makeLogPair (logWithCarTrack (0.0, 0.05), 0, options).objects.size (), 2u);
  // tolerance 0 keeps even the parked car
  options.still_tolerance = 0.0;
  EXPECT_EQ (pcl_crf::makeLogPair (logWithCarTrack (0.0, 0.0), 0, options).objects.size (), 2u);
  options.still_tolerance = -0.01;
  EXPECT_THROW (pcl_crf::makeLogPair (logWithCarTrack (0.0, 0.0), 0, options), pcl_crf::LogError);
}

TEST (LogPairs, UntrackedOrPoselessPairs)
{
  pcl_crf::LaserLog log = threeScanLog ();
  log.objects.front ().track = {};  // no car poses: only the world remains
  EXPECT_EQ (pcl_crf::makeLogPair (log, 0).objects.size (), 1u);
  log.scans[1].has_pose = false;
  const pcl_crf::ScanPair pair = pcl_crf::makeLogPair (log, 0);
  EXPECT_TRUE (pair.objects.empty ());
  Rigid2d reference;
  EXPECT_FALSE (pcl_crf::referenceEgoMotion (pair, reference));
  pcl_crf::LogPairOptions options;
  options.label_points = true;
  EXPECT_THROW (pcl_crf::makeLogPair (log, 0, options), pcl_crf::LogError);
}

TEST (LogPairs, RejectsBadPairsAndOptions)
{
  pcl_crf::LaserLog log = threeScanLog ();
  pcl_crf::LogPairOptions options;
  options.step = 0;
  EXPECT_THROW (pcl_crf::makeLogPair (log, 0, options), pcl_crf::LogError);
  options.step = 1;
  options.noise.min_translation_std = 0.0;
  EXPECT_THROW (pcl_crf::makeLogPair (log, 0, options), pcl_crf::LogError);
  EXPECT_THROW (pcl_crf::makeLogPair (log, 2), pcl_crf::LogError);
  log.scans[1].sensor.beam_count = 181;
  EXPECT_THROW (pcl_crf::makeLogPair (log, 0), pcl_crf::LogError);
  log = threeScanLog ();
  log.scans[1].points.resize (2, 0);
  log.scans[1].beams.clear ();
  EXPECT_THROW (pcl_crf::makeLogPair (log, 0), pcl_crf::LogError);
}

TEST (LogPairs, PoseTrackInterpolatesAndRespectsGaps)
{
  pcl_crf::PoseTrack track;
  track.append (1.0, makeRigid2d (0, 0, 3.0));
  track.append (1.4, makeRigid2d (2, 4, -3.0));  // crosses +-pi: the short way round
  track.append (1.4, makeRigid2d (9, 9, 0.0));   // same stamp: ignored
  track.append (5.0, makeRigid2d (0, 0, 0.0));
  EXPECT_EQ (track.stamps.size (), 3u);
  Rigid2d pose;
  ASSERT_TRUE (track.interpolate (1.2, pose));
  EXPECT_NEAR (pose.translation ().x (), 1.0, 1e-12);
  EXPECT_NEAR (pose.translation ().y (), 2.0, 1e-12);
  EXPECT_NEAR (std::abs (pcl_crf::rotationAngle (pose)), M_PI, 1e-9);
  ASSERT_TRUE (track.interpolate (1.4, pose));
  EXPECT_NEAR (pose.translation ().x (), 2.0, 1e-12);
  EXPECT_TRUE (track.interpolate (1.0 - 1e-7, pose));  // within a microsecond of the ends
  EXPECT_FALSE (track.interpolate (0.5, pose));
  EXPECT_FALSE (track.interpolate (3.0, pose));       // 3 s gap > 0.5 s
  EXPECT_TRUE (track.interpolate (3.0, pose, 5.0));  // allowed with a larger gap
  EXPECT_FALSE (track.interpolate (5.5, pose));
}

}  // namespace
