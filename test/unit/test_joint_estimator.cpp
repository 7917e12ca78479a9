// The joint model end to end: the shipped model on shipped pairs, the PCL adapter, bad input.
#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/planar_transform.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint_crf_estimator.h>
#include <pcl_crf/impl/joint_crf_estimator.hpp>  // PointNormal, not precompiled
#include <pcl_crf/logs/log_pairs.h>
#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/logs/rosbag_log.h>
#include <pcl_crf/matching/scan_matching.h>
#include <pcl_crf/metrics/association_metrics.h>
#include <pcl_crf/metrics/motion_error.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include "hokuyo_pairs.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <thread>
#include <type_traits>
#include <utility>

namespace {

// A copy would share pcl::Registration's search trees with the original (as ICP, not copyable).
static_assert (!std::is_copy_constructible_v<pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>> &&
                   !std::is_copy_assignable_v<pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>> &&
                   !std::is_move_constructible_v<pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>>,
               "JointCRFEstimator is neither copyable nor movable");

using namespace pcl_crf;

const std::string kModelPath = std::string (PCL_CRF_SOURCE_DIR) + "/data/models/joint.model";
const std::string kTestDir = std::string (PCL_CRF_SOURCE_DIR) + "/data/default/test/";

const joint::JointModel&
shippedModel ()
{
  static const joint::JointModel model = joint::loadJointModel (kModelPath);
  return model;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr
toCloud (const Eigen::Matrix2Xd& xy)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZ>);
  for (Eigen::Index i = 0; i < xy.cols (); ++i)
    cloud->push_back (pcl::PointXYZ (static_cast<float> (xy (0, i)), static_cast<float> (xy (1, i)), 0.0f));
  return cloud;
}

TEST (JointModelFile, ShippedModelRoundTripsExactly)
{
  std::ostringstream first, second;
  joint::writeJointModel (shippedModel (), first);
  std::istringstream text (first.str ());
  joint::writeJointModel (joint::readJointModel (text), second);
  EXPECT_EQ (first.str (), second.str ());
  EXPECT_TRUE (shippedModel ().isTrained ());
}

TEST (JointEstimation, RecoversEgoMotionAndAMovingCarOnShippedPairs)
{
  // pair_0016: a car moving 3.8 m against the static world; pair_0019: a cyclist.
  for (const char* name : {"pair_0016", "pair_0019"}) {
    SCOPED_TRACE (name);
    const ScanPair pair = loadScanPair (kTestDir + name);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    const PairScores scores = scorePair (pair, joint::toPrediction (pair.source, r));
    EXPECT_LT (scores.ego_translation_error, 0.03);  // [m]
    EXPECT_LT (scores.ego_rotation_error, 0.005);    // [rad]
    EXPECT_GT (scores.association_accuracy, 0.85);
    EXPECT_GT (scores.cluster_accuracy, 0.9);
    EXPECT_GE (r.cluster_motions.size (), 2u);  // the mover has a cluster of its own
    EXPECT_EQ (r.source_match.size (), static_cast<std::size_t> (pair.source.cols ()));
  }
}

/** Correct associations of the source points of object \a id. */
int
correctOn (const ScanPair& pair, int id, const std::vector<int>& matches)
{
  int correct = 0;
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    correct += pair.source_object[i] == id && pair.source_match[i] != kNoMatch && matches[i] == pair.source_match[i];
  return correct;
}

/** Matched source points of object \a id (those with a true association). */
int
matchedOn (const ScanPair& pair, int id)
{
  int matched = 0;
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    matched += pair.source_object[i] == id && pair.source_match[i] != kNoMatch;
  return matched;
}

/** The simulator's "outline" pairs of the Fig. 3 tests (seed, index): a car (object 1)
 *  driving along its own outline. */
const std::vector<std::pair<int, int>> kOutlinePairs{{208, 2}, {411, 4}};

ScanPair
outlinePair (int seed, int index)
{
  simulation::SimulatorConfig config;
  config.scene = simulation::SceneType::Outline;
  config.seed = static_cast<std::uint64_t> (seed);
  return simulation::ScanPairSimulator (config).simulate (index);
}

TEST (JointEstimation, AssociatesAMovingCarAlongItsMotionWhereCrfMatchingAloneDoesNot)
{
  // The joint paper's Fig. 3 effect on pairs neither model was trained on: the
  // simulator's "outline" scene, a car driving along its own outline, whose sides look
  // the same shifted or not. CRF-Matching alone associates none of the car's matched
  // points correctly (it takes the target points they would meet had the car stood
  // still); the joint model, where the car's cluster and its motion tie the
  // associations of its points together, gets most of them. Measured: seed 208 pair 2,
  // 0 and 44 of 66; seed 411 pair 4, 0 and 57 of 80 (the same with the models shipped
  // before the overlap radius in point spacings: 0 / 44 and 0 / 56). Over seeds
  // 101–599 (five pairs each), a car of 20 or more matched points that CRF-Matching
  // gets at most 3 of and the joint model a quarter or more of turns up 28 times
  // (25 with those earlier models; seed 101 pair 0, this test's pair then, is one of
  // the 5 they alone show).
  const matching::CrfMatchingModel matcher =
      matching::loadModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-matching.model");
  const int car = 1;
  for (const auto& [seed, index] : kOutlinePairs) {
    SCOPED_TRACE ("seed " + std::to_string (seed) + " pair " + std::to_string (index));
    const ScanPair pair = outlinePair (seed, index);
    ASSERT_EQ (pair.objects[pair.objectIndex (car)].kind, "car");
    const int matched = matchedOn (pair, car);
    ASSERT_GE (matched, 60);
    const matching::MatchResult alone =
        matching::matchScans (pair.source, pair.target, matching::MotionGuess::fromOdometry (pair.odometry), matcher);
    const joint::JointResult together = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    EXPECT_LE (correctOn (pair, car, alone.matches), 3);
    EXPECT_GE (correctOn (pair, car, together.source_match), matched / 2);
  }
}

TEST (JointEstimation, DoesNotSeekACarFartherThanItCanHaveDrivenInTheScanInterval)
{
  // The Fig. 3 pairs again, each car moving d metres relative to the static world. With
  // the pairs' true interval (d / interval is the car's 3–6 m/s, far below the model's
  // 30 m/s) the joint model follows the car; were the scans d / 60 s apart, 30 m/s
  // reaches only half of d, and no search may take the car's points that far.
  const int car = 1;
  for (const auto& [seed, index] : kOutlinePairs) {
    SCOPED_TRACE ("seed " + std::to_string (seed) + " pair " + std::to_string (index));
    ScanPair pair = outlinePair (seed, index);
    const Rigid2d world = pair.objects[pair.objectIndex (pair.staticObjectId ())].T_target_source;
    const Rigid2d moved = pair.objects[pair.objectIndex (car)].T_target_source;
    const double d = (moved.translation () - world.translation ()).norm ();
    ASSERT_GT (pair.odometry.interval, 0.2);
    EXPECT_GE (correctOn (pair, car, joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ()).source_match),
               matchedOn (pair, car) / 2);
    pair.odometry.interval = d / 60.0;
    EXPECT_LE (correctOn (pair, car, joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ()).source_match),
               3);
  }
}

TEST (JointAssociation, TakesTheNearestTargetPointUnderEachClustersMotion)
{
  // Two clusters: a wall that stays (identity) and a box that moved 1 m along x. The
  // target has both, sampled every 0.1 m; a point takes the target point nearest to
  // where its own cluster's motion puts it, not the one nearest to itself.
  Eigen::Matrix2Xd source (2, 6), target (2, 12);
  for (int k = 0; k < 3; ++k) {
    source.col (k) << 0.1 * k, 5.0;         // wall
    source.col (3 + k) << 0.1 * k, 2.0;     // box, moves +1 m in x
  }
  for (int k = 0; k < 6; ++k) {
    target.col (k) << 0.1 * k, 5.0;
    target.col (6 + k) << 0.8 + 0.1 * k, 2.0;  // the box's new place: x from 0.8 to 1.3
  }
  KnnIndex target_points;
  target_points.build (target);
  const std::vector<Rigid2d> motions = {Rigid2d::Identity (), Rigid2d (Eigen::Translation2d (1.0, 0.0))};
  const std::vector<int> cluster = {0, 0, 0, 1, 1, 1};
  std::vector<int> match (6, kNoMatch);
  joint::associateUnderClusterMotions (source, target_points, {0, 1, 3, 4, 5}, cluster, motions, match);
  EXPECT_EQ (match, (std::vector<int>{0, 1, kNoMatch, 8, 9, 10}));  // point 2 was not asked for
  EXPECT_THROW (joint::associateUnderClusterMotions (source, target_points, {6}, cluster, motions, match),
                std::invalid_argument);  // not a source point
  EXPECT_THROW (joint::associateUnderClusterMotions (source, target_points, {0}, {0, 0, 0}, motions, match),
                std::invalid_argument);  // not one cluster per source point
  EXPECT_THROW (joint::associateUnderClusterMotions (source, target_points, {0}, std::vector<int> (6, 2), motions, match),
                std::invalid_argument);  // a cluster without a motion
  EXPECT_THROW (joint::associateUnderClusterMotions (source, KnnIndex (), {0}, cluster, motions, match),
                std::invalid_argument);  // empty target
}

