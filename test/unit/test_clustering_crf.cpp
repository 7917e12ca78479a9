// CRF-Clustering end to end on hand-built scans: known motions, any initial
// over-segmentation, learning, and the paper's Fig. 4 case against the baselines.

#include <pcl_crf/clustering/clustering_learning.h>
#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/clustering/motion_kmeans.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/crf/chain_features.h>
#include <pcl_crf/crf/pseudo_likelihood.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <limits>
#include <random>
#include <string>

namespace {

using namespace pcl_crf;
using namespace pcl_crf::clustering;

/** A straight piece of an object's outline (world frame at the source time). */
struct Wall
{
  Eigen::Vector2d a, b;
  int object;
};

/** A street: the world (object 0) is two façades and a back wall; object 1 a box. */
std::vector<Wall>
street (const Eigen::Vector2d& box_min, const Eigen::Vector2d& box_max)
{
  return {{{-2, -4}, {26, -4}, 0}, {{26, -4}, {26, 7}, 0}, {{26, 7}, {-2, 7}, 0},
          {{box_min.x (), box_min.y ()}, {box_max.x (), box_min.y ()}, 1},
          {{box_min.x (), box_min.y ()}, {box_min.x (), box_max.y ()}, 1},
          {{box_min.x (), box_max.y ()}, {box_max.x (), box_max.y ()}, 1}};
}

/** Nearest hit of every beam (361 over 180°, 30 m) from the sensor at \a pose (world),
 *  walls of object o moved by motions[o]; points in the sensor frame, beam order. */
Eigen::Matrix2Xd
castScan (const std::vector<Wall>& walls, const std::vector<Rigid2d>& motions, const Rigid2d& pose,
          std::vector<int>& objects)
{
  std::vector<Eigen::Vector2d> points;
  objects.clear ();
  for (int beam = 0; beam < 361; ++beam)
  {
    const double angle = -M_PI / 2 + beam * M_PI / 360;
    const Eigen::Vector2d o = pose.translation ();
    const Eigen::Vector2d d = pose.linear () * Eigen::Vector2d (std::cos (angle), std::sin (angle));
    double best = 30.0;
    int hit = -1;
    for (const Wall& w : walls)
    {
      const Eigen::Vector2d a = motions[w.object] * w.a, e = motions[w.object] * w.b - a;
      Eigen::Matrix2d m;
      m << d, -e;
      if (std::abs (m.determinant ()) < 1e-12)
        continue;
      const Eigen::Vector2d tu = m.inverse () * (a - o);
      if (tu (0) > 1e-9 && tu (0) < best && tu (1) >= 0.0 && tu (1) <= 1.0)
        best = tu (0), hit = w.object;
    }
    if (hit >= 0)
    {
      points.push_back (pose.inverse () * Eigen::Vector2d (o + best * d));
      objects.push_back (hit);
    }
  }
  Eigen::Matrix2Xd scan (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t i = 0; i < points.size (); ++i)
    scan.col (i) = points[i];
  return scan;
}

/** A scan pair of \a walls: the ego drives \a ego, object 1 moves by \a box_motion (world
 *  frame). \a exact: the target holds exactly the moved source points (+ Gaussian noise
 *  of σ 0.3 mm), else a second ray-cast scan with nearest-point true associations. */
ScanPair
makePair (const std::vector<Wall>& walls, const Rigid2d& ego, const Rigid2d& box_motion, bool exact)
{
  ScanPair pair;
  pair.sensor = {361, -M_PI / 2, M_PI / 360, 30.0};
  const Rigid2d identity = Rigid2d::Identity ();
  pair.source = castScan (walls, {identity, identity}, identity, pair.source_object);
  const Rigid2d world_motion = ego.inverse (), box = ego.inverse () * box_motion;  // T_target_source
  pair.objects = {{0, true, world_motion, "world"}, {1, false, box, "car"}};
  pair.odometry.T_source_target = ego;
  pair.odometry.covariance = Eigen::Vector3d (1e-4, 1e-4, 1e-6).asDiagonal ();
  std::mt19937 rng (7);
  std::normal_distribution<double> noise (0.0, 0.0003);
  if (exact)
  {
    pair.target.resize (2, pair.source.cols ());
    for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    {
      pair.target.col (i) = (pair.source_object[i] == 0 ? world_motion : box) * Eigen::Vector2d (pair.source.col (i));
      pair.target.col (i) += Eigen::Vector2d (noise (rng), noise (rng));
      pair.source_match.push_back (static_cast<int> (i));
    }
    pair.target_object = pair.source_object;
    return pair;
  }
  pair.target = castScan (walls, {identity, box_motion}, ego, pair.target_object);
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
  {
    const int o = pair.source_object[i];
    const Eigen::Vector2d q = (o == 0 ? world_motion : box) * Eigen::Vector2d (pair.source.col (i));
    int best = kNoMatch;
    double tolerance = 2 * q.norm () * M_PI / 360 + 0.02;
    for (Eigen::Index j = 0; j < pair.target.cols (); ++j)
      if (pair.target_object[j] == o && (pair.target.col (j) - q).norm () < tolerance)
        tolerance = (pair.target.col (j) - q).norm (), best = static_cast<int> (j);
    pair.source_match.push_back (best);
  }
  return pair;
}

/** Weights of the order of those learned on the default training set. */
Eigen::VectorXd
typicalWeights ()
{
  Eigen::VectorXd w (kWeightCount);
  w << 0.0, -3.3, 0.0, 4.5, -0.7;
  return w;
}

const Rigid2d kEgo = makeRigid2d (2.0, 0.1, 0.03);
const Rigid2d kCarMotion = makeRigid2d (1.5, -0.4, 0.1);

/** Errors of an estimated motion: (translation [m], rotation [rad]) of T_est⁻¹ T_true. */
std::pair<double, double>
motionError (const Rigid2d& estimate, const Rigid2d& truth)
{
  const Rigid2d e = estimate.inverse () * truth;
  return {e.translation ().norm (), std::abs (rotationAngle (e))};
}

/** Fraction of object-1 points whose cluster holds mostly object-1 points. */
double
movingObjectRecall (const std::vector<int>& clusters, const std::vector<int>& objects)
{
  std::map<int, std::pair<int, int>> counts;  // cluster -> (object-1 points, points)
  int moving = 0;
  for (std::size_t i = 0; i < clusters.size (); ++i)
  {
    counts[clusters[i]].first += objects[i] == 1;
    counts[clusters[i]].second += 1;
    moving += objects[i] == 1;
  }
  int found = 0;
  for (const auto& [cluster, count] : counts)
    if (cluster >= 0 && 2 * count.first > count.second)
      found += count.first;
  return static_cast<double> (found) / moving;
}

TEST (CrfClustering, RecoversTwoRigidGroupsWithKnownMotions)
{
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, true);
  const ScanClustering result = clusterScan (pair.source, pair.target, pair.source_match, typicalWeights (), {},
                                             &pair.odometry, UnpairedLabelling::Outlier);
  ASSERT_EQ (result.motions.size (), 2u);
  EXPECT_TRUE (result.converged);
  EXPECT_LE (result.iterations, 7);
  ASSERT_EQ (result.static_cluster, 0);  // the world is the larger cluster
  for (int k = 0; k < 2; ++k)
  {
    const auto [translation, rotation] = motionError (result.motions[k], pair.objects[k].T_target_source);
    EXPECT_LT (translation, 1e-3) << "cluster " << k;
    EXPECT_LT (rotation, 1e-3) << "cluster " << k;
  }
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i)
    ASSERT_EQ (result.source_cluster[i], pair.source_object[i]) << "point " << i;
  // Marginals are confident and normalised.
  EXPECT_NEAR (result.marginals.colwise ().sum ().minCoeff (), 1.0, 1e-9);
  EXPECT_GT (result.marginals.colwise ().maxCoeff ().minCoeff (), 0.99);
}

