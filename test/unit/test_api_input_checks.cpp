// Inputs that do not fit together are errors naming the function and the problem: each
// of these crashed, read or wrote out of bounds, or returned NaN before (an audit of the
// core API).
#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/core/repeated_points.h>
#include <pcl_crf/core/rigid_fit.h>
#include <pcl_crf/core/scan_thinning.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_features.h>
#include <pcl_crf/joint/ladder_inference.h>
#include <pcl_crf/matching/candidates.h>
#include <pcl_crf/matching/lifted_matches.h>
#include <pcl_crf/matching/robust_rigid_fit.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>
#include <pcl_crf/matching/shape_features.h>
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
                 "point 3 has a NaN or infinite coordinate");
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

TEST (ApiInputChecks, CoordinatesBeyondTheLargestAreNamed)
{
  // Coordinates beyond kMaxCoordinate (1e18 m) are refused by the dataset format and the
  // PCL adapters; in the core API a point at 1e200 m came out as "queries hold NaN or
  // infinite values" (estimateJoint) or "node 0 has a NaN or +inf unary log-potential"
  // (clusterPointPairs), its squared distances overflowing.
  Eigen::Matrix2Xd far = arc (6);
  EXPECT_EQ (scanPointsProblem (far, "source"), "");
  far (1, 4) = -1e200;
  EXPECT_EQ (scanPointsProblem (far, "source"), "source point 4 has a coordinate beyond 1e18 m");
  far (0, 2) = kNaN;
  EXPECT_EQ (scanPointsProblem (far, "target"), "target point 2 has a NaN or infinite coordinate");
  far (0, 2) = 1.0;
  const std::vector<int> match{0, 1, 2, 3, 4, 5};
  expectInvalid ([&] { clustering::makePointPairs (far, arc (6), match); }, "source point 4 has a coordinate beyond");
  expectInvalid ([&] { clustering::makePointPairs (arc (6), far, match); },
                 "matches target point 4, which has a NaN, infinite or beyond-1e18-m coordinate");
  clustering::PointPairs pairs = clustering::makePointPairs (arc (6), arc (6), match);
  pairs.target (0, 1) = 1e19;
  EXPECT_EQ (clustering::pointPairsProblem (pairs), "the pairs' target point 1 has a coordinate beyond 1e18 m");
  SensorInfo sensor;
  sensor.beam_count = 10;
  sensor.angle_increment = M_PI / 180.0;
  sensor.range_max = 30.0;
  expectInvalid ([&] { clustering::detectDynamicSegments (arc (6), far, sensor, Rigid2d::Identity ()); },
                 "the other scan's point 4 has a coordinate beyond 1e18 m");
  Odometry odometry;
  odometry.T_source_target.translation () << 2e18, 0.0;
  EXPECT_EQ (odometryProblem (odometry), "odometry translation beyond 1e18 m");
}

TEST (ApiInputChecks, SegmentSettingsOutOfRangeAreNamed)
{
  // A NaN breakpoint angle segmented every scan as NaN comparisons fell, and the joint
  // model's post-processing steps took it without a word.
  const Eigen::Matrix2Xd scan = arc (5);
  expectInvalid ([&] { matching::segmentScan (scan, kNaN, 0.01); }, "the breakpoint angle must be in (0, pi/2] rad");
  expectInvalid ([&] { matching::segmentScan (scan, 0.17, -1.0); }, "the range noise a distance >= 0 m");
  expectInvalid ([&] { matching::occludedSurfaces (scan, {{0, 5}}, 2.0, 0.01); }, "[pcl_crf::matching::occludedSurfaces]");
  matching::SegmentMotionParameters parameters;
  EXPECT_EQ (matching::segmentParametersProblem (parameters), "");
  parameters.breakpoint_angle = kNaN;
  EXPECT_EQ (matching::segmentParametersProblem (parameters), "breakpoint_angle must be in (0, pi/2] rad");
  joint::JointResult result;
  result.source_match.assign (5, kNoMatch);
  result.source_cluster.assign (5, 0);
  result.cluster_motions = {Rigid2d::Identity ()};
  result.static_cluster = 0;
  expectInvalid ([&] { joint::markPointsThatMovedAway (scan, scan, parameters, result); },
                 "the segment parameters: breakpoint_angle must be in (0, pi/2] rad");
  parameters = matching::SegmentMotionParameters ();
  parameters.overlap_radius = kNaN;
  expectInvalid ([&] { joint::removeClustersTheStaticWorldExplains (scan, parameters, result); },
                 "[pcl_crf::joint::removeClustersTheStaticWorldExplains] the segment parameters: overlap_radius");
  matching::MatchingParameters matcher;
  matcher.candidates.segments.range_noise = kNaN;
  expectInvalid ([&] { matching::validateParameters (matcher); }, "range_noise must be a distance >= 0 m");
}