TEST (JointEstimation, FinalClustersKeepApartWhatTheLadderMerges)
{
  // Fresh pairs of the default distribution (the simulator's defaults, seed 3003, as
  // scripts/heldout_table.sh draws them). Measured with the ladder's own clusters
  // (before CRF-Clustering of the final associations gave the clusters): V 0.47, 0.00
  // (the car left in the static world) and 0.00 (a static world split in two); now
  // 0.68, 0.78 and 1.00 (0.98, 0.78 and 1.00 with the model trained before clusters the
  // static world explains were removed, whose outlier bias sat one grid step higher: pair
  // 0's car gains 4 static points; 0.87, 0.78 and 1.00 before the overlap radius in point
  // spacings).
  simulation::SimulatorConfig config;
  config.seed = 3003;
  const simulation::ScanPairSimulator simulator (config);
  const std::vector<std::pair<int, double>> expected = {{0, 0.6}, {3, 0.7}, {12, 0.99}};
  for (const auto& [index, min_v] : expected) {
    const ScanPair pair = simulator.simulate (index);
    SCOPED_TRACE (pair.name);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    EXPECT_GE (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, min_v);
    if (pair.objects.size () == 1) {
      EXPECT_EQ (r.cluster_motions.size (), 1u);
    }
  }
}

TEST (JointEstimation, AFacadeThatLeftTheViewDoesNotSplitTheStaticWorld)
{
  // Shipped test pairs 21 and 23 show no mover. Measured: the ladder and the final
  // clustering give a stretch of façade that left the target's view (40 and 16 points,
  // truly unmatched) its own cluster, slid 5.9 and 5.7 m along the façade onto target
  // points the static world already explains, so V = 0; removing such clusters leaves
  // the static world alone (V = 1) and those points outliers.
  const std::vector<ScanPair> pairs = loadDataset (kTestDir);
  ASSERT_EQ (pairs.size (), 30u);
  joint::JointParameters keep;
  keep.remove_clusters_the_static_world_explains = false;
  for (int index : {21, 23}) {
    const ScanPair& pair = pairs[index];
    SCOPED_TRACE (pair.name);
    for (int object : pair.source_object)  // no mover among the source points
      ASSERT_EQ (object, pair.staticObjectId ());
    const joint::JointResult kept = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), keep);
    EXPECT_GE (kept.cluster_motions.size (), 2u);
    EXPECT_EQ (scorePair (pair, joint::toPrediction (pair.source, kept)).v_measure, 0.0);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    ASSERT_EQ (r.cluster_motions.size (), 1u);
    EXPECT_EQ (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, 1.0);
    EXPECT_GT (r.outliers.size (), kept.outliers.size () + 15);
  }
}

TEST (JointEstimation, AVehicleAlongsideIsSeparatedByTheFreeSpaceItMovedInto)
{
  // Shipped test pairs 7 and 9: a truck side (162 points, 14 m long, 1.0 m slide) and a
  // car side (90 points, 2.9 m slide) along the sensor's left. Measured: without the
  // free-space step one cluster holds everything (V = 0); with it, V = 0.973 and 1.
  const std::vector<ScanPair> pairs = loadDataset (kTestDir);
  ASSERT_EQ (pairs.size (), 30u);
  joint::JointParameters without;
  without.separate_objects_in_free_space = false;
  for (int index : {7, 9}) {
    const ScanPair& pair = pairs[index];
    SCOPED_TRACE (pair.name);
    const joint::JointResult merged = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), without);
    EXPECT_EQ (merged.cluster_motions.size (), 1u);
    EXPECT_EQ (scorePair (pair, joint::toPrediction (pair.source, merged)).v_measure, 0.0);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    ASSERT_EQ (r.cluster_motions.size (), 2u);
    const PairScores scores = scorePair (pair, joint::toPrediction (pair.source, r));
    EXPECT_GT (scores.v_measure, 0.97);
    EXPECT_LT (scores.static_translation_error, 0.05);
  }
}

TEST (JointEstimation, ABuildingsEndTheTargetSeesEdgeOnDoesNotSlide)
{
  // The simulator's static street, seed 6006, pair 8: the ego drove 3.33 m past a
  // building whose end face (1.9 m deep, 68 points with its front) the target sees
  // edge-on, 2–6 cm in front of its origin. Its beams there land beyond the face, so three
  // noisy points of it read as seen through, and a 0.14 m slide of the whole building
  // (onto the next beams) dominated the static motion: V = 0. Beams grazing a segment
  // (at less than the breakpoint angle) now tell nothing, and the street stays one.
  simulation::SimulatorConfig config;
  config.scene = simulation::SceneType::Static;
  config.seed = 6006;
  const ScanPair pair = simulation::ScanPairSimulator (config).simulate (8);
  ASSERT_EQ (pair.objects.size (), 1u);
  joint::JointResult truth;
  truth.cluster_motions = {pair.objects[0].T_target_source};
  truth.static_cluster = 0;
  truth.source_cluster.assign (static_cast<std::size_t> (pair.source.cols ()), 0);
  truth.source_match.assign (static_cast<std::size_t> (pair.source.cols ()), kNoMatch);
  EXPECT_EQ (joint::separateSegmentsTheTargetSeesThrough (pair.source, pair.target, {}, 2, truth), 0);
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  EXPECT_EQ (r.cluster_motions.size (), 1u);
  EXPECT_EQ (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, 1.0);
}

TEST (JointEstimation, ACyclistCrossingIsSeparatedWhereverTheFreeSpaceRunLandsIt)
{
  // The simulator's crossing street, seed 6006, pair 18: a cyclist 18 m ahead crossing
  // 1.27 m to the left, seen side-on (12 points 0.16 m apart). Free space bounds its
  // slide to a run 0.3 m wide; at the run's middle, 0.15 m short, only 4 of its points
  // land on the target's samples, one fewer than the static motion puts on their ends,
  // and the cyclist stayed in the static world (V = 0). Some shift of the run lands
  // enough: the cyclist is a cluster of its own.
  simulation::SimulatorConfig config;
  config.scene = simulation::SceneType::Crossing;
  config.seed = 6006;
  const ScanPair pair = simulation::ScanPairSimulator (config).simulate (18);
  const int cyclist = 1;
  ASSERT_EQ (pair.objects[pair.objectIndex (cyclist)].kind, "cyclist");
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  std::vector<int> clusters;
  Eigen::Index first = -1;
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    if (pair.source_object[i] == cyclist) {
      clusters.push_back (r.source_cluster[i]);
      first = first < 0 ? i : first;
    }
  ASSERT_EQ (clusters.size (), 12u);
  EXPECT_NE (clusters.front (), r.static_cluster);
  EXPECT_NE (clusters.front (), kOutlierCluster);
  EXPECT_EQ (std::count (clusters.begin (), clusters.end (), clusters.front ()), 12);
  const Rigid2d& T_true = pair.objects[pair.objectIndex (cyclist)].T_target_source;
  const Rigid2d& T = r.cluster_motions[clusters.front ()];
  EXPECT_LT ((T * pair.source.col (first) - T_true * pair.source.col (first)).norm (), 0.3);  // the run's width
  EXPECT_GT (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, 0.9);
}

/** Pair \a index of the simulator's mixed street with seed 3003 (the first of the fresh
 *  seeds of scripts/heldout_table.sh). */
ScanPair
freshPairOfSeed3003 (int index)
{
  simulation::SimulatorConfig config;
  config.seed = 3003;
  return simulation::ScanPairSimulator (config).simulate (index);
}

/** How many points of \a labels are \a object's. */
std::ptrdiff_t
pointsOfObject (const std::vector<int>& labels, int object)
{
  return std::count (labels.begin (), labels.end (), object);
}

TEST (JointEstimation, ACarSplitByTwoStepsBecomesOneWhereItsPartsMeetAndMoveAlike)
{
  // Simulator seed 3003, pair 21 (mixed street, 30 fresh pairs): a car of 107 points
  // that the steps before the merge left in two clusters (94 + 13 points) meeting on
  // one surface, their motions alike on the 13 (V 0.852). Merged, it is one (V 0.930).
  const ScanPair pair = freshPairOfSeed3003 (21);
  const int car = 2;
  ASSERT_EQ (pointsOfObject (pair.source_object, car), 107);
  const auto clustersOfTheCar = [&] (const joint::JointResult& r) {
    std::vector<int> clusters;
    for (std::size_t i = 0; i < pair.source_object.size (); ++i)
      if (pair.source_object[i] == car)
        clusters.push_back (r.source_cluster[i]);
    std::sort (clusters.begin (), clusters.end ());
    return static_cast<int> (std::unique (clusters.begin (), clusters.end ()) - clusters.begin ());
  };
  joint::JointParameters apart;
  apart.merge_adjacent_clusters_that_move_alike = false;
  EXPECT_EQ (clustersOfTheCar (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), apart)), 2);
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  EXPECT_EQ (clustersOfTheCar (r), 1);
  EXPECT_GT (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, 0.92);
}

