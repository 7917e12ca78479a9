// The joint model's core: node pseudo-likelihood, ladder inference, model files.
#include <pcl_crf/crf/chain_inference.h>
#include <pcl_crf/crf/node_pseudo_likelihood.h>
#include <pcl_crf/joint/joint_features.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/joint/ladder_inference.h>
#include <pcl_crf/joint/map_history.h>

#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace {

using namespace pcl_crf;

TEST (NodePseudoLikelihood, GradientMatchesFiniteDifferences)
{
  std::mt19937 rng (7);
  std::normal_distribution<double> normal;
  std::vector<crf::NodeConditional> nodes;
  for (int v = 0; v < 6; ++v) {
    crf::NodeConditional node;
    node.features = Eigen::MatrixXd::NullaryExpr (2 + v % 3, 4, [&] () { return normal (rng); });
    node.label = v % node.features.rows ();
    nodes.push_back (node);
  }
  const Eigen::VectorXd w = Eigen::VectorXd::NullaryExpr (4, [&] () { return normal (rng); });
  Eigen::VectorXd gradient, unused;
  crf::nodePseudoLikelihoodObjective (nodes, 3.0, w, gradient);
  for (int k = 0; k < 4; ++k) {
    const double h = 1e-6;
    Eigen::VectorXd up = w, down = w;
    up (k) += h;
    down (k) -= h;
    const double numeric = (crf::nodePseudoLikelihoodObjective (nodes, 3.0, up, unused) -
                            crf::nodePseudoLikelihoodObjective (nodes, 3.0, down, unused)) / (2 * h);
    EXPECT_NEAR (gradient (k), numeric, 1e-6);
  }
}

TEST (NodePseudoLikelihood, LearnsTheFeatureThatPicksTheLabel)
{
  // Feature 0 is 1 on the true state, feature 1 is noise: w_0 must come out large, w_1 ~ 0.
  std::vector<crf::NodeConditional> nodes;
  for (int v = 0; v < 20; ++v) {
    crf::NodeConditional node;
    node.features = Eigen::MatrixXd::Zero (3, 2);
    node.label = v % 3;
    node.features (node.label, 0) = 1.0;
    node.features ((v + 1) % 3, 1) = 1.0;
    node.features ((v + 2) % 3, 1) = 1.0;
    node.features (node.label, 1) = 1.0;
    nodes.push_back (node);
  }
  const Eigen::VectorXd w = crf::learnNodePseudoLikelihood (nodes, 2.0).x;
  EXPECT_GT (w (0), 2.0);
  EXPECT_NEAR (w (1), 0.0, 1e-3);
}

TEST (NodePseudoLikelihood, RejectsBadInput)
{
  EXPECT_THROW (crf::learnNodePseudoLikelihood ({}, 1.0), std::invalid_argument);
  crf::NodeConditional node{Eigen::MatrixXd::Zero (2, 3), 2};
  EXPECT_THROW (crf::learnNodePseudoLikelihood ({node}, 1.0), std::invalid_argument);  // label out of range
  node.label = 0;
  EXPECT_THROW (crf::learnNodePseudoLikelihood ({node}, 0.0), std::invalid_argument);  // σ
  crf::NodeConditional other{Eigen::MatrixXd::Zero (2, 4), 0};
  EXPECT_THROW (crf::learnNodePseudoLikelihood ({node, other}, 1.0), std::invalid_argument);  // D differs
}

/** A ladder where a moving object's shape is ambiguous (the Fig. 3 situation of the
 *  joint paper): 12 static points (the true target is candidate 0) and 8 points of
 *  an object moved by 1 m along x. The object's points each have two candidates:
 *  the target point straight ahead under the static motion (a slightly better local
 *  score, what a wall sliding along itself shows) and the true one, 1 m further;
 *  only at the object's two ends is the static-looking candidate 1 m off. */
struct AmbiguousLadder
{
  joint::LadderGeometry geometry;
  crf::ChainPotentials association;
  std::vector<int> truth_state, truth_cluster;
  std::vector<Rigid2d> motions{Rigid2d::Identity (), makeRigid2d (1.0, 0.0, 0.0)};
  Eigen::VectorXd weights = Eigen::VectorXd::Zero (joint::kJointWeightCount);

