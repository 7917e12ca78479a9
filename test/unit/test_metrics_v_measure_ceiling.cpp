#include <pcl_crf/metrics/v_measure_ceiling.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::labelsWithoutSmallObjects;
using pcl_crf::vMeasureCeilings;

/** A pair of \a objects.size () source points on the x axis labelled \a objects, whose
 *  static world is object \a static_id. */
pcl_crf::ScanPair
labelledPair (const std::vector<int>& objects, int static_id)
{
  pcl_crf::ScanPair pair;
  pair.name = "pair";
  pair.source = Eigen::Matrix2Xd::Zero (2, static_cast<Eigen::Index> (objects.size ()));
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    pair.source (0, i) = static_cast<double> (i);
  pair.target = pair.source;
  pair.source_object = objects;
  pair.objects.push_back ({static_id, true, pcl_crf::Rigid2d::Identity (), "world"});
  return pair;
}

TEST (VMeasureCeilingTest, SmallObjectsJoinTheBackground)
{
  EXPECT_EQ (labelsWithoutSmallObjects ({0, 0, 0, 1, 1, 2}, 1, 0), (std::vector<int>{0, 0, 0, 1, 1, 2}));
  EXPECT_EQ (labelsWithoutSmallObjects ({0, 0, 0, 1, 1, 2}, 2, 0), (std::vector<int>{0, 0, 0, 1, 1, 0}));
  EXPECT_EQ (labelsWithoutSmallObjects ({0, 0, 0, 1, 1, 2}, 3, 0), (std::vector<int>{0, 0, 0, 0, 0, 0}));
  // the background need not be an object of the pair (no static world: -1)
  EXPECT_EQ (labelsWithoutSmallObjects ({4, 4, 7}, 2, -1), (std::vector<int>{4, 4, -1}));
  EXPECT_THROW (labelsWithoutSmallObjects ({0, 1}, 0, 0), std::invalid_argument);
}

TEST (VMeasureCeilingTest, MeanVOfTheOraclesEqualsHandComputedValues)
{
  // Pair a: world 7 points, a 2-point car, a 1-point pedestrian. Pair b: world only.
  const std::vector<pcl_crf::ScanPair> pairs = {labelledPair ({0, 0, 0, 0, 0, 0, 0, 1, 1, 2}, 0),
                                                labelledPair ({0, 0, 0, 0}, 0)};
  const auto ceilings = vMeasureCeilings (pairs, {1, 2, 3}, 0.95);
  ASSERT_EQ (ceilings.size (), 3u);
  // Every object found: V = 1 on both pairs.
  EXPECT_EQ (ceilings[0].min_points, 1);
  EXPECT_DOUBLE_EQ (ceilings[0].mean_v, 1.0);
  EXPECT_EQ (ceilings[0].pairs_reaching, 2);
  // The pedestrian in the world, on pair a: clusters {world + pedestrian: 8, car: 2}.
  // H(C) = -(.7 ln .7 + .2 ln .2 + .1 ln .1) = 0.8018186, H(C|K) = -(.7 ln 7/8 + .1 ln 1/8)
  // = 0.3014161, h = 0.6240844; every class in one cluster, c = 1; V = 2h / (h + 1) =
  // 0.7685369. Pair b keeps V = 1: mean 0.8842684.
  EXPECT_NEAR (ceilings[1].mean_v, (0.7685369 + 1.0) / 2.0, 1e-7);
  EXPECT_EQ (ceilings[1].pairs_reaching, 1);
  // The car too: pair a is one cluster of three classes, h = 0 and V = 0.
  EXPECT_NEAR (ceilings[2].mean_v, 0.5, 1e-12);
  EXPECT_EQ (ceilings[2].pairs_reaching, 1);
}

TEST (VMeasureCeilingTest, RejectsUnlabelledPairsAndBadSizes)
{
  EXPECT_THROW (vMeasureCeilings ({}, {1}, 0.95), std::invalid_argument);
  pcl_crf::ScanPair unlabelled = labelledPair ({0, 0, 1}, 0);
  unlabelled.source_object.pop_back ();
  EXPECT_THROW (vMeasureCeilings ({unlabelled}, {1}, 0.95), std::invalid_argument);
  EXPECT_THROW (vMeasureCeilings ({labelledPair ({}, 0)}, {1}, 0.95), std::invalid_argument);
  EXPECT_THROW (vMeasureCeilings ({labelledPair ({0, 1}, 0)}, {0}, 0.95), std::invalid_argument);
}

}  // namespace