TEST (ApiInputChecks, BuildingBlocksNameInputsThatDoNotFit)
{
  // Each of these read out of bounds on the inputs below.
  const Eigen::Matrix2Xd scan = arc (4);
  matching::Candidates candidates;
  candidates.targets = {0, 1, 1, 2, 3};
  candidates.offsets = {0, 2, 3, 4, 5};
  EXPECT_EQ (matching::matchStates (candidates, {1, kNoMatch, 3, 3}), (std::vector<int>{1, 1, 1, 0}));
  expectInvalid ([&] { matching::matchStates (candidates, {1}); }, "1 matches for the candidates of 4 source points");
  const Eigen::MatrixXd shape = matching::computeShapeFeatures (scan);
  EXPECT_EQ (matching::shapeEmbedding (shape, scan, 10.0).cols (), 4);
  expectInvalid ([&] { matching::shapeEmbedding (shape.leftCols (2), scan, 10.0); }, "shape features for 4 points");
  expectInvalid ([&] { matching::shapeEmbedding (shape.topRows (3), scan, 10.0); }, "3 x 4 shape features");

  const ThinnedScan thinned = thinScan (arc (9), 2, M_PI / 180.0);
  ASSERT_EQ (thinned.kept, (std::vector<int>{0, 2, 4, 6, 8}));
  EXPECT_EQ (matching::targetSpan (thinned, 9, 2), Eigen::Vector2i (3, 5));
  expectInvalid ([&] { matching::targetSpan (thinned, 9, 5); }, "kept point 5 of 5 in a scan of 9 points");
  expectInvalid ([&] { matching::targetSpan (thinned, 4, 1); }, "kept point 1 of 5 in a scan of 4 points");
  expectInvalid ([] { thinScan (arc (9), 2, kNaN); }, "needs the scan's beam spacing, an angle > 0 rad");
  expectInvalid ([] { thinScan (arc (9), 2, 0.0); }, "needs the scan's beam spacing");
  EXPECT_EQ (thinScan (arc (9), 1, kNaN).kept.size (), 9u);  // no thinning, no spacing needed

  const joint::LadderGeometry geometry = joint::makeLadderGeometry (scan, scan, candidates);
  EXPECT_EQ (joint::ladderGeometryProblem (geometry), "");
  matching::Candidates beyond = candidates;
  beyond.targets[4] = 7;
  expectInvalid ([&] { joint::makeLadderGeometry (scan, scan, beyond); },
                 "candidate 0 of source point 3 is target point 7 of 4");
  joint::LadderGeometry broken = geometry;
  broken.candidates = beyond;
  const std::vector<Rigid2d> motions{Rigid2d::Identity ()};
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones (joint::kJointWeightCount);
  joint::RungPotentials rungs;
  expectInvalid ([&] { joint::rungPotentials (broken, motions, weights, rungs); }, "is target point 7 of 4");
  broken = geometry;
  broken.inverse_scales = broken.inverse_scales.leftCols (2);
  expectInvalid ([&] { joint::rungPotentials (broken, motions, weights, rungs); },
                 "2 inverse scales and 3 neighbour distances for 4 source points");
  crf::ChainPotentials association;
  for (int i = 0; i < 4; ++i)
    association.unary.push_back (Eigen::VectorXd::Zero (geometry.associationStates (i)));
  for (int i = 0; i < 3; ++i)
    association.pairwise.push_back (Eigen::MatrixXd::Zero (geometry.associationStates (i), geometry.associationStates (i + 1)));
  const std::vector<int> start_association{0, 0, 0, 0}, start_cluster{0, 0, 0, 0};
  EXPECT_EQ (joint::inferLadder (geometry, association, weights, motions, start_association, start_cluster).cluster.size (), 4u);
  expectInvalid ([&] { joint::inferLadder (broken, association, weights, motions, start_association, start_cluster); },
                 "[pcl_crf::joint::inferLadder] 2 inverse scales");

  joint::rungPotentials (geometry, motions, weights, rungs);
  expectInvalid ([&] { joint::updateRungColumn (geometry, motions[0], weights, 1, rungs); }, "cluster 1");
  joint::RungPotentials unsized;
  expectInvalid ([&] { joint::updateRungColumn (geometry, motions[0], weights, 0, unsized); }, "0 rungs");
  EXPECT_EQ (joint::rungFeatures (geometry, 3, 1, 1, motions) (joint::kRungUnmatchedCluster), 0.0);
  expectInvalid ([&] { joint::rungFeatures (geometry, 4, 0, 0, motions); }, "point 4, association state 0");
  expectInvalid ([&] { joint::rungFeatures (geometry, 0, 3, 0, motions); }, "association state 3");
  expectInvalid ([&] { joint::rungFeatures (geometry, 0, 0, 2, motions); }, "cluster 2");
  expectInvalid ([&] { joint::clusterEdgeFeatures (geometry, 3, 0, 0, motions); }, "edge 3 of 3");
  expectInvalid ([&] { joint::clusterEdgeFeatures (geometry, 0, 0, 2, motions); }, "in clusters 0 and 2");
}

}  // namespace
