#include <pcl_crf/metrics/cluster_matching.h>
#include <pcl_crf/metrics/clustering_metrics.h>
#include <pcl_crf/metrics/edit_distance.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace {

// point:                         0  1  2  3  4  5  6   7  8  9 10
const std::vector<int> kObjects = {0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2};
const std::vector<int> kClusters = {0, 0, 0, 1, 1, 1, 1, -1, 2, 2, 3};
// Overlaps (cluster, object): (0,0)=3, (1,0)=2, (1,1)=2, (2,2)=2, (3,2)=1; the
// outlier point 7 is never counted. Greedy: (0,0) first; then the ties at 2 in
// order (1,0), (1,1), (2,2): (1,0) is skipped (object 0 taken), (1,1) and (2,2)
// are paired; (3,2) is skipped (object 2 taken), so cluster 3 maps to nothing.

TEST (MetricsClusterMatching, GreedyPairsLargestOverlapFirst)
{
  const pcl_crf::ClusterObjectMatching matching =
      pcl_crf::matchClustersToObjects (kClusters, kObjects);
  ASSERT_EQ (matching.pairs.size (), 3u);
  EXPECT_EQ (matching.pairs[0].cluster, 0);
  EXPECT_EQ (matching.pairs[0].object, 0);
  EXPECT_EQ (matching.pairs[0].overlap, 3u);
  EXPECT_EQ (matching.pairs[1].cluster, 1);
  EXPECT_EQ (matching.pairs[1].object, 1);
  EXPECT_EQ (matching.pairs[2].cluster, 2);
  EXPECT_EQ (matching.pairs[2].object, 2);
  EXPECT_EQ (matching.objectOf (3), -1);
  EXPECT_EQ (matching.objectOf (-1), -1);
}

TEST (MetricsClusterMatching, MutualMajorityNeedsMoreThanHalfBothWays)
{
  const pcl_crf::ClusterObjectMatching matching =
      pcl_crf::matchClustersToObjects (kClusters, kObjects);
  // (0,0): 3 of object 0's 5 points, 3 of cluster 0's 3 points -> yes.
  EXPECT_EQ (matching.pairs[0].object_points, 5u);
  EXPECT_EQ (matching.pairs[0].cluster_points, 3u);
  EXPECT_TRUE (matching.pairs[0].isMutualMajority ());
  // (1,1): 2 of object 1's 3 points, but only 2 of cluster 1's 4 points (not > half) -> no.
  EXPECT_EQ (matching.pairs[1].cluster_points, 4u);
  EXPECT_FALSE (matching.pairs[1].isMutualMajority ());
  // (2,2): 2 of object 2's 3 points, 2 of cluster 2's 2 points -> yes.
  EXPECT_TRUE (matching.pairs[2].isMutualMajority ());
}

TEST (MetricsClusterMatching, TiesGoToSmallerClusterThenSmallerObject)
{
  // One cluster split evenly over objects 2 and 1: the smaller object id wins.
  EXPECT_EQ (pcl_crf::matchClustersToObjects ({0, 0, 0, 0}, {2, 2, 1, 1}).objectOf (0), 1);
  // Two clusters splitting one object evenly: the smaller cluster label wins.
  const auto matching = pcl_crf::matchClustersToObjects ({3, 3, 1, 1}, {4, 4, 4, 4});
  EXPECT_EQ (matching.objectOf (1), 4);
  EXPECT_EQ (matching.objectOf (3), -1);
}

TEST (MetricsClusterMatching, OutliersAreNeverPaired)
{
  EXPECT_TRUE (pcl_crf::matchClustersToObjects ({-1, -1}, {0, 0}).pairs.empty ());
}

TEST (MetricsClusterMatching, MappedSequenceAccuracyAndEditDistance)
{
  const auto matching = pcl_crf::matchClustersToObjects (kClusters, kObjects);
  const std::vector<int> mapped = pcl_crf::mapClustersToObjects (kClusters, matching);
  EXPECT_EQ (mapped, (std::vector<int>{0, 0, 0, 1, 1, 1, 1, -1, 2, 2, -1}));
  // Correct at points 0, 1, 2, 5, 6, 8, 9: 7 of 11.
  EXPECT_DOUBLE_EQ (pcl_crf::clusterAccuracy (mapped, kObjects), 7.0 / 11.0);
  // Four substitutions (points 3, 4, 7, 10); no alignment does better.
  EXPECT_EQ (pcl_crf::editDistance (mapped, kObjects), 4);
}

TEST (MetricsClusterMatching, CountsClustersAndObjects)
{
  EXPECT_EQ (pcl_crf::countClusters (kClusters), 4);
  EXPECT_EQ (pcl_crf::countClusters ({-1, -1}), 0);
  EXPECT_EQ (pcl_crf::countObjects (kObjects), 3);
}

TEST (MetricsClusterMatching, SizeMismatchThrows)
{
  EXPECT_THROW (pcl_crf::matchClustersToObjects ({0, 1}, {0}), std::invalid_argument);
  EXPECT_THROW (pcl_crf::clusterAccuracy ({0, 1}, {0}), std::invalid_argument);
}

}  // namespace