TEST (CrfClustering, DirectPotentialsEqualWeightedFeatures)
{
  // Inference builds w · f directly; learning uses the feature table: they must agree.
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, false);
  const PointPairs pairs = makePointPairs (pair.source, pair.target, pair.source_match);
  const std::vector<Rigid2d> motions = {pair.objects[0].T_target_source, pair.objects[1].T_target_source,
                                        makeRigid2d (0.3, -0.2, 0.4)};
  CandidateStates states = allStates (pairs.size (), 3);
  for (std::size_t i = 0; i < states.size (); i += 3)
    states[i] = {static_cast<int> (i % 3)};  // some nodes with a single candidate
  const Eigen::VectorXd w = typicalWeights () + Eigen::VectorXd::LinSpaced (kWeightCount, 0.1, 0.6);
  const Eigen::MatrixXd residuals = squaredResiduals (pairs, motions);
  const crf::ChainPotentials from_features =
      crf::potentials (chainFeatures (pairs, motions, states, {}, &residuals), w);
  const crf::ChainPotentials direct =
      chainPotentials (pairs, motions, states, localLogPotentials (pairs, residuals, w, {}), w);
  ASSERT_EQ (direct.size (), from_features.size ());
  for (std::size_t i = 0; i < direct.size (); ++i)
    ASSERT_TRUE (direct.unary[i].isApprox (from_features.unary[i], 1e-12)) << "node " << i;
  for (std::size_t i = 0; i + 1 < direct.size (); ++i)
    ASSERT_LT ((direct.pairwise[i] - from_features.pairwise[i]).cwiseAbs ().maxCoeff (), 1e-9) << "edge " << i;
}

