#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/metrics/association_metrics.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace {

using pcl_crf::kNoMatch;

// Target points t0 = (0, 0), t1 = (0.05, 0), t2 = (1, 0), t3 = (2, 0).
Eigen::Matrix2Xd
fourTargetPoints ()
{
  Eigen::Matrix2Xd target (2, 4);
  target << 0.0, 0.05, 1.0, 2.0,
            0.0, 0.0, 0.0, 0.0;
  return target;
}

// Five source points:        p0  p1  p2        p3        p4
const std::vector<int> kTruth = {0, 2, kNoMatch, 3, kNoMatch};
const std::vector<int> kPredicted = {1, 2, kNoMatch, kNoMatch, 0};

TEST (MetricsAssociation, ExactAccuracyCountsEqualMatches)
{
  // p1 equal, p2 none == none: 2 of 5.
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracy (kPredicted, kTruth), 0.4);
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracy (kTruth, kTruth), 1.0);
}

TEST (MetricsAssociation, ToleranceAcceptsNearbyTargetPoint)
{
  // p0 predicts t1, 0.05 m from its true t0: correct within 0.1 m -> 3 of 5.
  // p3 (none vs t3) and p4 (t0 vs none) stay wrong whatever the tolerance.
  const Eigen::Matrix2Xd target = fourTargetPoints ();
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracyWithin (kPredicted, kTruth, target, 0.1), 0.6);
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracyWithin (kPredicted, kTruth, target, 0.05), 0.6);
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracyWithin (kPredicted, kTruth, target, 0.01), 0.4);
  EXPECT_DOUBLE_EQ (pcl_crf::associationAccuracyWithin (kPredicted, kTruth, target, 100.0), 0.6);
}

TEST (MetricsAssociation, OutlierPercentages)
{
  // predicted none: p2, p3 -> 2/5 = 40 %; true none: p2, p4 -> 40 %;
  // of the true outliers {p2, p4} only p2 is predicted none -> 50 %.
  const pcl_crf::OutlierStatistics stats = pcl_crf::computeOutlierStatistics (kPredicted, kTruth);
  EXPECT_DOUBLE_EQ (stats.predicted_pct, 40.0);
  EXPECT_DOUBLE_EQ (stats.true_pct, 40.0);
  EXPECT_DOUBLE_EQ (stats.found_pct, 50.0);
}

TEST (MetricsAssociation, FoundOutliersIsNanWithoutTrueOutliers)
{
  const pcl_crf::OutlierStatistics stats =
      pcl_crf::computeOutlierStatistics ({kNoMatch, 1, 2, 3}, {0, 1, 2, 3});
  EXPECT_DOUBLE_EQ (stats.predicted_pct, 25.0);
  EXPECT_DOUBLE_EQ (stats.true_pct, 0.0);
  EXPECT_TRUE (std::isnan (stats.found_pct));
}

TEST (MetricsAssociation, NoPointsGiveNan)
{
  EXPECT_TRUE (std::isnan (pcl_crf::associationAccuracy ({}, {})));
  EXPECT_TRUE (std::isnan (pcl_crf::outlierPercentage ({})));
}

TEST (MetricsAssociation, SizeMismatchThrows)
{
  EXPECT_THROW (pcl_crf::associationAccuracy ({0, 1}, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW (pcl_crf::computeOutlierStatistics ({0}, {0, 1}), std::invalid_argument);
  EXPECT_THROW (pcl_crf::associationAccuracyWithin ({0}, {0, 1}, fourTargetPoints (), 0.1),
                std::invalid_argument);
}

TEST (MetricsAssociation, OutOfRangeTargetIndexThrows)
{
  EXPECT_THROW (pcl_crf::associationAccuracyWithin ({4}, {0}, fourTargetPoints (), 0.1),
                std::invalid_argument);
  EXPECT_THROW (pcl_crf::associationAccuracyWithin ({0}, {-2}, fourTargetPoints (), 0.1),
                std::invalid_argument);
}

}  // namespace