TEST (JointEstimation, ACarAlongsideTakesTheRestOfItsSideFromTheStaticWorld)
{
  // Simulator seed 3003, pair 19: a car of 139 points alongside, 1.22 m slower than the
  // sensor, its side one surface sliding along itself. Only 41 points near its end were
  // given the car's motion; the static motion explains 41 others as well as the car's
  // does, and the 57 without a match (outliers) take the static world's label in the
  // prediction (98 in all, V 0.320). The 41 join the car, and the 57 with them (V 0.924).
  const ScanPair pair = freshPairOfSeed3003 (19);
  const int car = 1;
  ASSERT_EQ (pointsOfObject (pair.source_object, car), 139);
  const auto inStaticWorld = [&] (const joint::JointResult& r) {
    const pcl_crf::Prediction prediction = joint::toPrediction (pair.source, r);
    int n = 0;
    for (std::size_t i = 0; i < pair.source_object.size (); ++i)
      n += pair.source_object[i] == car && prediction.source_cluster[i] == prediction.static_cluster ? 1 : 0;
    return n;
  };
  joint::JointParameters parameters;
  parameters.sensor = pair.sensor;  // as pcl_crf_eval passes it
  joint::JointParameters unextended = parameters;
  unextended.extend_moving_clusters_over_their_surfaces = false;
  EXPECT_EQ (inStaticWorld (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), unextended)),
             98);
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), parameters);
  EXPECT_EQ (inStaticWorld (r), 0);
  EXPECT_GT (scorePair (pair, joint::toPrediction (pair.source, r)).v_measure, 0.92);
}

TEST (JointEstimation, ACarThatLeftTheViewIsNotMatchedOntoTheCarFollowingIt)
{
  // Test pair 17: in the oncoming lane a car of 59 points 7.6 m away drives out of the
  // target's view behind the sensor, and the car 12.4 m away (27 points) takes its
  // place. The first was clustered with a motion onto the second's view in the target,
  // 6.4 m from its true one, both clusters claiming 19 target points. The one that moved
  // farther from the static motion goes: its points become outliers, free for the
  // later steps, which give the car a cluster of its own with its true motion.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0017");
  const int leaving = 3, following = 1;
  ASSERT_EQ (pointsOfObject (pair.source_object, leaving), 59);
  ASSERT_EQ (pointsOfObject (pair.source_object, following), 27);
  joint::JointParameters parameters;
  parameters.sensor = pair.sensor;
  joint::JointParameters kept = parameters;
  kept.remove_clusters_a_nearer_cluster_explains = false;
  const auto score = [&] (const joint::JointParameters& p) {
    return scorePair (pair, joint::toPrediction (pair.source, joint::estimateJoint (pair.source, pair.target,
                                                                                     pair.odometry, shippedModel (), p)));
  };
  const pcl_crf::PairScores before = score (kept), after = score (parameters);
  EXPECT_NEAR (before.association_accuracy, 0.809, 0.001);
  EXPECT_NEAR (after.association_accuracy, 0.948, 0.001);
  EXPECT_NEAR (after.v_measure, before.v_measure, 1e-9);  // the car is still one group
  const Rigid2d& T_true = pair.objects[pair.objectIndex (leaving)].T_target_source;
  const auto motionError = [&] (const joint::JointParameters& p) {  // mean over the car's points
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), p);
    double error = 0.0;
    int cluster = -2;
    for (std::size_t i = 0; i < pair.source_object.size (); ++i)
      if (pair.source_object[i] == leaving) {
        EXPECT_TRUE (cluster == -2 || r.source_cluster[i] == cluster) << i;  // one cluster
        cluster = r.source_cluster[i];
        EXPECT_NE (cluster, r.static_cluster);
        EXPECT_NE (cluster, kOutlierCluster);
        const Eigen::Vector2d p_i = pair.source.col (static_cast<Eigen::Index> (i));
        error += (r.cluster_motions[cluster] * p_i - T_true * p_i).norm () / 59.0;
      }
    return error;
  };
  EXPECT_GT (motionError (kept), 6.0);
  EXPECT_LT (motionError (parameters), 0.1);
}

TEST (JointEstimation, ACarThatLeftTheTargetsViewIsNotTheStaticWorld)
{
  // Simulator seed 3003, pair 23: a car of 68 points that the target no longer sees.
  // Without a counterpart its points are outliers, which the prediction used to give the
  // static world's label (V 0.170). The target saw through to returns beyond 40 of them
  // under the static motion: they moved away, and the prediction keeps the car out of
  // the static world (V 0.883).
  const ScanPair pair = freshPairOfSeed3003 (23);
  const int car = 2;
  ASSERT_EQ (pointsOfObject (pair.source_object, car), 68);
  ASSERT_EQ (pointsOfObject (pair.target_object, car), 0);
  const auto carOutliers = [&] (const pcl_crf::Prediction& prediction) {
    int outliers = 0;
    for (std::size_t i = 0; i < pair.source_object.size (); ++i)
      outliers += pair.source_object[i] == car && prediction.source_cluster[i] == kOutlierCluster ? 1 : 0;
    return outliers;
  };
  joint::JointParameters unmarked;
  unmarked.mark_points_that_moved_away = false;
  const joint::JointResult before = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), unmarked);
  EXPECT_TRUE (before.moved_away.empty ());
  EXPECT_EQ (carOutliers (joint::toPrediction (pair.source, before)), 0);
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  ASSERT_EQ (r.moved_away.size (), 40u);
  for (int i : r.moved_away)
    EXPECT_EQ (pair.source_object[i], car) << i;
  const pcl_crf::Prediction prediction = joint::toPrediction (pair.source, r);
  EXPECT_EQ (carOutliers (prediction), 68);
  EXPECT_GT (scorePair (pair, prediction).v_measure, 0.85);
}

TEST (JointEstimation, ASlidSegmentNeedsAsManyBearingsSeenThroughOnAFinerScan)
{
  // Simulator seed 3003, pair 8, at 1081 beams over 270° (0.25°, thinned by 2 for the
  // 0.5° models): the end of a building the ego drove 3.2 m past shows 2 points seen
  // through near its corner under the static motion, one beam of the training scans, and
  // a 0.08 m slide of the building (154 points) removed them. Asking twice the points
  // on a scan twice as fine keeps the static world whole.
  const ScanPair pair = test::hokuyoPair (3003, 8);
  const auto worldClusters = [&] (const joint::JointResult& r) {
    std::vector<int> clusters;
    for (std::size_t i = 0; i < pair.source_object.size (); ++i)
      if (pair.source_object[i] == pair.staticObjectId () && r.source_cluster[i] != kOutlierCluster)
        clusters.push_back (r.source_cluster[i]);
    std::sort (clusters.begin (), clusters.end ());
    return static_cast<int> (std::unique (clusters.begin (), clusters.end ()) - clusters.begin ());
  };
  joint::JointParameters as_many_points;  // 1 point at 0.5°: 2 at 0.25°, as before
  as_many_points.segment_min_points_seen_through = 1;
  EXPECT_EQ (worldClusters (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), as_many_points)), 2);
  EXPECT_EQ (worldClusters (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ())), 1);
}

TEST (JointEstimation, AssociatesBetterThanCrfMatchingOnTheShippedTestSplit)
{
  // Measured: 0.829 against CRF-Matching's 0.804 (0.830 against 0.813 before the
  // overlap radius in point spacings; 0.820 before the matched points were associated
  // under their clusters' final motions).
  const matching::CrfMatchingModel matcher =
      matching::loadModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-matching.model");
  const std::vector<ScanPair> pairs = loadDataset (kTestDir);
  ASSERT_EQ (pairs.size (), 30u);
  double joint_accuracy = 0.0, matching_accuracy = 0.0;
  for (const ScanPair& pair : pairs) {
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    joint_accuracy += scorePair (pair, joint::toPrediction (pair.source, r)).association_accuracy / pairs.size ();
    const matching::MatchResult alone =
        matching::matchScans (pair.source, pair.target, matching::MotionGuess::fromOdometry (pair.odometry), matcher);
    matching_accuracy += associationAccuracy (alone.matches, pair.source_match) / pairs.size ();
  }
  EXPECT_GT (joint_accuracy, 0.825);
  EXPECT_GT (joint_accuracy, matching_accuracy + 0.012);
}