TEST (CrfClustering, FindsTheNumberOfClustersWhateverTheOverSegmentation)
{
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, true);
  const PointPairs pairs = makePointPairs (pair.source, pair.target, pair.source_match);
  for (const double gap : {0.1, 0.5, 2.0})
    for (const int cap : {3, 8, 20, 50, 0})
    {
      CrfClusteringParameters parameters;
      parameters.segment_break_distance = gap;
      parameters.max_segment_points = cap;
      const CrfClusteringResult result = clusterPointPairs (pairs, typicalWeights (), parameters, &pair.odometry);
      EXPECT_EQ (result.motions.size (), 2u) << "gap " << gap << " cap " << cap << ", "
                                             << result.initial_clusters << " initial clusters";
      EXPECT_GE (result.initial_clusters, cap == 3 ? 50 : 3);
    }
}

TEST (CrfClustering, LearnsWeightsThatSeparateMotions)
{
  // Train on three pairs with other motions, cluster a fourth.
  std::vector<crf::LabelledChain> chains;
  const Rigid2d motions[3] = {makeRigid2d (0.8, 0.5, -0.05), makeRigid2d (-1.5, 0.0, 0.0),
                              makeRigid2d (0.4, -0.4, 0.2)};
  for (int k = 0; k < 3; ++k)
  {
    const ScanPair pair =
        makePair (street ({6.0 + 2 * k, -1}, {10.5 + 2 * k, 0.8}), makeRigid2d (2.5, 0, 0), motions[k], false);
    const PointPairs pairs = makePointPairs (pair.source, pair.target, pair.source_match);
    std::vector<int> labels;
    for (const int i : pairs.source_index)
      labels.push_back (pair.source_object[i]);
    chains.push_back (makeTrainingChain (pairs, labels));
  }
  const crf::LbfgsResult fit = learnWeights (chains);
  EXPECT_TRUE (fit.converged) << fit.status;
  EXPECT_LT (fit.x (0) + fit.x (1), -1.0);  // a residual makes its cluster less likely
  EXPECT_GT (fit.x (3), 0.0);               // close neighbours share their cluster
  Eigen::VectorXd gradient;
  const crf::PseudoLikelihood objective (chains, LearningOptions ().prior_sigma);
  const double at_zero = objective.objectiveAndGradient (Eigen::VectorXd::Zero (kWeightCount), gradient);
  EXPECT_LT (fit.value, 0.05 * at_zero);

  const ScanPair test = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, false);
  const ScanClustering result = clusterScan (test.source, test.target, test.source_match, fit.x, {}, &test.odometry,
                                             UnpairedLabelling::Outlier);
  // The world and the car are the two largest clusters. (Three points at the far
  // corner of the back wall, whose nearest-point associations jump the corner, may
  // form a cluster of their own: 2 or 3 clusters.)
  ASSERT_GE (result.motions.size (), 2u);
  EXPECT_LE (result.motions.size (), 3u);
  EXPECT_EQ (result.static_cluster, 0);
  EXPECT_LT (motionError (result.motions[0], test.objects[0].T_target_source).first, 0.05);
  EXPECT_LT (motionError (result.motions[1], test.objects[1].T_target_source).first, 0.05);
  EXPECT_GE (result.sizes[0] + result.sizes[1], 0.98 * static_cast<double> (result.pairs.size ()));
  EXPECT_GT (movingObjectRecall (result.source_cluster, test.source_object), 0.95);
}