  AmbiguousLadder ()
  {
    const int statics = 12, movers = 8, n = statics + movers;
    Eigen::Matrix2Xd source (2, n), target (2, n + movers);
    matching::Candidates candidates;
    for (int i = 0; i < n; ++i) {
      const bool moving = i >= statics;
      source.col (i) = moving ? Eigen::Vector2d (0.2 * (i - statics), 2.0) : Eigen::Vector2d (0.25 * i - 1.0, 5.0);
      const bool end = i == statics || i == n - 1;  // the object's ends show where it went
      target.col (i) = moving ? Eigen::Vector2d (source.col (i) + Eigen::Vector2d (0.0, end ? 1.0 : 0.001))
                              : source.col (i);
      if (moving)  // the true match, one metre along the motion
        target.col (n + i - statics) = source.col (i) + Eigen::Vector2d (1.0, 0.0);
      candidates.targets.push_back (i);
      if (moving)
        candidates.targets.push_back (n + i - statics);
      candidates.offsets.push_back (static_cast<int> (candidates.targets.size ()));
      truth_state.push_back (moving ? 1 : 0);
      truth_cluster.push_back (moving ? 1 : 0);
    }
    geometry = joint::makeLadderGeometry (source, target, candidates);
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd u = Eigen::VectorXd::Constant (candidates.count (i) + 1, -3.0);  // the outlier state last
      u (0) = 0.0;
      if (candidates.count (i) == 2)
        u (1) = -0.5;  // the true, moved candidate looks slightly worse locally
      association.unary.push_back (u);
    }
    for (int i = 0; i + 1 < n; ++i)
      association.pairwise.push_back (Eigen::MatrixXd::Zero (candidates.count (i) + 1, candidates.count (i + 1) + 1));
    weights (joint::kRungSpacingResidual) = -1.0;
    weights (joint::kRungBeamResidual) = -1.0;
    weights (joint::kRungMatchedOutlierCluster) = -20.0;
    weights (joint::kRungUnmatchedCluster) = -20.0;
    weights (joint::kClusterWeightedNeighbour) = 2.0;  // 10 between object points 0.2 m apart
  }
};

TEST (LadderInference, AssociatesAlongTheClusterMotionWhereTheChainAloneDoesNot)
{
  const AmbiguousLadder ladder;
  // The association chain alone takes the locally better, static-looking candidate.
  const crf::MapResult alone = crf::maxProduct (ladder.association);
  for (int i = 12; i < 20; ++i)
    EXPECT_EQ (alone.labels[i], 0) << i;
  // The joint ladder, started from those associations with the object in its own
  // cluster, associates the object along its motion.
  joint::LadderOptions options;
  options.max_iterations = 60;
  const joint::LadderResult r = joint::inferLadder (ladder.geometry, ladder.association, ladder.weights,
                                                    ladder.motions, alone.labels, ladder.truth_cluster, options);
  EXPECT_EQ (r.association, ladder.truth_state);
  EXPECT_EQ (r.cluster, ladder.truth_cluster);
  EXPECT_TRUE (r.converged);
  // the refit motions are the true ones (exact pairs)
  EXPECT_NEAR ((r.motions[1].translation () - Eigen::Vector2d (1.0, 0.0)).norm (), 0.0, 1e-9);
  EXPECT_NEAR (rotationAngle (r.motions[1]), 0.0, 1e-9);
  EXPECT_NEAR (r.motions[0].translation ().norm (), 0.0, 1e-9);
}

TEST (LadderInference, FloodingScheduleKeepsTheStaticWorld)
{
  // The paper's flooding schedule moves evidence one point per iteration; on this
  // ladder it settles on the static reading of the object (the sweep does not), but
  // the static world's associations and motion come out exact.
  const AmbiguousLadder ladder;
  joint::LadderOptions options;
  options.schedule = joint::MessageSchedule::Flooding;
  options.max_iterations = 60;
  const joint::LadderResult r = joint::inferLadder (ladder.geometry, ladder.association, ladder.weights,
                                                    ladder.motions, ladder.truth_state, ladder.truth_cluster, options);
  ASSERT_EQ (r.association.size (), 20u);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ (r.association[i], 0);
    EXPECT_EQ (r.cluster[i], 0);
  }
  EXPECT_LE (r.iterations, 60);
}

