#include <pcl_crf/metrics/clustering_metrics.h>
#include <pcl_crf/metrics/pair_scores.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pcl_crf::kNoMatch;
using pcl_crf::makeRigid2d;

Eigen::Matrix2Xd
pointsOnXAxis (int count)
{
  Eigen::Matrix2Xd points = Eigen::Matrix2Xd::Zero (2, count);
  for (int i = 0; i < count; ++i)
    points (0, i) = i;
  return points;
}

/** Five source points, four target points t0 = (0, 0), t1 = (0.05, 0),
 *  t2 = (1, 0), t3 = (2, 0); true matches {0, 2, none, 3, none}; one static world.
 */
pcl_crf::ScanPair
associationPair ()
{
  pcl_crf::ScanPair pair;
  pair.source = pointsOnXAxis (5);
  pair.target.resize (2, 4);
  pair.target << 0.0, 0.05, 1.0, 2.0,
                 0.0, 0.0, 0.0, 0.0;
  pair.source_match = {0, 2, kNoMatch, 3, kNoMatch};
  pair.source_object = {0, 0, 0, 0, 0};
  pair.objects.push_back ({0, true, pcl_crf::Rigid2d::Identity (), "world"});
  return pair;
}

/** Eleven source points of objects {0,0,0,0,0,1,1,1,2,2,2}: 0 the static world
 *  turning 0.1 rad, 1 a car, 2 a pedestrian. The last three are true outliers.
 */
pcl_crf::ScanPair
clusteringPair ()
{
  pcl_crf::ScanPair pair;
  pair.source = pointsOnXAxis (11);
  pair.target = pointsOnXAxis (2);
  pair.source_object = {0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2};
  pair.source_match = {0, 0, 0, 0, 0, 1, 1, 1, kNoMatch, kNoMatch, kNoMatch};
  pair.objects.push_back ({0, true, makeRigid2d (0.0, 0.0, 0.1), "world"});
  pair.objects.push_back ({1, false, makeRigid2d (2.0, 0.0, 0.0), "car"});
  pair.objects.push_back ({2, false, makeRigid2d (1.0, 0.5, 0.0), "pedestrian"});
  return pair;
}

/** Clusters {0,0,0,1,1,1,1,-1,2,2,3}: cluster 0 -> world and cluster 2 ->
 *  pedestrian are mutual majorities; cluster 1 -> car is not (2 of its 4 points),
 *  cluster 3 is unpaired (see test_metrics_cluster_matching.cpp).
 */
pcl_crf::Prediction
clusteringPrediction ()
{
  pcl_crf::Prediction prediction;
  prediction.source_cluster = {0, 0, 0, 1, 1, 1, 1, -1, 2, 2, 3};
  prediction.cluster_motions = {makeRigid2d (0.0, 0.0, 0.08),   // world: 0.02 rad off
                                makeRigid2d (5.0, 5.0, 1.0),    // car: far off, but not scored
                                makeRigid2d (1.3, 0.1, 0.0),    // pedestrian: (-0.3, 0.4) off
                                pcl_crf::Rigid2d::Identity ()};
  prediction.static_cluster = 0;
  // The truth is the inverse of the world's motion, R(-0.1).
  prediction.T_source_target = makeRigid2d (0.0, 0.0, -0.08);
  prediction.seconds = 0.25;
  return prediction;
}