TEST (JointEstimation, FinerScansAreEstimatedAtTheResolutionItWasTrainedAt)
{
  // The shipped model learned from 0.5° scans; on 0.25° scans (1081 beams over 270°)
  // it runs on every other beam and lifts its clusters and associations back.
  // Measured on these six pairs: association accuracy 0.846, motion-detection accuracy
  // 0.943 and V 0.560, against 0.858, 0.953 and 0.726 on every beam (the overlap radius
  // in point spacings made the models less sensitive to the resolution; before it,
  // 0.844 / 0.961 / 0.540 against 0.817 / 0.924 / 0.404). On the 60 pairs of the
  // README's 1081-beam table thinning still detects motion better (0.899 and V 0.540
  // against 0.880 and 0.478 on every beam, association 0.803 against 0.807) in 2.4
  // times less time, so it stays; here it must not fall far behind.
  const std::vector<ScanPair> pairs = test::hokuyoPairs (13, 6);
  joint::JointModel at_full_resolution = shippedModel ();
  at_full_resolution.matcher.parameters.training_beam_spacing = 0.0;
  double thinned = 0.0, full = 0.0, thinned_detection = 0.0, full_detection = 0.0, thinned_v = 0.0, full_v = 0.0;
  for (const ScanPair& pair : pairs) {
    SCOPED_TRACE (pair.name);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    ASSERT_EQ (r.source_match.size (), static_cast<std::size_t> (pair.source.cols ()));
    ASSERT_EQ (r.source_cluster.size (), r.source_match.size ());
    // Clusters numbered largest first, their sizes and the outlier list those of the lifted labels.
    std::vector<int> sizes (r.cluster_motions.size (), 0), outliers;
    for (std::size_t i = 0; i < r.source_cluster.size (); ++i) {
      if (r.source_cluster[i] == kOutlierCluster) {
        outliers.push_back (static_cast<int> (i));
        EXPECT_EQ (r.source_match[i], kNoMatch);
        continue;
      }
      ASSERT_LT (r.source_cluster[i], static_cast<int> (sizes.size ()));
      ++sizes[r.source_cluster[i]];
    }
    EXPECT_EQ (r.cluster_sizes, sizes);
    EXPECT_TRUE (std::is_sorted (sizes.rbegin (), sizes.rend ()));
    EXPECT_EQ (r.outliers, outliers);
    ASSERT_GE (r.static_cluster, 0);
    EXPECT_TRUE (r.T_source_target.isApprox (r.cluster_motions[r.static_cluster].inverse ()));
    const PairScores scores = scorePair (pair, joint::toPrediction (pair.source, r));
    thinned += scores.association_accuracy / pairs.size ();
    thinned_detection += scores.cluster_accuracy / pairs.size ();
    thinned_v += scores.v_measure / pairs.size ();
    const joint::JointResult every_beam = joint::estimateJoint (pair.source, pair.target, pair.odometry, at_full_resolution);
    const PairScores every_beam_scores = scorePair (pair, joint::toPrediction (pair.source, every_beam));
    full += every_beam_scores.association_accuracy / pairs.size ();
    full_detection += every_beam_scores.cluster_accuracy / pairs.size ();
    full_v += every_beam_scores.v_measure / pairs.size ();
  }
  EXPECT_GT (thinned, 0.83);
  EXPECT_GT (thinned, full - 0.03);
  EXPECT_GT (thinned_detection, 0.93);
  EXPECT_GT (thinned_detection, full_detection - 0.03);
  EXPECT_GT (thinned_v, 0.5);
}

TEST (JointEstimation, StaticClusterStartsFromPassOnesRobustMotion)
{
  // CRF-Clustering proposes the initial clusters from pass 1's matches; the static
  // world's cluster (nearest to the odometry) starts from pass 1's robust motion, the
  // others keep their point-to-point fits.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  const joint::JointModel& model = shippedModel ();
  const matching::PreparedTarget target = matching::prepareTarget (pair.target, model.matcher.parameters.candidates);
  const joint::AssociationStage stage = joint::firstAssociationPass (
      pair.source, target, matching::MotionGuess::fromOdometry (pair.odometry), model.matcher);
  const joint::LadderStart start = joint::initialClusters (pair.source, pair.target, stage, model, {}, pair.odometry);
  ASSERT_GE (start.motions.size (), 2u);
  int starts_at_pass_one = 0;
  for (const Rigid2d& motion : start.motions)
    starts_at_pass_one += motion.matrix () == stage.T_first.matrix () ? 1 : 0;
  EXPECT_EQ (starts_at_pass_one, 1);
}

TEST (JointEstimation, DoesNotSlideAlongTheCsailCorridor)
{
  // csail, scans 112 → 113 (1.06 m of travel along a corridor): CRF-Clustering's
  // point-to-point fit of pass 1's matches slid 0.17 m along the corridor, and the
  // ladder's refits, started there, slid on to 0.59 m of ego-motion error. Started from
  // pass 1's robust motion, the static world stays within 2 cm.
  const std::string path = std::string (PCL_CRF_SHARED_DATA_DIR) + "/carmen/csail-corrected.log.gz";
  if (!std::filesystem::is_regular_file (path))
    GTEST_SKIP () << path << " is absent (the shared real-data folder is optional)";
  const ScanPair pair = makeLogPair (readLaserLog (path), 112);
  Rigid2d reference;
  ASSERT_TRUE (referenceEgoMotion (pair, reference));
  const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  EXPECT_LT (computeMotionError (r.T_source_target, reference).translation, 0.02);  // [m]; measured 0.008
}

TEST (JointEstimation, StandsStillAmongWalkingPeople)
{
  // people_stationary_robot.bag, scans 700 → 740: the robot stands still (the true ego
  // motion is the identity) while people walk around it; at scan 710 one fills a third
  // of the scan 0.5 m in front of the sensor. The static world must not follow them.
  const std::string path = std::string (PCL_CRF_SHARED_DATA_DIR) + "/rosbag/people_stationary_robot.bag";
  if (!std::filesystem::is_regular_file (path))
    GTEST_SKIP () << path << " is absent (the shared real-data folder is optional)";
  if (!rosbagSupported ())
    GTEST_SKIP () << "built without ROS bag support";
  const LaserLog log = readLaserLog (path);
  std::vector<double> translation, rotation;
  for (std::size_t k = 700; k < 740; ++k) {
    const ScanPair pair = makeLogPair (log, k);
    const joint::JointResult r = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
    const MotionError error = computeMotionError (r.T_source_target, Rigid2d::Identity ());
    translation.push_back (error.translation);
    rotation.push_back (error.rotation);
  }
  std::sort (translation.begin (), translation.end ());
  std::sort (rotation.begin (), rotation.end ());
  EXPECT_LT (translation[translation.size () / 2], 0.008);  // [m]; measured 0.0045 (ICP: 0.028)
  EXPECT_LT (translation.back (), 0.03);                     // [m]; measured 0.017 (ICP: 0.135)
  EXPECT_LT (rotation.back (), 0.01);                        // [rad]; measured 0.0044 (ICP: 0.044)
}

const std::string kOvertakesBag = std::string (PCL_CRF_SHARED_DATA_DIR) + "/rosbag/overtakes.bag";

/** Why the real overtakes bag cannot be read here, or an empty string. */
std::string
overtakesBagMissing ()
{
  if (!std::filesystem::is_regular_file (kOvertakesBag))
    return kOvertakesBag + " is absent (the shared real-data folder is optional)";
  return rosbagSupported () ? "" : "built without ROS bag support";
}

/** Scans \a scan → \a scan + 1 of the overtakes bag, labelled, read as the README's
 *  pcl_crf_run line does. */
ScanPair
overtakesPair (std::size_t scan)
{
  LaserLogReadOptions read;
  read.rosbag.pose_topic = "/ego_pose";
  read.rosbag.object_topics = {"/red_pose"};
  read.rosbag.T_pose_laser = makeRigid2d (-0.166, 0.019, 0.0);
  read.rosbag.pose_delay = 0.025;
  read.carmen.max_range = 8.0;
  LogPairOptions labels;
  labels.label_points = true;
  return makeLogPair (readLaserLog (kOvertakesBag, read), scan, labels);
}

TEST (JointEstimation, TheFinalClusteringKeepsARealSmallCarThatTheWallsWouldPullIntoTheirMotion)
{
  // overtakes.bag, scans 57 → 58 (read as the README's pcl_crf_run line does): a
  // 1/10-scale car 0.5 m from the sensor moves 5 cm against the walls. The ladder's
  // associations follow its motion, but refitted to every pair's marginal the wall
  // pairs pulled the car's motion to theirs and N_eff merged it into the static world.
  const std::string missing = overtakesBagMissing ();
  if (!missing.empty ())
    GTEST_SKIP () << missing;
  const ScanPair pair = overtakesPair (57);
  const auto v_with = [&pair] (clustering::MotionFit fit) {
    joint::JointParameters parameters;
    parameters.sensor = pair.sensor;
    parameters.final_motion_fit = fit;
    const joint::JointResult r =
        joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), parameters);
    return scorePair (pair, joint::toPrediction (pair.source, r)).v_measure;
  };
  EXPECT_EQ (v_with (clustering::MotionFit::OwnPoints), 1.0);
  EXPECT_EQ (v_with (clustering::MotionFit::Marginals), 0.0);
}