TEST (CrfClustering, FindsACarMovingAlongItsOwnOutlineThatConsistencyMisses)
{
  // Paper Fig. 4: a 24 m vehicle alongside the ego (its rear behind the sensor, its
  // front facing away) drives 2 m along its own near side while the ego drives 1 m;
  // the target scan sees the same outline, so the vehicle occupies no free space.
  const ScanPair pair =
      makePair (street ({-10, 2}, {14, 4.5}), makeRigid2d (1.0, 0, 0), makeRigid2d (2.0, 0, 0), false);
  const std::vector<int> cbd = detectDynamicSegments (pair.source, pair.target, pair.sensor,
                                                      pair.odometry.T_source_target.inverse (), {},
                                                      &pair.odometry.covariance);
  EXPECT_EQ (*std::max_element (cbd.begin (), cbd.end ()), 0) << "CBD should see no dynamic segment";
  EXPECT_EQ (movingObjectRecall (cbd, pair.source_object), 0.0);

  const ScanClustering crf = clusterScan (pair.source, pair.target, pair.source_match, typicalWeights (), {},
                                          &pair.odometry, UnpairedLabelling::NearestSegmentNeighbour);
  // The world, the vehicle, and at most one more cluster: the vehicle's far end is seen
  // at a grazing angle (0.7 m between points) where the nearest-point associations
  // are 0.2 m off, and two of its points may keep a cluster of their own.
  ASSERT_GE (crf.motions.size (), 2u);
  EXPECT_LE (crf.motions.size (), 3u);
  EXPECT_EQ (crf.static_cluster, 0);
  EXPECT_GT (movingObjectRecall (crf.source_cluster, pair.source_object), 0.95);
  EXPECT_LT (motionError (crf.motions[0], pair.objects[0].T_target_source).first, 0.02);
  EXPECT_LT (motionError (crf.motions[1], pair.objects[1].T_target_source).first, 0.02);
}

/** \a pair with Gaussian range noise of \a sigma on every point of both scans. */
ScanPair
withRangeNoise (ScanPair pair, double sigma, unsigned seed)
{
  std::mt19937 rng (seed);
  std::normal_distribution<double> noise (0.0, sigma);
  for (Eigen::Matrix2Xd* scan : {&pair.source, &pair.target})
    for (Eigen::Index i = 0; i < scan->cols (); ++i)
      scan->col (i) *= 1.0 + noise (rng) / scan->col (i).norm ();
  return pair;
}

TEST (CrfClustering, KeepsANearbySmallCarWhoseFitTheWallsWouldPullToTheirMotion)
{
  // Like the real 1/10-scale cars of the overtakes bag: a small box 0.4–0.6 m from the
  // sensor drives 5 cm ahead of the ego, the walls are 4–26 m away, 1 cm range noise.
  // There the motions differ by several beam spacings on the box and by less than one
  // on the walls, so every wall pair keeps a little of the box's marginal. Refitted to
  // the marginals of every pair (the paper's Eq. (3)), the box's motion is pulled
  // towards the walls' until the N_eff test merges it; refitted to its own pairs it stays.
  const Eigen::VectorXd weights = (Eigen::VectorXd (kWeightCount) << 0.11, -1.12, 1.98, 3.72, -0.76).finished ();
  const Rigid2d ego = makeRigid2d (0.065, 0.0, -0.03);
  const Rigid2d car = makeRigid2d (0.115, 0.0, -0.03);
  for (const auto& [box_min, box_max] : {std::pair<Eigen::Vector2d, Eigen::Vector2d> ({0.1, 0.4}, {0.25, 0.5}),
                                          std::pair<Eigen::Vector2d, Eigen::Vector2d> ({0.1, 0.6}, {0.4, 0.7})})
  {
    const ScanPair pair = withRangeNoise (makePair (street (box_min, box_max), ego, car, false), 0.01, 1);
    for (const MotionFit fit : {MotionFit::OwnPoints, MotionFit::Marginals})
    {
      CrfClusteringParameters parameters;
      parameters.motion_fit = fit;
      const ScanClustering result = clusterScan (pair.source, pair.target, pair.source_match, weights, parameters,
                                                 &pair.odometry, UnpairedLabelling::Outlier);
      const double recall = movingObjectRecall (result.source_cluster, pair.source_object);
      if (fit == MotionFit::Marginals)
      {
        EXPECT_EQ (result.motions.size (), 1u) << "box at y " << box_min.y ();
        EXPECT_EQ (recall, 0.0) << "box at y " << box_min.y ();
        continue;
      }
      ASSERT_EQ (result.motions.size (), 2u) << "box at y " << box_min.y ();
      EXPECT_EQ (recall, 1.0) << "box at y " << box_min.y ();
      // Both motions from 1 cm noise and nearest-point associations: the box's within 2 cm
      // of its 5 cm step, the walls' (up to 26 m away, where rotation counts) within 4 cm.
      EXPECT_LT (motionError (result.motions[1], pair.objects[1].T_target_source).first, 0.02);
      EXPECT_LT (motionError (result.motions[0], pair.objects[0].T_target_source).first, 0.04);
    }
  }
}