TEST (MetricsPairScores, AssociationScores)
{
  pcl_crf::Prediction prediction;
  prediction.source_match = {1, 2, kNoMatch, kNoMatch, 0};
  prediction.seconds = 0.5;
  const pcl_crf::PairScores scores = pcl_crf::scorePair (associationPair (), prediction);
  // p1 and p2 exact; p0 (t1 for t0, 0.05 m away) also within 0.1 m.
  EXPECT_DOUBLE_EQ (scores.association_accuracy, 0.4);
  EXPECT_DOUBLE_EQ (scores.association_accuracy_tolerance, 0.6);
  // Substitutions at p0, p3, p4.
  EXPECT_DOUBLE_EQ (scores.association_sed, 3.0);
  EXPECT_DOUBLE_EQ (scores.predicted_outlier_pct, 40.0);
  EXPECT_DOUBLE_EQ (scores.true_outlier_pct, 40.0);
  EXPECT_DOUBLE_EQ (scores.found_outlier_pct, 50.0);
  // No clustering given: clustering fields NaN, objects_true from the truth.
  EXPECT_TRUE (std::isnan (scores.v_measure));
  EXPECT_TRUE (std::isnan (scores.cluster_accuracy));
  EXPECT_TRUE (std::isnan (scores.static_rotation_error));
  EXPECT_DOUBLE_EQ (scores.objects_true, 1.0);
  // Identity ego motion against an identity world.
  EXPECT_NEAR (scores.ego_rotation_error, 0.0, 1e-12);
  EXPECT_NEAR (scores.ego_translation_error, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ (scores.seconds, 0.5);
}

/** Six source and six target points on an arc 5 m away, bearings 0, 0.1, ..., 0.5 rad
 *  (beam order); true matches 0 … 5, one static world. */
pcl_crf::ScanPair
arcPair ()
{
  pcl_crf::ScanPair pair;
  pair.source.resize (2, 6);
  for (int i = 0; i < 6; ++i)
    pair.source.col (i) = 5.0 * Eigen::Vector2d (std::cos (0.1 * i), std::sin (0.1 * i));
  pair.target = pair.source;
  pair.source_match = {0, 1, 2, 3, 4, 5};
  pair.source_object.assign (6, 0);
  pair.objects.push_back ({0, true, pcl_crf::Rigid2d::Identity (), "world"});
  return pair;
}

TEST (MetricsPairScores, EditDistancesReadTheScanInBeamOrder)
{
  // Matches shifted by one beam: delete the first, insert an outlier at the end.
  pcl_crf::ScanPair pair = arcPair ();
  pcl_crf::Prediction prediction;
  prediction.source_match = {1, 2, 3, 4, 5, kNoMatch};
  EXPECT_DOUBLE_EQ (pcl_crf::scorePair (pair, prediction).association_sed, 2.0);
  // The same source points listed in no beam order, truth and prediction with them:
  // read in the file's order the sequences were 6 edits apart.
  const std::vector<int> order{3, 0, 5, 1, 4, 2};
  pcl_crf::ScanPair shuffled = pair;
  pcl_crf::Prediction shuffled_prediction;
  for (std::size_t k = 0; k < order.size (); ++k) {
    shuffled.source.col (static_cast<Eigen::Index> (k)) = pair.source.col (order[k]);
    shuffled.source_match[k] = pair.source_match[static_cast<std::size_t> (order[k])];
    shuffled_prediction.source_match.push_back (prediction.source_match[static_cast<std::size_t> (order[k])]);
  }
  EXPECT_DOUBLE_EQ (pcl_crf::scorePair (shuffled, shuffled_prediction).association_sed, 2.0);
}

TEST (MetricsPairScores, ToleranceComesFromOptions)
{
  pcl_crf::Prediction prediction;
  prediction.source_match = {1, 2, kNoMatch, kNoMatch, 0};
  pcl_crf::ScoreOptions options;
  options.match_tolerance = 0.01;  // t1 is 0.05 m from t0: no longer close enough
  EXPECT_DOUBLE_EQ (pcl_crf::scorePair (associationPair (), prediction, options)
                        .association_accuracy_tolerance, 0.4);
}

TEST (MetricsPairScores, ClusteringScores)
{
  const pcl_crf::PairScores scores =
      pcl_crf::scorePair (clusteringPair (), clusteringPrediction ());
  // Raw labels (-1 a label of its own) against object ids; reference values
  // from an independent entropy computation of the same contingency table.
  EXPECT_NEAR (scores.homogeneity, 0.763793, 1e-6);
  EXPECT_NEAR (scores.completeness, 0.555149, 1e-6);
  EXPECT_NEAR (scores.v_measure, 0.642968, 1e-6);
  // Mapped {0,0,0,1,1,1,1,-1,2,2,-1} vs true {0,0,0,0,0,1,1,1,2,2,2}.
  EXPECT_DOUBLE_EQ (scores.cluster_accuracy, 7.0 / 11.0);
  EXPECT_DOUBLE_EQ (scores.cluster_sed, 4.0);
  EXPECT_DOUBLE_EQ (scores.clusters_found, 4.0);
  EXPECT_DOUBLE_EQ (scores.objects_true, 3.0);
  // World: 0.1 rad true, 0.08 estimated.
  EXPECT_NEAR (scores.static_rotation_error, 0.02, 1e-12);
  EXPECT_NEAR (scores.static_translation_error, 0.0, 1e-12);
  // Only the pedestrian counts: ||(1.0, 0.5) - (1.3, 0.1)|| = 0.5.
  EXPECT_NEAR (scores.moving_rotation_error, 0.0, 1e-12);
  EXPECT_NEAR (scores.moving_translation_error, 0.5, 1e-12);
  // Ego: R(-0.08) against the true R(-0.1).
  EXPECT_NEAR (scores.ego_rotation_error, 0.02, 1e-12);
  EXPECT_NEAR (scores.ego_translation_error, 0.0, 1e-12);
  // No association given: association fields NaN, true outliers from the truth (3 of 11).
  EXPECT_TRUE (std::isnan (scores.association_accuracy));
  EXPECT_TRUE (std::isnan (scores.association_sed));
  EXPECT_TRUE (std::isnan (scores.predicted_outlier_pct));
  EXPECT_TRUE (std::isnan (scores.found_outlier_pct));
  EXPECT_DOUBLE_EQ (scores.true_outlier_pct, 300.0 / 11.0);
  EXPECT_DOUBLE_EQ (scores.seconds, 0.25);
}

TEST (MetricsPairScores, VMeasureUsesBetaFromOptions)
{
  pcl_crf::ScoreOptions options;
  options.v_beta = 0.0;  // V_0 = homogeneity
  const auto scores = pcl_crf::scorePair (clusteringPair (), clusteringPrediction (), options);
  EXPECT_NEAR (scores.v_measure, 0.763793, 1e-6);
}

TEST (MetricsPairScores, MovingErrorsAreAveragedOverCorrectObjects)
{
  pcl_crf::ScanPair truth;
  truth.source = pointsOnXAxis (6);
  truth.source_object = {0, 0, 1, 1, 2, 2};
  truth.objects.push_back ({0, true, pcl_crf::Rigid2d::Identity (), "world"});
  truth.objects.push_back ({1, false, makeRigid2d (1.0, 0.0, 0.0), "car"});
  truth.objects.push_back ({2, false, makeRigid2d (0.0, 1.0, 0.2), "cyclist"});
  pcl_crf::Prediction prediction;
  prediction.source_cluster = {0, 0, 1, 1, 2, 2};
  prediction.cluster_motions = {pcl_crf::Rigid2d::Identity (),
                                makeRigid2d (1.5, 0.0, 0.0),   // 0 rad, 0.5 m
                                makeRigid2d (0.0, 1.1, 0.1)};  // 0.1 rad, 0.1 m
  const auto matching =
      pcl_crf::matchClustersToObjects (prediction.source_cluster, truth.source_object);
  const auto errors = pcl_crf::computeObjectMotionErrors (truth, prediction, matching);
  EXPECT_NEAR (errors.static_rotation, 0.0, 1e-12);
  EXPECT_NEAR (errors.static_translation, 0.0, 1e-12);
  EXPECT_NEAR (errors.moving_rotation, (0.0 + 0.1) / 2.0, 1e-12);
  EXPECT_NEAR (errors.moving_translation, (0.5 + 0.1) / 2.0, 1e-12);
}

TEST (MetricsPairScores, NoCorrectObjectGivesNanErrors)
{
  // One cluster over two equal objects: 2 of 4 points is not a majority of the cluster.
  pcl_crf::ScanPair truth;
  truth.source = pointsOnXAxis (4);
  truth.source_object = {0, 0, 1, 1};
  truth.objects.push_back ({0, true, pcl_crf::Rigid2d::Identity (), "world"});
  truth.objects.push_back ({1, false, makeRigid2d (1.0, 0.0, 0.0), "car"});
  pcl_crf::Prediction prediction;
  prediction.source_cluster = {0, 0, 0, 0};
  prediction.cluster_motions = {pcl_crf::Rigid2d::Identity ()};
  const auto scores = pcl_crf::scorePair (truth, prediction);
  EXPECT_TRUE (std::isnan (scores.static_rotation_error));
  EXPECT_TRUE (std::isnan (scores.moving_translation_error));
  // The cluster pairs with the world (tie -> smaller id): points 0 and 1 right.
  EXPECT_DOUBLE_EQ (scores.cluster_accuracy, 0.5);
  EXPECT_DOUBLE_EQ (scores.clusters_found, 1.0);
}

TEST (MetricsPairScores, EmptyPredictionLeavesOnlyTruthEgoAndTime)
{
  pcl_crf::Prediction prediction;  // an ICP-like method: ego motion only
  prediction.T_source_target = makeRigid2d (0.0, 0.0, -0.08);
  prediction.seconds = 0.125;
  const auto scores = pcl_crf::scorePair (clusteringPair (), prediction);
  EXPECT_TRUE (std::isnan (scores.association_accuracy));
  EXPECT_TRUE (std::isnan (scores.association_accuracy_tolerance));
  EXPECT_TRUE (std::isnan (scores.association_sed));
  EXPECT_TRUE (std::isnan (scores.predicted_outlier_pct));
  EXPECT_TRUE (std::isnan (scores.found_outlier_pct));
  EXPECT_TRUE (std::isnan (scores.homogeneity));
  EXPECT_TRUE (std::isnan (scores.completeness));
  EXPECT_TRUE (std::isnan (scores.v_measure));
  EXPECT_TRUE (std::isnan (scores.cluster_accuracy));
  EXPECT_TRUE (std::isnan (scores.cluster_sed));
  EXPECT_TRUE (std::isnan (scores.clusters_found));
  EXPECT_TRUE (std::isnan (scores.static_rotation_error));
  EXPECT_TRUE (std::isnan (scores.static_translation_error));
  EXPECT_TRUE (std::isnan (scores.moving_rotation_error));
  EXPECT_TRUE (std::isnan (scores.moving_translation_error));
  EXPECT_DOUBLE_EQ (scores.true_outlier_pct, 300.0 / 11.0);
  EXPECT_DOUBLE_EQ (scores.objects_true, 3.0);
  EXPECT_NEAR (scores.ego_rotation_error, 0.02, 1e-12);
  EXPECT_DOUBLE_EQ (scores.seconds, 0.125);
}

void
expectInvalidArgumentMentioning (const pcl_crf::ScanPair& truth,
                                 const pcl_crf::Prediction& prediction,
                                 const std::string& words)
{
  try {
    pcl_crf::scorePair (truth, prediction);
    ADD_FAILURE () << "expected std::invalid_argument mentioning '" << words << "'";
  }
  catch (const std::invalid_argument& error) {
    EXPECT_NE (std::string (error.what ()).find (words), std::string::npos) << error.what ();
  }
}

TEST (MetricsPairScores, WrongLengthsThrow)
{
  pcl_crf::Prediction matches;
  matches.source_match = {0, 1};
  expectInvalidArgumentMentioning (associationPair (), matches, "2 entries for 5 source points");

  pcl_crf::Prediction clusters;
  clusters.source_cluster = {0, 0, 0};
  clusters.cluster_motions = {pcl_crf::Rigid2d::Identity ()};
  expectInvalidArgumentMentioning (associationPair (), clusters, "3 entries for 5 source points");

  pcl_crf::ScanPair no_true_matches = associationPair ();
  no_true_matches.source_match.clear ();
  pcl_crf::Prediction five_matches;
  five_matches.source_match = {0, 0, 0, 0, 0};
  expectInvalidArgumentMentioning (no_true_matches, five_matches,
                                   "truth.source_match has 0 entries");
}

TEST (MetricsPairScores, BadLabelsAndIndicesThrow)
{
  pcl_crf::Prediction beyond_motions;
  beyond_motions.source_cluster = {0, 1, 0, 0, 0};
  beyond_motions.cluster_motions = {pcl_crf::Rigid2d::Identity ()};
  expectInvalidArgumentMentioning (associationPair (), beyond_motions, "cluster_motions holds 1");

  pcl_crf::Prediction negative_label;
  negative_label.source_cluster = {0, -2, 0, 0, 0};
  negative_label.cluster_motions = {pcl_crf::Rigid2d::Identity ()};
  expectInvalidArgumentMentioning (associationPair (), negative_label, "is -2");

  pcl_crf::Prediction beyond_target;
  beyond_target.source_match = {0, 0, 4, 0, 0};
  expectInvalidArgumentMentioning (associationPair (), beyond_target, "target index 4");

  pcl_crf::ScanPair undeclared_object = associationPair ();
  undeclared_object.source_object[3] = 7;
  pcl_crf::Prediction one_cluster;
  one_cluster.source_cluster = {0, 0, 0, 0, 0};
  one_cluster.cluster_motions = {pcl_crf::Rigid2d::Identity ()};
  expectInvalidArgumentMentioning (undeclared_object, one_cluster, "is 7");
}

}  // namespace