TEST (JointEstimation, TheFinalClusteringJoinsNoWorldSegmentToACarAcrossARunOfMissingReturns)
{
  // overtakes.bag, scans 74 → 75 (read as the README's pcl_crf_run line does): a
  // 1/10-scale car 0.5–0.6 m from the sensor moves a few cm; the world's next returns
  // come after more than 10 beams without one. The final CRF-Clustering's weighted
  // neighbour feature (1/d of a 0.3 m gap) joined world points there to the car.
  const std::string missing = overtakesBagMissing ();
  if (!missing.empty ())
    GTEST_SKIP () << missing;
  const ScanPair pair = overtakesPair (74);
  const auto world_points_with_the_car = [&pair] (bool bound) {
    joint::JointParameters parameters;
    parameters.sensor = pair.sensor;
    parameters.bound_weighted_neighbours_by_missing_returns = bound;
    const joint::JointResult r =
        joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), parameters);
    std::map<int, int> car_points;  // cluster -> the car's points in it
    for (std::size_t i = 0; i < r.source_cluster.size (); ++i)
      car_points[r.source_cluster[i]] += pair.source_object[i] != 0 ? 1 : 0;
    const int car = std::max_element (car_points.begin (), car_points.end (), [] (const auto& a, const auto& b) {
                      return a.second < b.second;
                    })->first;
    int world = 0;
    for (std::size_t i = 0; i < r.source_cluster.size (); ++i)
      world += r.source_cluster[i] == car && pair.source_object[i] == 0 ? 1 : 0;
    EXPECT_NE (car, r.static_cluster) << "the car is found either way";
    return world;
  };
  EXPECT_EQ (world_points_with_the_car (false), 8);
  EXPECT_EQ (world_points_with_the_car (true), 0);
}

TEST (JointEstimation, RejectsBadInput)
{
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  EXPECT_THROW (joint::estimateJoint (Eigen::Matrix2Xd (2, 0), pair.target, pair.odometry, shippedModel ()),
                std::invalid_argument);
  Eigen::Matrix2Xd nan = pair.source;
  nan (0, 3) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (joint::estimateJoint (nan, pair.target, pair.odometry, shippedModel ()), std::invalid_argument);
  Eigen::Matrix2Xd far = pair.target;  // "queries hold NaN or infinite values" before
  far (1, 7) = 1e200;
  try {
    joint::estimateJoint (pair.source, far, pair.odometry, shippedModel ());
    ADD_FAILURE () << "no error";
  }
  catch (const std::invalid_argument& e) {
    EXPECT_NE (std::string (e.what ()).find ("target point 7 has a coordinate beyond 1e18 m"), std::string::npos)
        << e.what ();
  }
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, pair.odometry, joint::JointModel ()),
                std::invalid_argument);
  joint::JointParameters bad;
  bad.max_rounds = 0;
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), bad),
                std::invalid_argument);
  Odometry backwards = pair.odometry;
  backwards.interval = -0.1;
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, backwards, shippedModel ()), std::invalid_argument);
  Odometry nowhere = pair.odometry;  // once a crash in the features
  nowhere.T_source_target.translation ().x () = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, nowhere, shippedModel ()), std::invalid_argument);
  Odometry scaled = pair.odometry;
  scaled.T_source_target.linear () *= 2.0;
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, scaled, shippedModel ()), std::invalid_argument);
  joint::JointParameters one_beam;
  one_beam.sensor.beam_count = 1;
  one_beam.sensor.angle_increment = 0.01;
  EXPECT_THROW (joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), one_beam),
                std::invalid_argument);
}

TEST (JointEstimation, ALaserWithABackGivesTheSameResultKnownOrNot)
{
  // Only a laser whose beams go all round changes the free-space steps' field of view
  // (matching::makeRangeProfile (scan, sensor)); the test split's is 180°.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0007");
  ASSERT_EQ (pair.sensor.beam_count, 361);
  joint::JointParameters known;
  known.sensor = pair.sensor;
  const joint::JointResult with = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), known);
  const joint::JointResult without = joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel ());
  EXPECT_EQ (with.source_cluster, without.source_cluster);
  EXPECT_EQ (with.source_match, without.source_match);
  EXPECT_TRUE (with.T_source_target.isApprox (without.T_source_target, 0.0));
}

/** \a pair scanned the other way round: beams in reverse order (a clockwise laser). */
ScanPair
reversedBeams (const ScanPair& pair)
{
  ScanPair reversed = pair;
  const Eigen::Index n = pair.source.cols (), m = pair.target.cols ();
  reversed.source = pair.source.rowwise ().reverse ();
  reversed.target = pair.target.rowwise ().reverse ();
  std::reverse (reversed.source_object.begin (), reversed.source_object.end ());
  std::reverse (reversed.target_object.begin (), reversed.target_object.end ());
  for (Eigen::Index i = 0; i < n; ++i) {
    const int j = pair.source_match[static_cast<std::size_t> (n - 1 - i)];
    reversed.source_match[static_cast<std::size_t> (i)] = j == kNoMatch ? kNoMatch : static_cast<int> (m - 1 - j);
  }
  reversed.sensor.angle_min = pair.sensor.angleMax ();
  reversed.sensor.angle_increment = -pair.sensor.angle_increment;
  return reversed;
}

/** The reflection y → −y of a motion. */
Rigid2d
mirrored (const Rigid2d& T)
{
  const Eigen::Matrix2d flip = Eigen::Vector2d (1.0, -1.0).asDiagonal ();
  Rigid2d M = Rigid2d::Identity ();
  M.linear () = flip * T.linear () * flip;
  M.translation () = flip * T.translation ();
  return M;
}

/** \a pair in the mirror image of its world (y → −y): its clockwise scans become
 *  counter-clockwise again, so the beams stay in the order of increasing bearing. */
ScanPair
mirroredWorld (const ScanPair& pair)
{
  ScanPair mirror = reversedBeams (pair);
  mirror.source.row (1) *= -1.0;
  mirror.target.row (1) *= -1.0;
  for (ObjectTruth& object : mirror.objects)
    object.T_target_source = mirrored (object.T_target_source);
  mirror.odometry.T_source_target = mirrored (pair.odometry.T_source_target);
  const Eigen::Matrix3d flip = Eigen::Vector3d (1.0, -1.0, -1.0).asDiagonal ();  // (dx, dy, dθ)
  mirror.odometry.covariance = flip * pair.odometry.covariance * flip;
  mirror.sensor.angle_min = -pair.sensor.angleMax ();
  mirror.sensor.angle_increment = pair.sensor.angle_increment;
  return mirror;
}

joint::JointResult
estimateWithSensor (const ScanPair& pair)
{
  joint::JointParameters parameters;
  parameters.sensor = pair.sensor;
  return joint::estimateJoint (pair.source, pair.target, pair.odometry, shippedModel (), parameters);
}

TEST (JointEstimation, AClockwiseLaserFindsTheSameCarAndEgoMotion)
{
  // pair_0016 (a car moving 3.8 m against the static world) with its beams reversed:
  // the chains run the other way, the scores stay those of the counter-clockwise scan.
  const ScanPair pair = reversedBeams (loadScanPair (kTestDir + "pair_0016"));
  const joint::JointResult r = estimateWithSensor (pair);
  const PairScores scores = scorePair (pair, joint::toPrediction (pair.source, r));
  EXPECT_LT (scores.ego_translation_error, 0.03);  // [m]
  EXPECT_LT (scores.ego_rotation_error, 0.005);    // [rad]
  EXPECT_GT (scores.association_accuracy, 0.85);
  EXPECT_GT (scores.cluster_accuracy, 0.9);
  EXPECT_GE (r.cluster_motions.size (), 2u);
}

TEST (JointEstimation, AMirroredWorldGivesTheMirroredResult)
{
  // Nothing in the estimator may prefer one side (traffic on the left or the right). The
  // mirrored world scanned counter-clockwise is the mirror image of the world scanned
  // clockwise, point for point: it gets the same labels and the mirrored motions.
  for (const char* name : {"pair_0016", "pair_0024"}) {
    SCOPED_TRACE (name);
    const ScanPair pair = loadScanPair (kTestDir + name);
    const joint::JointResult r = estimateWithSensor (reversedBeams (pair));
    const joint::JointResult m = estimateWithSensor (mirroredWorld (pair));
    EXPECT_EQ (m.source_match, r.source_match);
    EXPECT_EQ (m.source_cluster, r.source_cluster);
    ASSERT_EQ (m.cluster_motions.size (), r.cluster_motions.size ());
    for (std::size_t k = 0; k < r.cluster_motions.size (); ++k)
      EXPECT_TRUE (m.cluster_motions[k].matrix ().isApprox (mirrored (r.cluster_motions[k]).matrix (), 1e-9)) << k;
    EXPECT_GE (r.cluster_motions.size (), 2u);
  }
}

TEST (JointEstimation, HandlesTinyScans)
{
  // One to four points on either side: a result sized to the source, or a clear
  // invalid_argument, never a crash.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  for (int n_source : {1, 2, 4})
    for (int n_target : {1, 3}) {
      SCOPED_TRACE (std::to_string (n_source) + " x " + std::to_string (n_target));
      const Eigen::Matrix2Xd source = pair.source.leftCols (n_source);
      const Eigen::Matrix2Xd target = pair.target.leftCols (n_target);
      try {
        const joint::JointResult r = joint::estimateJoint (source, target, pair.odometry, shippedModel ());
        EXPECT_EQ (r.source_match.size (), static_cast<std::size_t> (n_source));
        EXPECT_EQ (r.source_cluster.size (), static_cast<std::size_t> (n_source));
        EXPECT_TRUE (r.T_source_target.matrix ().allFinite ());
      }
      catch (const std::invalid_argument&) {
      }
    }
}

/** Sets \a pair's target and odometry (as the float matrix PCL users pass, returned)
 *  on \a estimator and aligns its source into \a aligned. */