TEST (ConsistencyDetection, FindsACarThatLeftItsPlace)
{
  // The same street, a car driving 3 m towards the back wall: its old place is free.
  const ScanPair pair =
      makePair (street ({8, 0}, {12.5, 1.8}), makeRigid2d (1.0, 0, 0), makeRigid2d (3.0, 0, 0), false);
  const std::vector<int> cbd = detectDynamicSegments (pair.source, pair.target, pair.sensor,
                                                      pair.odometry.T_source_target.inverse ());
  EXPECT_GT (movingObjectRecall (cbd, pair.source_object), 0.95);
  int world_flagged = 0;
  for (std::size_t i = 0; i < cbd.size (); ++i)
    world_flagged += pair.source_object[i] == 0 && cbd[i] != 0;
  EXPECT_EQ (world_flagged, 0);
}

TEST (ConsistencyDetection, TheFirstBeamsAngleIsReadWithinOneTurn)
{
  // angle_min and angle_min ± 2π name the same laser: the same segments are dynamic.
  const ScanPair pair =
      makePair (street ({8, 0}, {12.5, 1.8}), makeRigid2d (1.0, 0, 0), makeRigid2d (3.0, 0, 0), false);
  const Rigid2d T_target_source = pair.odometry.T_source_target.inverse ();
  const std::vector<int> cbd = detectDynamicSegments (pair.source, pair.target, pair.sensor, T_target_source);
  ASSERT_GT (movingObjectRecall (cbd, pair.source_object), 0.95);
  for (const double turns : {-2.0, -1.0, 1.0, 3.0}) {
    SensorInfo sensor = pair.sensor;
    sensor.angle_min += turns * 2.0 * M_PI;
    EXPECT_EQ (detectDynamicSegments (pair.source, pair.target, sensor, T_target_source), cbd) << turns << " turns";
  }
}

TEST (KMeansBaseline, RecoversTwoMotionsAndSplitsAStaticWorld)
{
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, true);
  const PointPairs pairs = makePointPairs (pair.source, pair.target, pair.source_match);
  MotionKMeansParameters parameters;
  parameters.cluster_count = 2;
  const MotionKMeansResult two = clusterKMeans (pairs, parameters);
  EXPECT_TRUE (two.converged);
  ASSERT_EQ (two.motions.size (), 2u);
  EXPECT_LT (motionError (two.motions[0], pair.objects[0].T_target_source).first, 1e-3);
  EXPECT_LT (motionError (two.motions[1], pair.objects[1].T_target_source).first, 1e-3);
  // k too large: K-Means has no way to drop the extra cluster of the same motion.
  parameters.cluster_count = 4;
  EXPECT_GE (clusterKMeans (pairs, parameters).motions.size (), 3u);
  parameters.cluster_count = 0;
  EXPECT_THROW (clusterKMeans (pairs, parameters), std::invalid_argument);
}

TEST (PointPairsCheck, PairsBuiltByHandWithMissingPartsAreRejected)
{
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, true);
  const PointPairs pairs = makePointPairs (pair.source, pair.target, pair.source_match);
  EXPECT_EQ (pointPairsProblem (pairs), "");
  const auto n = std::to_string (pairs.size ());
  PointPairs no_target = pairs;  // these once crashed K-Means and CRF-Clustering
  no_target.target.resize (2, 0);
  EXPECT_EQ (pointPairsProblem (no_target),
             n + " source points, 0 target points, " + n + " spacings and " + n + " source indices: one of each per pair");
  EXPECT_THROW (clusterKMeans (no_target), std::invalid_argument);
  EXPECT_THROW (clusterPointPairs (no_target, typicalWeights ()), std::invalid_argument);
  PointPairs no_spacing = pairs;
  no_spacing.spacing.resize (0);
  EXPECT_THROW (clusterPointPairs (no_spacing, typicalWeights ()), std::invalid_argument);
  EXPECT_THROW (makeTrainingChain (no_spacing, std::vector<int> (pairs.size (), 0)), std::invalid_argument);
  PointPairs nan = pairs;
  nan.target (1, 0) = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_EQ (pointPairsProblem (nan), "the pairs hold NaN or infinite points");
  EXPECT_THROW (clusterKMeans (nan), std::invalid_argument);
}

