// Inputs that do not fit together are errors naming the function and the problem: each
// of these crashed, read or wrote out of bounds, or returned NaN before (an audit of the
// core API).
#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/core/repeated_points.h>
#include <pcl_crf/core/rigid_fit.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/lifted_matches.h>
#include <pcl_crf/matching/robust_rigid_fit.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>
#include <pcl_crf/metrics/validate_prediction.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace pcl_crf;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

/** \a call throws std::invalid_argument whose message holds \a fragment. */
void
expectInvalid (const std::function<void ()>& call, const std::string& fragment)
{
  try {
    call ();
    ADD_FAILURE () << "expected std::invalid_argument containing '" << fragment << "'";
  }
  catch (const std::invalid_argument& e) {
    EXPECT_NE (std::string (e.what ()).find (fragment), std::string::npos) << e.what ();
  }
}

/** \a n points on an arc 5 m away, 1° apart. */
Eigen::Matrix2Xd
arc (int n)
{
  Eigen::Matrix2Xd points (2, n);
  for (int i = 0; i < n; ++i)
    points.col (i) = 5.0 * Eigen::Vector2d (std::cos (i * M_PI / 180.0), std::sin (i * M_PI / 180.0));
  return points;
}

TEST (ApiInputChecks, TheRobustFitNamesPairsThatDoNotFitTheScans)
{
  const Eigen::Matrix2Xd scan = arc (10);
  matching::Candidates candidates;
  for (int i = 0; i < 10; ++i) {
    candidates.targets.push_back (i);
    candidates.offsets.push_back (static_cast<int> (candidates.targets.size ()));
  }
  std::vector<int> matches (10);
  for (int i = 0; i < 10; ++i)
    matches[i] = i;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones (10);
  const matching::MotionGuess guess;
  matching::RobustFitParameters parameters;
  parameters.reassociate = true;  // the candidates are read
  const auto fit = [&] (const std::vector<int>& m, const Eigen::VectorXd& confidence) {
    matching::robustRigidFit (scan, scan, Eigen::Matrix2Xd (), candidates, m, confidence, Rigid2d::Identity (), guess,
                              parameters);
  };
  EXPECT_TRUE (matching::robustRigidFit (scan, scan, Eigen::Matrix2Xd (), candidates, matches, ones,
                                         Rigid2d::Identity (), guess, parameters)
                   .isApprox (Rigid2d::Identity (), 1e-9));
  expectInvalid ([&] { fit (std::vector<int> (matches.begin (), matches.begin () + 4), ones); },
                 "10 source points, 4 matches and 10 confidences");  // a segmentation fault
  expectInvalid ([&] { fit (matches, Eigen::VectorXd::Ones (3)); }, "10 source points, 10 matches and 3 confidences");
  std::vector<int> far = matches;
  far[2] = 50;
  expectInvalid ([&] { fit (far, ones); }, "point 2 is matched to target point 50 of 10");
  candidates.targets[3] = 999;
  expectInvalid ([&] { fit (matches, ones); }, "a candidate is target point 999 of 10");
}

TEST (ApiInputChecks, SegmentsOutsideTheScanAreNamed)
{
  const Eigen::Matrix2Xd scan = arc (10);
  for (const matching::ScanSegment& bad : {matching::ScanSegment{-5, 3}, matching::ScanSegment{0, 50},
                                          matching::ScanSegment{0, 100000}, matching::ScanSegment{4, 4}}) {
    const std::vector<matching::ScanSegment> segments{bad};
    expectInvalid ([&] { matching::segmentOfEachPoint (segments, 10); }, "is not a run of the scan's 10 points");
    expectInvalid ([&] { matching::segmentNormals (scan, segments); }, "[pcl_crf::matching::segmentNormals]");
    expectInvalid ([&] { matching::endAlignments ({0, 0}, {1, 1}, {true, true}, scan, segments, {}); },
                   "[pcl_crf::matching::endAlignments]");
    KnnIndex index;
    index.build (scan);
    expectInvalid ([&] { matching::segmentMotionHypotheses (scan, scan, scan, segments, index, {}); },
                   "[pcl_crf::matching::segmentMotionHypotheses]");
  }
}

TEST (ApiInputChecks, ClusterIndicesOutsideTheClustersAreNamed)
{
  clustering::ScanClustering scan;
  scan.static_cluster = 5;  // of no cluster: a segmentation fault
  expectInvalid ([&] { clustering::toPrediction (scan, Rigid2d::Identity ()); }, "the static cluster 5 is not one");
  Eigen::MatrixXd marginals = Eigen::MatrixXd::Constant (3, 5, 1.0 / 3.0);
  std::vector<int> labels{0, 0, 0, 0, 0};
  expectInvalid ([&] { clustering::keepClusters ({0, 7}, marginals, labels); },
                 "kept cluster 7 is not one of the 3 clusters");  // a double free
  std::vector<int> too_few{0, 0};
  expectInvalid ([&] { clustering::keepClusters ({0}, marginals, too_few); }, "2 labels for 5 nodes' marginals");
}