Eigen::Matrix4f
alignWithPairOdometry (pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>& estimator, const ScanPair& pair,
                       pcl::PointCloud<pcl::PointXYZ>& aligned)
{
  estimator.setInputTarget (toCloud (pair.target));
  const Eigen::Matrix4f odometry = toMatrix4<float> (pair.odometry.T_source_target);
  estimator.setOdometry (odometry, pair.odometry.covariance);
  estimator.align (aligned);
  return odometry;
}

TEST (JointCRFEstimator, AlignsLikeAPclRegistration)
{
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  ASSERT_TRUE (estimator.loadModel (kModelPath));
  auto source = toCloud (pair.source);
  (*source)[5].x = std::numeric_limits<float>::quiet_NaN ();  // skipped, indices still refer to the cloud
  estimator.setInputSource (source);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  alignWithPairOdometry (estimator, pair, aligned);
  ASSERT_TRUE (estimator.hasConverged ());
  // the final transformation is the static world's motion: the inverse of the true ego motion
  const Rigid2d truth = pair.objects[pair.objectIndex (pair.staticObjectId ())].T_target_source;
  const Eigen::Matrix4f T = estimator.getFinalTransformation ();
  EXPECT_NEAR (T (0, 3), truth.translation ().x (), 0.03);
  EXPECT_NEAR (T (1, 3), truth.translation ().y (), 0.03);
  EXPECT_EQ (aligned.size (), source->size ());
  // clusters largest first, disjoint, never holding the NaN point
  const auto& clusters = estimator.getClusters ();
  ASSERT_GE (clusters.size (), 2u);
  std::size_t total = estimator.getOutliers ().size ();
  for (std::size_t k = 0; k < clusters.size (); ++k) {
    total += clusters[k].indices.size ();
    if (k > 0) {
      EXPECT_GE (clusters[k - 1].indices.size (), clusters[k].indices.size ());
    }
    for (int index : clusters[k].indices)
      EXPECT_NE (index, 5);
  }
  EXPECT_EQ (total, source->size () - 1);
  EXPECT_EQ (estimator.getClusterTransformations ().size (), clusters.size ());
  EXPECT_GE (estimator.getStaticCluster (), 0);
  for (const pcl::Correspondence& c : estimator.getCorrespondences ())
    EXPECT_NE (c.index_query, 5);
  EXPECT_GT (estimator.getCorrespondences ().size (), source->size () / 2);
}

/** \a cloud's points in the order \a order (point k of the result is point order[k]). */
pcl::PointCloud<pcl::PointXYZ>::Ptr
reorderedCloud (const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<int>& order)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr out (new pcl::PointCloud<pcl::PointXYZ>);
  for (const int i : order)
    out->push_back (cloud[static_cast<std::size_t> (i)]);
  return out;
}

/** Test pair 16's clouds with their points in the orders \a source_order and \a
 *  target_order are chained in beam order, counter-clockwise: the result is the pair's
 *  own, reported with the reordered clouds' indices. */
void
expectChainedInBeamOrder (bool shuffle)
{
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  const auto source = toCloud (pair.source), target = toCloud (pair.target);
  std::vector<int> source_order (source->size ()), target_order (target->size ());
  std::iota (source_order.begin (), source_order.end (), 0);
  std::iota (target_order.begin (), target_order.end (), 0);
  std::mt19937 rng (16);
  if (shuffle) {
    std::shuffle (source_order.begin (), source_order.end (), rng);
    std::shuffle (target_order.begin (), target_order.end (), rng);
  } else {
    std::reverse (source_order.begin (), source_order.end ());
    std::reverse (target_order.begin (), target_order.end ());
  }
  const Eigen::Matrix4f odometry = toMatrix4<float> (pair.odometry.T_source_target);
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> ordered, reordered;
  for (auto* estimator : {&ordered, &reordered}) {
    estimator->setModel (shippedModel ());
    estimator->setOdometry (odometry, pair.odometry.covariance);
  }
  pcl::PointCloud<pcl::PointXYZ> aligned;
  ordered.setInputSource (source);
  ordered.setInputTarget (target);
  ordered.align (aligned);
  reordered.setInputSource (reorderedCloud (*source, source_order));
  reordered.setInputTarget (reorderedCloud (*target, target_order));
  reordered.align (aligned);
  ASSERT_TRUE (ordered.hasConverged ());
  ASSERT_TRUE (reordered.hasConverged ());
  EXPECT_EQ (reordered.getFinalTransformation (), ordered.getFinalTransformation ());
  ASSERT_EQ (reordered.getCorrespondences ().size (), ordered.getCorrespondences ().size ());
  std::map<int, int> ordered_match;
  for (const pcl::Correspondence& c : ordered.getCorrespondences ())
    ordered_match[c.index_query] = c.index_match;
  for (const pcl::Correspondence& c : reordered.getCorrespondences ())
    EXPECT_EQ (target_order[c.index_match], ordered_match.at (source_order[c.index_query]));
  ASSERT_EQ (reordered.getClusters ().size (), ordered.getClusters ().size ());
  for (std::size_t l = 0; l < ordered.getClusters ().size (); ++l) {
    std::vector<int> mapped;
    for (const int i : reordered.getClusters ()[l].indices)
      mapped.push_back (source_order[static_cast<std::size_t> (i)]);
    std::sort (mapped.begin (), mapped.end ());
    EXPECT_EQ (mapped, ordered.getClusters ()[l].indices) << "cluster " << l;
  }
  // The index lists are in cloud order (increasing), whatever order the chains read.
  for (const pcl::PointIndices& cluster : reordered.getClusters ())
    EXPECT_TRUE (std::is_sorted (cluster.indices.begin (), cluster.indices.end ()));
  EXPECT_TRUE (std::is_sorted (reordered.getOutliers ().begin (), reordered.getOutliers ().end ()));
  EXPECT_TRUE (std::is_sorted (
      reordered.getCorrespondences ().begin (), reordered.getCorrespondences ().end (),
      [] (const pcl::Correspondence& a, const pcl::Correspondence& b) { return a.index_query < b.index_query; }));
  // getResult () is in beam order, its points named by getResultSourceIndices ().
  EXPECT_EQ (reordered.getResult ().source_cluster, ordered.getResult ().source_cluster);
  for (std::size_t k = 0; k < reordered.getResultSourceIndices ().size (); ++k)
    EXPECT_EQ (source_order[reordered.getResultSourceIndices ()[k]], ordered.getResultSourceIndices ()[k]);
}

TEST (JointCRFEstimator, SkipsPointsAtTheSensor)
{
  // Test pair 16 with (0, 0, 0) before every fifth point of both clouds (a driver's range
  // of 0 for a beam without a return, converted to x, y): the same estimate as without
  // them, and no cluster, outlier or correspondence names one.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  const auto source = toCloud (pair.source), target = toCloud (pair.target);
  const auto withOrigins = [] (const pcl::PointCloud<pcl::PointXYZ>& cloud, std::vector<int>& position) {
    auto out = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
    position.clear ();
    for (std::size_t i = 0; i < cloud.size (); ++i) {
      if (i % 5 == 0)
        out->push_back (pcl::PointXYZ (0.0f, 0.0f, 0.0f));
      position.push_back (static_cast<int> (out->size ()));
      out->push_back (cloud[i]);
    }
    return out;
  };
  std::vector<int> in_source, in_target;
  const auto padded_source = withOrigins (*source, in_source), padded_target = withOrigins (*target, in_target);
  const Eigen::Matrix4f odometry = toMatrix4<float> (pair.odometry.T_source_target);
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> plain, padded;
  for (auto* estimator : {&plain, &padded}) {
    estimator->setModel (shippedModel ());
    estimator->setOdometry (odometry, pair.odometry.covariance);
  }
  pcl::PointCloud<pcl::PointXYZ> aligned;
  plain.setInputSource (source);
  plain.setInputTarget (target);
  plain.align (aligned);
  padded.setInputSource (padded_source);
  padded.setInputTarget (padded_target);
  padded.align (aligned);
  ASSERT_TRUE (plain.hasConverged ());
  ASSERT_TRUE (padded.hasConverged ());
  EXPECT_EQ (padded.getFinalTransformation (), plain.getFinalTransformation ());
  ASSERT_EQ (padded.getCorrespondences ().size (), plain.getCorrespondences ().size ());
  for (std::size_t c = 0; c < plain.getCorrespondences ().size (); ++c) {
    const pcl::Correspondence& a = plain.getCorrespondences ()[c];
    const pcl::Correspondence& b = padded.getCorrespondences ()[c];
    EXPECT_EQ (b.index_query, in_source[static_cast<std::size_t> (a.index_query)]);
    EXPECT_EQ (b.index_match, in_target[static_cast<std::size_t> (a.index_match)]);
  }
  ASSERT_EQ (padded.getClusters ().size (), plain.getClusters ().size ());
  for (std::size_t l = 0; l < plain.getClusters ().size (); ++l) {
    std::vector<int> mapped;
    for (const int i : plain.getClusters ()[l].indices)
      mapped.push_back (in_source[static_cast<std::size_t> (i)]);
    EXPECT_EQ (padded.getClusters ()[l].indices, mapped) << "cluster " << l;
  }
  std::vector<int> outliers;
  for (const auto i : plain.getOutliers ())
    outliers.push_back (in_source[static_cast<std::size_t> (i)]);
  EXPECT_EQ (std::vector<int> (padded.getOutliers ().begin (), padded.getOutliers ().end ()), outliers);
}