TEST (ClusteringLearning, ChainsWithoutAnEdgeCannotTeachThePairwiseWeights)
{
  // Once 2 weights of the 5, refused only when used.
  const ScanPair pair = makePair (street ({8, 0}, {12.5, 1.8}), kEgo, kCarMotion, true);
  std::vector<int> one_match (pair.source_match.size (), kNoMatch);
  one_match[10] = pair.source_match[10];
  ASSERT_NE (one_match[10], kNoMatch);
  const PointPairs one = makePointPairs (pair.source, pair.target, one_match);
  const std::vector<crf::LabelledChain> chains{makeTrainingChain (one, {0})};
  EXPECT_THROW (learnWeights (chains), std::invalid_argument);
  EXPECT_FALSE (crf::hasAnEdge (chains));
}

TEST (CrfClustering, ALongScanStartsFromABoundedNumberOfClusters)
{
  // 10 000 pairs on a 10 m circle, one static world: 20-pair segments made 500 initial
  // clusters, and every round costs clusters × pairs (100 000 pairs took minutes; with
  // the bound 2.3 s).
  const int n = 10000;
  Eigen::Matrix2Xd source (2, n);
  for (int i = 0; i < n; ++i)
    source.col (i) << 10.0 * std::cos (2.0 * M_PI * i / n), 10.0 * std::sin (2.0 * M_PI * i / n);
  std::vector<int> match (n);
  std::iota (match.begin (), match.end (), 0);
  const Rigid2d ego = makeRigid2d (0.1, 0.0, 0.01);
  const Eigen::Matrix2Xd target = (ego.linear () * source).colwise () + ego.translation ();
  const PointPairs pairs = makePointPairs (source, target, match);
  CrfClusteringParameters parameters;
  const CrfClusteringResult result = clusterPointPairs (pairs, typicalWeights (), parameters);
  EXPECT_LE (result.initial_clusters, 256);  // ⌈10 000 / 256⌉ = 40 pairs each
  EXPECT_GE (result.initial_clusters, 250);
  ASSERT_EQ (result.motions.size (), 1u);
  EXPECT_LT (motionError (result.motions[0], ego).first, 1e-6);
  parameters.max_initial_clusters = 0;
  EXPECT_THROW (clusterPointPairs (pairs, typicalWeights (), parameters), std::invalid_argument);
}

TEST (CrfClustering, ScatteredPairsStartFromABoundedNumberOfClusters)
{
  // 3 000 pairs scattered over 40 m x 40 m, every one its own segment at 0.5 m: the
  // bound on pairs per cluster cannot join them, and 3 000 initial clusters cost
  // 3 000 x 3 000 per round (20 000 such pairs took over 600 s and 3 GB).
  const int n = 3000;
  std::mt19937 rng (7);
  std::uniform_real_distribution<double> coordinate (-20.0, 20.0);
  Eigen::Matrix2Xd source (2, n);
  for (int i = 0; i < n; ++i)
    source.col (i) << coordinate (rng), coordinate (rng);
  std::vector<int> match (n);
  std::iota (match.begin (), match.end (), 0);
  const Rigid2d ego = makeRigid2d (0.1, 0.0, 0.01);
  const Eigen::Matrix2Xd target = (ego.linear () * source).colwise () + ego.translation ();
  const PointPairs pairs = makePointPairs (source, target, match);
  const CrfClusteringResult result = clusterPointPairs (pairs, typicalWeights (), CrfClusteringParameters ());
  EXPECT_EQ (result.initial_clusters, 256);
  ASSERT_EQ (result.motions.size (), 1u);
  EXPECT_LT (motionError (result.motions[0], ego).first, 1e-6);
}

}  // namespace
