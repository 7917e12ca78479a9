#include <pcl_crf/metrics/summary.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const pcl_crf::MetricSummary&
rowNamed (const std::vector<pcl_crf::MetricSummary>& rows, const std::string& name)
{
  for (const auto& row : rows)
    if (row.name == name)
      return row;
  throw std::runtime_error ("no summary row " + name);
}

TEST (MetricsSummary, MeanAndPopulationStddevSkipNan)
{
  std::vector<pcl_crf::PairScores> scores (3);
  scores[0].association_accuracy = 0.2;
  scores[1].association_accuracy = 0.4;  // scores[2] stays NaN
  scores[0].seconds = 1.0;
  scores[1].seconds = 2.0;
  scores[2].seconds = 6.0;
  const auto rows = pcl_crf::summarize (scores);

  // (0.2 + 0.4) / 2 = 0.3; deviations +-0.1 -> sqrt ((0.01 + 0.01) / 2) = 0.1.
  const auto& accuracy = rowNamed (rows, "association_accuracy");
  EXPECT_NEAR (accuracy.mean, 0.3, 1e-12);
  EXPECT_NEAR (accuracy.stddev, 0.1, 1e-12);
  EXPECT_EQ (accuracy.count, 2);
  EXPECT_EQ (accuracy.unit, "fraction");

  // (1 + 2 + 6) / 3 = 3; deviations -2, -1, 3 -> sqrt ((4 + 1 + 9) / 3) = sqrt (14 / 3) = 2.160247.
  const auto& seconds = rowNamed (rows, "seconds");
  EXPECT_DOUBLE_EQ (seconds.mean, 3.0);
  EXPECT_NEAR (seconds.stddev, 2.160247, 1e-6);
  EXPECT_EQ (seconds.count, 3);
  EXPECT_EQ (seconds.unit, "s");

  const auto& never = rowNamed (rows, "v_measure");
  EXPECT_EQ (never.count, 0);
  EXPECT_TRUE (std::isnan (never.mean));
  EXPECT_TRUE (std::isnan (never.stddev));
}

TEST (MetricsSummary, OneRowPerFieldInDeclarationOrder)
{
  pcl_crf::PairScores s;
  s.association_accuracy = 1;
  s.association_accuracy_tolerance = 2;
  s.association_sed = 3;
  s.predicted_outlier_pct = 4;
  s.true_outlier_pct = 5;
  s.found_outlier_pct = 6;
  s.homogeneity = 7;
  s.completeness = 8;
  s.v_measure = 9;
  s.cluster_accuracy = 10;
  s.cluster_sed = 11;
  s.clusters_found = 12;
  s.objects_true = 13;
  s.static_rotation_error = 14;
  s.static_translation_error = 15;
  s.moving_rotation_error = 16;
  s.moving_translation_error = 17;
  s.ego_rotation_error = 18;
  s.ego_translation_error = 19;
  s.seconds = 20;
  const auto rows = pcl_crf::summarize ({s});
  ASSERT_EQ (rows.size (), 20u);
  for (std::size_t k = 0; k < rows.size (); ++k) {
    EXPECT_DOUBLE_EQ (rows[k].mean, static_cast<double> (k + 1)) << rows[k].name;
    EXPECT_DOUBLE_EQ (rows[k].stddev, 0.0) << rows[k].name;
    EXPECT_EQ (rows[k].count, 1) << rows[k].name;
  }
  EXPECT_EQ (rows.front ().name, "association_accuracy");
  EXPECT_EQ (rows[12].name, "objects_true");
  EXPECT_EQ (rows[17].name, "ego_rotation_error");
  EXPECT_EQ (rows[17].unit, "rad");
  EXPECT_EQ (rows.back ().name, "seconds");
}

TEST (MetricsSummary, NoPairsGiveNanRowsWithZeroCount)
{
  const auto rows = pcl_crf::summarize ({});
  ASSERT_EQ (rows.size (), pcl_crf::metricFields ().size ());
  for (const auto& row : rows) {
    EXPECT_EQ (row.count, 0) << row.name;
    EXPECT_TRUE (std::isnan (row.mean)) << row.name;
  }
}

}  // namespace