TEST (JointCRFEstimator, ChainsAShuffledCloudInBeamOrder)
{
  // A cloud out of beam order: a kd-tree's or a voxel grid's, here a shuffle.
  expectChainedInBeamOrder (true);
}

TEST (JointCRFEstimator, ChainsAClockwiseCloudCounterClockwise)
{
  // A laser mounted upside down lists its beams clockwise: read backwards, as the model learned.
  expectChainedInBeamOrder (false);
}

TEST (JointCRFEstimator, EstimatorsInThreadsOfTheirOwnGiveTheAnswersOfOneThread)
{
  // A program may run an estimator per sensor or per robot in threads of their own: no
  // estimator shares mutable state with another (the one per-thread workspace is
  // thread_local). Three threads, each its own estimator, over the test split's pairs.
  const std::vector<ScanPair> pairs = loadDataset (kTestDir);
  const auto estimate = [&pairs] (std::size_t k, pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>& estimator) {
    const ScanPair& pair = pairs[k % pairs.size ()];
    estimator.setInputSource (toCloud (pair.source));
    estimator.setInputTarget (toCloud (pair.target));
    estimator.setOdometry (toMatrix4<float> (pair.odometry.T_source_target), pair.odometry.covariance);
    pcl::PointCloud<pcl::PointXYZ> aligned;
    estimator.align (aligned);
    return std::make_pair (estimator.getFinalTransformation (), estimator.getResult ().source_cluster);
  };
  std::vector<std::pair<Eigen::Matrix4f, std::vector<int>>> expected;
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> alone;
  alone.setModel (shippedModel ());
  for (std::size_t k = 0; k < pairs.size (); ++k)
    expected.push_back (estimate (k, alone));
  std::vector<int> mismatches (3, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < mismatches.size (); ++t)
    threads.emplace_back ([&, t] {
      pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
      estimator.setModel (shippedModel ());
      for (std::size_t k = 7 * t; k < 7 * t + pairs.size (); ++k)
        mismatches[t] += estimate (k, estimator) == expected[k % pairs.size ()] ? 0 : 1;
    });
  for (std::thread& thread : threads)
    thread.join ();
  EXPECT_EQ (mismatches, std::vector<int> (3, 0));
}

TEST (JointCRFEstimator, TurnsTheNormalsOfAPointNormalCloudWithItsPoints)
{
  // Any point type with x and y works (through the .hpp, as PCL's PCL_NO_PRECOMPILE);
  // the output's normals turn with its points, as pcl::IterativeClosestPoint turns them.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  pcl::PointCloud<pcl::PointNormal>::Ptr source (new pcl::PointCloud<pcl::PointNormal>);
  pcl::PointCloud<pcl::PointNormal>::Ptr target (new pcl::PointCloud<pcl::PointNormal>);
  for (const auto& [scan, cloud] : {std::make_pair (&pair.source, source), std::make_pair (&pair.target, target)})
    for (Eigen::Index i = 0; i < scan->cols (); ++i) {
      pcl::PointNormal p;
      p.x = static_cast<float> ((*scan) (0, i));
      p.y = static_cast<float> ((*scan) (1, i));
      p.z = 0.0f;
      p.normal_x = 1.0f;
      p.normal_y = p.normal_z = 0.0f;
      cloud->push_back (p);
    }
  pcl_crf::JointCRFEstimator<pcl::PointNormal, pcl::PointNormal> estimator;
  estimator.setModel (shippedModel ());
  estimator.setInputSource (source);
  estimator.setInputTarget (target);
  estimator.setOdometry (toMatrix4<float> (pair.odometry.T_source_target), pair.odometry.covariance);
  pcl::PointCloud<pcl::PointNormal> aligned;
  estimator.align (aligned);
  ASSERT_TRUE (estimator.hasConverged ());
  const Eigen::Matrix4f T = estimator.getFinalTransformation ();
  ASSERT_EQ (aligned.size (), source->size ());
  for (std::size_t i = 0; i < aligned.size (); i += 50) {
    EXPECT_NEAR (aligned[i].normal_x, T (0, 0), 1e-6) << i;
    EXPECT_NEAR (aligned[i].normal_y, T (1, 0), 1e-6) << i;
    EXPECT_NEAR (aligned[i].x, (T * (*source)[i].getVector4fMap ()).x (), 1e-5) << i;
  }
  // The same estimate as through PointXYZ.
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> xyz;
  xyz.setModel (shippedModel ());
  pcl::PointCloud<pcl::PointXYZ> xyz_aligned;
  xyz.setInputSource (toCloud (pair.source));
  alignWithPairOdometry (xyz, pair, xyz_aligned);
  EXPECT_EQ (xyz.getFinalTransformation (), T);
}

