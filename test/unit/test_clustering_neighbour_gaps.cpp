// CRF-Clustering's weighted neighbour feature (Eq. (5)) across runs of beams without an
// associated return (FeatureOptions::weighted_neighbour_max_gap). Its effect in the joint
// model's final clustering is tested on the real overtakes bag in test_joint_estimator.cpp.

#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/crf/chain_features.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace {

using namespace pcl_crf;
using namespace pcl_crf::clustering;

constexpr double kDegree = M_PI / 180.0;

/** A point at \a range [m] on the beam at \a bearing [degrees]. */
Eigen::Vector2d
onBeam (double range, double bearing)
{
  return range * Eigen::Vector2d (std::cos (bearing * kDegree), std::sin (bearing * kDegree));
}

/** Pairs of a scan with a 1° step, each point associated with itself moved by \a T. */
PointPairs
pairsOf (const std::vector<Eigen::Vector2d>& points, const Rigid2d& T = Rigid2d::Identity ())
{
  Eigen::Matrix2Xd source (2, static_cast<Eigen::Index> (points.size ()));
  std::vector<int> match (points.size ());
  for (std::size_t i = 0; i < points.size (); ++i) {
    source.col (static_cast<Eigen::Index> (i)) = points[i];
    match[i] = static_cast<int> (i);
  }
  const Eigen::Matrix2Xd target = (T.linear () * source).colwise () + T.translation ();
  return makePointPairs (source, target, match);
}

/** The weighted neighbour feature of edge (i, i + 1) when both nodes take cluster 0. */
double
weightedNeighbourOfEdge (const PointPairs& pairs, std::size_t i, const FeatureOptions& options)
{
  const std::vector<Rigid2d> motions = {Rigid2d::Identity ()};
  const crf::ChainFeatures features = chainFeatures (pairs, motions, allStates (pairs.size (), 1), options);
  return features.pairwise[i] (crf::ChainFeatures::pairRow (0, 0, 1), 1);
}

TEST (WeightedNeighbourGaps, TheFeatureIsZeroAcrossMoreBeamsThanTheBoundWithoutAPair)
{
  // Bearings 0–4° a beam apart, then 16° (11 beams between) and 27° (10 between).
  const PointPairs pairs = pairsOf ({onBeam (1.0, 0), onBeam (1.0, 1), onBeam (1.0, 2), onBeam (1.0, 3),
                                     onBeam (1.0, 4), onBeam (1.0, 16), onBeam (1.0, 27)});
  ASSERT_NEAR (pairs.angular_resolution, kDegree, 1e-12);
  const double across_eleven = 1.0 / (onBeam (1.0, 16) - onBeam (1.0, 4)).norm ();
  const double across_ten = 1.0 / (onBeam (1.0, 27) - onBeam (1.0, 16)).norm ();
  FeatureOptions paper;  // no bound
  EXPECT_NEAR (weightedNeighbourOfEdge (pairs, 4, paper), across_eleven, 1e-12);
  EXPECT_NEAR (weightedNeighbourOfEdge (pairs, 5, paper), across_ten, 1e-12);
  FeatureOptions bounded;
  bounded.weighted_neighbour_max_gap = 10;
  EXPECT_NEAR (weightedNeighbourOfEdge (pairs, 0, bounded), 1.0 / (2.0 * std::sin (0.5 * kDegree)), 1e-9);
  EXPECT_EQ (weightedNeighbourOfEdge (pairs, 4, bounded), 0.0);
  EXPECT_NEAR (weightedNeighbourOfEdge (pairs, 5, bounded), across_ten, 1e-12);
  bounded.weighted_neighbour_max_gap = 11;
  EXPECT_NEAR (weightedNeighbourOfEdge (pairs, 4, bounded), across_eleven, 1e-12);
}

TEST (WeightedNeighbourGaps, DirectPotentialsApplyTheBoundAsTheFeaturesDo)
{
  const PointPairs pairs = pairsOf ({onBeam (2.0, 0), onBeam (2.0, 1), onBeam (0.5, 20), onBeam (0.5, 21)});
  const std::vector<Rigid2d> motions = {Rigid2d::Identity (), makeRigid2d (0.05, 0.0, 0.0)};
  const CandidateStates states = allStates (pairs.size (), 2);
  Eigen::VectorXd w (kWeightCount);
  w << 0.11, -1.12, 1.98, 3.72, -0.76;  // the order of the shipped joint model's CRF-Clustering
  FeatureOptions options;
  options.weighted_neighbour_max_gap = 10;
  const Eigen::MatrixXd residuals = squaredResiduals (pairs, motions);
  const crf::ChainPotentials from_features =
      crf::potentials (chainFeatures (pairs, motions, states, options, &residuals), w);
  const crf::ChainPotentials direct =
      chainPotentials (pairs, motions, states, localLogPotentials (pairs, residuals, w, options), w, options);
  for (std::size_t i = 0; i + 1 < direct.size (); ++i)
    ASSERT_LT ((direct.pairwise[i] - from_features.pairwise[i]).cwiseAbs ().maxCoeff (), 1e-12) << "edge " << i;
  // Across the 18 beams between points 1 and 2 only the neighbour weight rewards a shared cluster.
  EXPECT_NEAR (direct.pairwise[1] (0, 0), w (2), 1e-12);
  EXPECT_NEAR (direct.pairwise[0] (0, 0), w (2) + w (3) / (onBeam (2.0, 1) - onBeam (2.0, 0)).norm (), 1e-9);
}

TEST (WeightedNeighbourGaps, ABoundBelowMinusOneIsAnError)
{
  const PointPairs pairs = pairsOf ({onBeam (1.0, 0), onBeam (1.0, 1), onBeam (1.0, 2)});
  Eigen::VectorXd w (kWeightCount);
  w << 0.11, -1.12, 1.98, 3.72, -0.76;
  CrfClusteringParameters parameters;
  parameters.features.weighted_neighbour_max_gap = -2;
  EXPECT_THROW (clusterPointPairs (pairs, w, parameters), std::invalid_argument);
  parameters.features.weighted_neighbour_max_gap = 0;  // a bound of no beam at all is a valid one
  EXPECT_EQ (clusterPointPairs (pairs, w, parameters).motions.size (), 1u);
}

}  // namespace