TEST (LadderInference, SweepConvergesInFewIterations)
{
  const AmbiguousLadder ladder;
  const joint::LadderResult r = joint::inferLadder (ladder.geometry, ladder.association, ladder.weights,
                                                    ladder.motions, ladder.truth_state, ladder.truth_cluster, {});
  EXPECT_TRUE (r.converged);
  EXPECT_LE (r.iterations, 3);
  // the beliefs are normalised probabilities
  for (int i = 0; i < r.cluster_beliefs.cols (); ++i)
    EXPECT_NEAR (r.cluster_beliefs.col (i).sum (), 1.0, 1e-12);
}

TEST (LadderInference, RejectsInconsistentInput)
{
  const AmbiguousLadder ladder;
  const std::vector<int> short_labels (3, 0);
  EXPECT_THROW (joint::inferLadder (ladder.geometry, ladder.association, ladder.weights, ladder.motions, short_labels,
                                    ladder.truth_cluster),
                std::invalid_argument);
  EXPECT_THROW (joint::inferLadder (ladder.geometry, ladder.association, Eigen::VectorXd::Zero (3), ladder.motions,
                                    ladder.truth_state, ladder.truth_cluster),
                std::invalid_argument);
  EXPECT_THROW (joint::inferLadder (ladder.geometry, ladder.association, ladder.weights, {}, ladder.truth_state,
                                    ladder.truth_cluster),
                std::invalid_argument);
  joint::LadderOptions bad;
  bad.damping = 1.0;
  EXPECT_THROW (joint::inferLadder (ladder.geometry, ladder.association, ladder.weights, ladder.motions,
                                    ladder.truth_state, ladder.truth_cluster, bad),
                std::invalid_argument);
}

TEST (JointFeatures, PotentialsEqualWeightsTimesFeatures)
{
  const AmbiguousLadder ladder;
  Eigen::VectorXd w = Eigen::VectorXd::LinSpaced (joint::kJointWeightCount, -2.0, 3.0);
  const int i = 14;
  Eigen::Matrix2Xd moved (2, 2), moved_next (2, 2);
  for (int l = 0; l < 2; ++l) {
    moved.col (l) = ladder.motions[l] * ladder.geometry.source.col (i);
    moved_next.col (l) = ladder.motions[l] * ladder.geometry.source.col (i + 1);
  }
  joint::RungPotentials rungs;
  Eigen::MatrixXd edge (3, 3);
  joint::rungPotentials (ladder.geometry, ladder.motions, w, rungs);
  joint::clusterEdgePotential (ladder.geometry, i, moved, moved_next, w, edge);
  ASSERT_EQ (rungs.size (), static_cast<std::size_t> (ladder.geometry.size ()));
  for (int p = 0; p < ladder.geometry.size (); ++p) {
    const auto rung = rungs[p];
    ASSERT_EQ (rung.rows (), ladder.geometry.associationStates (p));
    ASSERT_EQ (rung.cols (), 3);
    for (int s = 0; s < rung.rows (); ++s)
      for (int l = 0; l < 3; ++l)
        EXPECT_NEAR (rung (s, l), w.dot (joint::rungFeatures (ladder.geometry, p, s, l, ladder.motions)), 1e-12);
  }
  // a new motion of cluster 1 rewrites its column and only it
  std::vector<Rigid2d> moved_motions = ladder.motions;
  moved_motions[1] = makeRigid2d (0.3, -0.2, 0.1);
  joint::updateRungColumn (ladder.geometry, moved_motions[1], w, 1, rungs);
  for (int p = 0; p < ladder.geometry.size (); ++p)
    for (int s = 0; s < rungs[p].rows (); ++s)
      for (int l = 0; l < 3; ++l)
        EXPECT_NEAR (rungs[p](s, l), w.dot (joint::rungFeatures (ladder.geometry, p, s, l, moved_motions)), 1e-12);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l)
      EXPECT_NEAR (edge (k, l), w.dot (joint::clusterEdgeFeatures (ladder.geometry, i, k, l, ladder.motions)), 1e-12);
}