TEST (JointCRFEstimator, AnEstimateThatFailsLeavesTheOdometrysMotion)
{
  // A setting no estimate can run with gives a PCL_ERROR, no result, and the motion the
  // estimator would have started from: the odometry's (it replaces align ()'s guess).
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  estimator.setModel (shippedModel ());
  estimator.setMaxMissingReturns (-5);
  estimator.setInputSource (toCloud (pair.source));
  pcl::PointCloud<pcl::PointXYZ> aligned;
  const Eigen::Matrix4f odometry = alignWithPairOdometry (estimator, pair, aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  EXPECT_TRUE (estimator.getClusters ().empty ());
  EXPECT_TRUE (estimator.getFinalTransformation ().isApprox (odometry.inverse (), 1e-6));
  EXPECT_NEAR (aligned[0].x, (odometry.inverse () * toCloud (pair.source)->front ().getVector4fMap ()).x (), 1e-5);
  // An odometry that is no rigid motion is refused when it is set, and the one before stays.
  Eigen::Matrix4f broken = odometry;
  broken (0, 3) = std::numeric_limits<float>::quiet_NaN ();
  estimator.setOdometry (broken, pair.odometry.covariance);
  estimator.align (aligned);
  EXPECT_TRUE (estimator.getFinalTransformation ().isApprox (odometry.inverse (), 1e-6));
  // Forgotten, align ()'s guess takes its place.
  estimator.clearOdometry ();
  const Eigen::Matrix4f guess = toMatrix4<float> (makeRigid2d (-1.0, 0.5, 0.1));
  estimator.align (aligned, guess);
  EXPECT_TRUE (estimator.getFinalTransformation ().isApprox (guess, 1e-6));
}

/** Aligns \a pair's scans at float precision with \a estimator (the shipped model, the
 *  pair's odometry), the source cloud holding a NaN point at index 7; \a direct receives
 *  estimateJoint on what the adapter sees (the valid points, the float odometry).
 *  \return whether the alignment converged. */
bool
alignWithANaNAt7 (const ScanPair& pair, pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ>& estimator,
                  joint::JointResult& direct)
{
  const Eigen::Matrix2Xd source = pair.source.cast<float> ().cast<double> ();
  const Eigen::Matrix2Xd target = pair.target.cast<float> ().cast<double> ();
  auto source_cloud = toCloud (source);
  source_cloud->insert (source_cloud->begin () + 7,
                        pcl::PointXYZ (std::numeric_limits<float>::quiet_NaN (), 0.0f, 0.0f));
  if (!estimator.loadModel (kModelPath))
    return false;
  estimator.setInputSource (source_cloud);
  estimator.setInputTarget (toCloud (target));
  const Eigen::Matrix4f odometry = toMatrix4<float> (pair.odometry.T_source_target);
  estimator.setOdometry (odometry, pair.odometry.covariance);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  estimator.align (aligned);
  Odometry as_given = pair.odometry;  // what the adapter sees: the float matrix
  as_given.T_source_target = toRigid2d (odometry);
  direct = joint::estimateJoint (source, target, as_given, shippedModel ());
  return estimator.hasConverged ();
}

TEST (JointCRFEstimator, GivesAFinerCloudTheThinnedEstimateWithCloudIndices)
{
  // A 1081-beam pair over 270° with a NaN point: the adapter's clusters and
  // correspondences are estimateJoint's on the valid points (thinned and lifted),
  // mapped to cloud indices.
  const ScanPair pair = test::hokuyoPair (21, 0);
  ASSERT_LT (thinToSpacing (pair.source, shippedModel ().matcher.parameters.training_beam_spacing).kept.size (),
             static_cast<std::size_t> (pair.source.cols ()));  // it is thinned
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  joint::JointResult direct;
  ASSERT_TRUE (alignWithANaNAt7 (pair, estimator, direct));
  const auto cloudIndex = [] (int k) { return k < 7 ? k : k + 1; };  // the NaN point sits at 7
  pcl::Correspondences expected;
  for (std::size_t k = 0; k < direct.source_match.size (); ++k)
    if (direct.source_match[k] != kNoMatch)
      expected.emplace_back (cloudIndex (static_cast<int> (k)), direct.source_match[k], 0.0f);
  const pcl::Correspondences& found = estimator.getCorrespondences ();
  ASSERT_EQ (found.size (), expected.size ());
  for (std::size_t c = 0; c < found.size (); ++c) {
    EXPECT_EQ (found[c].index_query, expected[c].index_query);
    EXPECT_EQ (found[c].index_match, expected[c].index_match);
  }
  const auto& clusters = estimator.getClusters ();
  ASSERT_EQ (clusters.size (), direct.cluster_motions.size ());
  for (std::size_t l = 0; l < clusters.size (); ++l)
    EXPECT_EQ (clusters[l].indices.size (), static_cast<std::size_t> (direct.cluster_sizes[l]));
  EXPECT_EQ (estimator.getOutliers ().size (), direct.outliers.size ());
}

TEST (JointCRFEstimator, ReportsThePointsThatMovedAwayWithCloudIndices)
{
  // Simulator seed 3003, pair 23 (see JointEstimation.ACarThatLeftTheTargetsViewIsNot…),
  // with a NaN point at 7: the 40 points of the car that left, at their cloud indices.
  const ScanPair pair = freshPairOfSeed3003 (23);
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  joint::JointResult direct;
  ASSERT_TRUE (alignWithANaNAt7 (pair, estimator, direct));
  ASSERT_EQ (direct.moved_away.size (), 40u);
  pcl::Indices expected;
  for (const int i : direct.moved_away)
    expected.push_back (i < 7 ? i : i + 1);
  EXPECT_EQ (estimator.getMovedAway (), expected);
  for (const auto index : estimator.getMovedAway ())
    EXPECT_NE (std::find (estimator.getOutliers ().begin (), estimator.getOutliers ().end (), index),
               estimator.getOutliers ().end ());
}

TEST (JointCRFEstimator, ReportsBadInputWithoutCrashing)
{
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  EXPECT_FALSE (estimator.loadModel ("/nonexistent/joint.model"));
  pcl::PointCloud<pcl::PointXYZ> aligned;
  estimator.align (aligned);  // no clouds: PCL reports it
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setInputSource (pcl::PointCloud<pcl::PointXYZ>::Ptr (new pcl::PointCloud<pcl::PointXYZ>));
  estimator.setInputTarget (toCloud (Eigen::Matrix2Xd::Random (2, 10)));
  estimator.align (aligned);  // untrained model and empty source
  EXPECT_FALSE (estimator.hasConverged ());
  EXPECT_TRUE (estimator.getClusters ().empty ());
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  estimator.setModel (shippedModel ());
  estimator.setInputSource (toCloud (pair.source));
  estimator.setInputTarget (toCloud (pair.target));
  estimator.setScanInterval (std::numeric_limits<double>::quiet_NaN ());
  estimator.align (aligned);  // a NaN interval
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setScanInterval (0.3);
  EXPECT_EQ (estimator.getMaxMissingReturns (), 10);
  estimator.setMaxMissingReturns (-2);
  estimator.align (aligned);  // a nonsense bound on dropped returns
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setMaxMissingReturns (10);
  Eigen::Matrix4f nan_guess = Eigen::Matrix4f::Identity ();
  nan_guess (1, 3) = std::numeric_limits<float>::quiet_NaN ();
  estimator.align (aligned, nan_guess);  // a NaN guess, reported
  EXPECT_FALSE (estimator.hasConverged ());
  // A target that nothing of the source overlaps: no point is associated, and the guess
  // came back as the "estimate" with hasConverged () true.
  Eigen::Matrix2Xd far = pair.target;
  far.row (0).array () += 500.0;
  estimator.setInputTarget (toCloud (far));
  Eigen::Matrix4f shifted = Eigen::Matrix4f::Identity ();
  shifted (0, 3) = 1000.0f;
  estimator.align (aligned, shifted);
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setInputTarget (toCloud (pair.target.leftCols (1)));  // one target point
  estimator.align (aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  // Coordinates near 1e37 made PCL's kd-tree of the target abort (a FLANN assertion);
  // beyond 1e18 m squared distances overflow PCL's floats.
  estimator.setInputTarget (toCloud (pair.target * 1e37));
  estimator.align (aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setInputTarget (toCloud (pair.target));
  estimator.setInputSource (toCloud (pair.source * 1e20));
  estimator.align (aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  EXPECT_TRUE (estimator.getCorrespondences ().empty ());
  // Every source point is one node: an index given twice was estimated twice.
  estimator.setInputSource (toCloud (pair.source));
  pcl::IndicesPtr twice (new pcl::Indices);
  for (int i = 0; i < static_cast<int> (pair.source.cols ()); ++i)
    twice->insert (twice->end (), {i, i});
  estimator.setIndices (twice);
  estimator.align (aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  estimator.setIndices (pcl::IndicesPtr ());
  estimator.setInputSource (toCloud (Eigen::Matrix2Xd::Zero (2, 20)));  // every point at the sensor: no return
  estimator.align (aligned);
  EXPECT_FALSE (estimator.hasConverged ());
  EXPECT_TRUE (estimator.getClusters ().empty ());
  estimator.setInputSource (toCloud (pair.source));
  alignWithPairOdometry (estimator, pair, aligned);
  EXPECT_TRUE (estimator.hasConverged ());
}

TEST (JointCRFEstimator, EstimatesOnlyTheIndexedSourcePoints)
{
  // setIndices restricts the source to those points, as in every PCL registration:
  // the result is estimateJoint's on them, reported with cloud indices.
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  auto source = toCloud (pair.source);
  pcl::IndicesPtr indices (new pcl::Indices);
  for (int i = 20; i < static_cast<int> (source->size ()) - 20; ++i)  // both ends cut off
    indices->push_back (i);
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  estimator.setModel (shippedModel ());
  estimator.setInputSource (source);
  estimator.setIndices (indices);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  const Eigen::Matrix4f odometry = alignWithPairOdometry (estimator, pair, aligned);
  ASSERT_TRUE (estimator.hasConverged ());
  EXPECT_EQ (aligned.size (), indices->size ());
  const Eigen::Matrix4f T = estimator.getFinalTransformation ();
  const Eigen::Vector4f moved = T * (*source)[20].getVector4fMap ();
  EXPECT_NEAR (aligned[0].x, moved.x (), 1e-5);
  EXPECT_NEAR (aligned[0].y, moved.y (), 1e-5);

  Odometry as_given = pair.odometry;  // what the adapter sees: float points and odometry
  as_given.T_source_target = toRigid2d (odometry);
  const Eigen::Matrix2Xd cut = pair.source.middleCols (20, static_cast<Eigen::Index> (indices->size ()));
  const joint::JointResult direct = joint::estimateJoint (cut.cast<float> ().cast<double> (),
                                                          pair.target.cast<float> ().cast<double> (), as_given,
                                                          shippedModel ());
  const pcl::Correspondences& found = estimator.getCorrespondences ();
  std::size_t k = 0;
  for (std::size_t i = 0; i < direct.source_match.size (); ++i) {
    if (direct.source_match[i] == kNoMatch)
      continue;
    ASSERT_LT (k, found.size ());
    EXPECT_EQ (found[k].index_query, static_cast<int> (i) + 20);
    EXPECT_EQ (found[k].index_match, direct.source_match[i]);
    ++k;
  }
  EXPECT_EQ (k, found.size ());
  const auto& clusters = estimator.getClusters ();
  ASSERT_EQ (clusters.size (), direct.cluster_motions.size ());
  std::size_t total = estimator.getOutliers ().size ();
  for (std::size_t l = 0; l < clusters.size (); ++l) {
    EXPECT_EQ (clusters[l].indices.size (), static_cast<std::size_t> (direct.cluster_sizes[l]));
    total += clusters[l].indices.size ();
    for (int index : clusters[l].indices) {
      EXPECT_GE (index, 20);
      EXPECT_LT (index, static_cast<int> (source->size ()) - 20);
    }
  }
  EXPECT_EQ (total, indices->size ());
}

TEST (JointCRFEstimator, ReportsSourceIndicesOutsideTheCloudWithoutCrashing)
{
  // PCL's Registration::align copies the indexed points before any estimator runs:
  // an index past the cloud used to read past it (a crash).
  const ScanPair pair = loadScanPair (kTestDir + "pair_0016");
  auto source = toCloud (pair.source);
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> estimator;
  estimator.setModel (shippedModel ());
  estimator.setInputSource (source);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  alignWithPairOdometry (estimator, pair, aligned);
  ASSERT_TRUE (estimator.hasConverged ());
  for (const int bad : {static_cast<int> (source->size ()), 1000000000, -1}) {
    pcl::IndicesPtr indices (new pcl::Indices{0, 1, 2, bad, 4});
    estimator.setIndices (indices);
    estimator.align (aligned);
    EXPECT_FALSE (estimator.hasConverged ()) << bad;
    EXPECT_TRUE (estimator.getClusters ().empty ()) << bad;
    EXPECT_TRUE (estimator.getCorrespondences ().empty ()) << bad;
  }
  pcl::IndicesPtr all (new pcl::Indices (source->size ()));
  for (std::size_t i = 0; i < all->size (); ++i)
    (*all)[i] = static_cast<int> (i);
  estimator.setIndices (all);  // every point again
  estimator.align (aligned);
  EXPECT_TRUE (estimator.hasConverged ());
  EXPECT_EQ (aligned.size (), source->size ());
}

}  // namespace