TEST (ApiInputChecks, ConsistencyDetectionNamesAnAbsurdSensorAndNaNInputs)
{
  const Eigen::Matrix2Xd scan = arc (10);
  SensorInfo sensor{10, 0.0, M_PI / 180.0, 30.0};
  EXPECT_EQ (clustering::detectDynamicSegments (scan, scan, sensor, Rigid2d::Identity ()).size (), 10u);
  sensor.beam_count = 1000000000;  // ran for minutes
  expectInvalid ([&] { clustering::detectDynamicSegments (scan, scan, sensor, Rigid2d::Identity ()); },
                 "a beam_count in [1, 100000]");
  sensor.beam_count = 10;
  sensor.angle_min = kNaN;
  expectInvalid ([&] { clustering::detectDynamicSegments (scan, scan, sensor, Rigid2d::Identity ()); },
                 "a finite angle_min");
  sensor.angle_min = 0.0;
  Eigen::Matrix2Xd with_nan = scan;
  with_nan (0, 3) = kNaN;
  expectInvalid ([&] { clustering::detectDynamicSegments (with_nan, scan, sensor, Rigid2d::Identity ()); },
                 "NaN or infinite points");
  Rigid2d nan_motion = Rigid2d::Identity ();
  nan_motion.translation ().x () = kNaN;
  expectInvalid ([&] { clustering::detectDynamicSegments (scan, scan, sensor, nan_motion); },
                 "not a finite rigid motion");
}

TEST (ApiInputChecks, RigidFitsRefuseNaNPairs)
{
  Eigen::Matrix2Xd source = arc (10), target = arc (10);
  source (1, 4) = kNaN;  // the fit came out NaN
  expectInvalid ([&] { fitRigid2d (source, target); }, "pair 4 has a NaN or infinite point");
  expectInvalid ([&] { fitRigid2d (target, target, Eigen::VectorXd::Constant (10, INFINITY)); },
                 "weights must be finite");
  RigidFitAccumulator accumulator;
  expectInvalid ([&] { accumulator.add (source.col (4), target.col (4)); }, "NaN or infinite");
}

TEST (ApiInputChecks, AnAsymmetricInformationMatrixIsNamed)
{
  matching::MotionGuess guess;
  guess.information = Eigen::Matrix3d::Identity ();
  EXPECT_TRUE (matching::motionGuessProblem (guess).empty ());
  guess.information (0, 1) = 1e6;  // a translation of 2.4e96 m came out
  EXPECT_EQ (matching::motionGuessProblem (guess), "the motion guess's information matrix is not symmetric");
}

TEST (ApiInputChecks, APredictionsMotionsMustBeFiniteRigidMotions)
{
  ScanPair truth;
  truth.source = arc (3);
  truth.target = arc (3);
  truth.source_object = {0, 0, 0};
  truth.objects.push_back ({0, true, Rigid2d::Identity (), "world"});
  Prediction prediction;
  prediction.source_cluster = {0, 0, 0};
  prediction.cluster_motions = {Rigid2d::Identity ()};
  prediction.static_cluster = 0;
  EXPECT_NO_THROW (validatePrediction (truth, prediction));
  Prediction nan_ego = prediction;
  nan_ego.T_source_target.translation ().x () = kNaN;  // its rotation error read 0
  expectInvalid ([&] { validatePrediction (truth, nan_ego); }, "prediction.T_source_target is not a finite rigid motion");
  Prediction sheared = prediction;
  sheared.cluster_motions[0].linear () (0, 1) = 0.5;
  expectInvalid ([&] { validatePrediction (truth, sheared); }, "prediction.cluster_motions[0] is not a finite rigid");
  Prediction no_such_static = prediction;
  no_such_static.static_cluster = 4;
  expectInvalid ([&] { validatePrediction (truth, no_such_static); }, "prediction.static_cluster is 4");
}

TEST (ApiInputChecks, IndicesOfLiftsAndSpacingsOutsideTheirRangeAreNamed)
{
  // Each read out of bounds (a raw std::out_of_range from liftLabels).
  expectInvalid ([] { matching::liftLabels ({0, 5}, {1, 2}); }, "point 1 is anchored to 5, not one of the 2");
  expectInvalid ([] { matching::liftLabels ({-4}, {1, 2}); }, "point 0 is anchored to -4");
  EXPECT_EQ (firstCopyColumns ({0, 1, 0, 1, 4}), (std::vector<int>{0, 1, 0, 1, 2}));
  expectInvalid ([] { firstCopyColumns ({0, 5, -3, 1}); }, "point 1's first copy 5 is not a first copy");
  const Eigen::Matrix2Xd scan = arc (5);
  EXPECT_GT (matching::pointSpacing (scan, 2, 0, 5), 0.0);
  expectInvalid ([&] { matching::pointSpacing (scan, 10, 0, 5); }, "point 10 is not in the run [0, 5)");
  expectInvalid ([&] { matching::pointSpacing (scan, -1, 0, 5); }, "point -1 is not in the run [0, 5)");
}

TEST (ApiInputChecks, AJointResultOutsideItsClustersIsNamed)
{
  joint::JointResult result;
  result.source_match.assign (3, kNoMatch);
  result.source_cluster = {0, 0, 99};  // copied into the prediction before
  result.cluster_motions = {Rigid2d::Identity ()};
  result.static_cluster = 0;
  expectInvalid ([&] { joint::toPrediction (arc (3), result); }, "point 2 is in cluster 99 of 1");
  result.source_cluster = {0, 0, 0};
  result.static_cluster = 42;
  expectInvalid ([&] { joint::toPrediction (arc (3), result); }, "the static cluster 42 is not one of the 1");
}

}  // namespace