TEST (JointModelFile, RejectsCorruptText)
{
  std::istringstream empty ("");
  EXPECT_THROW (joint::readJointModel (empty), std::runtime_error);
  std::istringstream wrong ("pcl_crf_crf_clustering_model 1\n");
  EXPECT_THROW (joint::readJointModel (wrong), std::runtime_error);
  std::istringstream version ("pcl_crf_joint_model 9\n");
  EXPECT_THROW (joint::readJointModel (version), std::runtime_error);
  std::istringstream truncated ("pcl_crf_joint_model 1\nprior_sigma 10\nmin_cluster_points 3\n");
  EXPECT_THROW (joint::readJointModel (truncated), std::runtime_error);
  std::istringstream nan ("pcl_crf_joint_model 1\nprior_sigma nan\n");
  EXPECT_THROW (joint::readJointModel (nan), std::runtime_error);
  EXPECT_THROW (joint::loadJointModel ("/nonexistent/joint.model"), std::runtime_error);
}

TEST (JointModelFile, VersionIsOneExactIntegerToken)
{
  // "1abc", "1.9" and "1e9" used to read as version 1 (operator>> stops at the first
  // character that is not a digit); trailing words were ignored.
  const std::pair<const char*, const char*> cases[] = {
      {"pcl_crf_joint_model 1abc\n", "version 1abc is not supported (expected 1)"},
      {"pcl_crf_joint_model 1.9\n", "version 1.9 is not supported"},
      {"pcl_crf_joint_model 1e9\n", "version 1e9 is not supported"},
      {"pcl_crf_joint_model +1\n", "version +1 is not supported"},
      {"pcl_crf_joint_model\n", "missing version"},
      {"pcl_crf_joint_model 1 junk\n", "unexpected text 'junk' after the version"}};
  for (const auto& [text, message] : cases) {
    std::istringstream in (text);
    try {
      joint::readJointModel (in, "j.model");
      ADD_FAILURE () << "accepted " << text;
    }
    catch (const std::runtime_error& error) {
      EXPECT_NE (std::string (error.what ()).find (message), std::string::npos) << error.what ();
    }
  }
}

}  // namespace

namespace pcl_crf {
namespace {

TEST (MapHistory, StopsOnlyWhenNoNodeReachesANewState)
{
  joint::MapHistory history;
  EXPECT_FALSE (history.repeats ({0, 1, 2}, {0, 0, 1}));  // nothing to compare with yet
  EXPECT_FALSE (history.repeats ({5, 1, 3}, {0, 0, 1}));  // one record before is not enough
  EXPECT_TRUE (history.repeats ({0, 1, 2}, {0, 0, 1}));   // nodes 0 and 2 flip back: a 2-cycle
  EXPECT_TRUE (history.repeats ({0, 1, 3}, {0, 0, 1}));   // node 0 settles, node 2 keeps flipping
  EXPECT_FALSE (history.repeats ({0, 1, 3}, {0, 2, 1}));  // node 1 reaches a new cluster
  // node 2's association state 2 was last held three records ago: new to the history
  EXPECT_FALSE (history.repeats ({0, 1, 2}, {0, 2, 1}));
  EXPECT_TRUE (history.repeats ({0, 1, 3}, {0, 2, 1}));
  EXPECT_FALSE (history.repeats ({0, 1, 4}, {0, 2, 1}));  // a third association state of node 2
}

TEST (MapHistory, NeverRepeatsAcrossDifferentSizes)
{
  joint::MapHistory history;
  history.repeats ({0, 1}, {0, 0});
  history.repeats ({0, 1}, {0, 0});
  EXPECT_FALSE (history.repeats ({0, 1, 2}, {0, 0, 0}));
  EXPECT_FALSE (history.repeats ({0}, {0, 0}));  // association and cluster sizes differ
}

}  // namespace
}  // namespace pcl_crf
