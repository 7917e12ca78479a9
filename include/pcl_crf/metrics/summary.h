#pragma once

#include <pcl_crf/metrics/pair_scores.h>

#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Name, unit and location of one PairScores field. */
struct MetricField
{
  const char* name;
  const char* unit;
  double PairScores::*value;
};

/** \brief Every PairScores field, in declaration order, with its name (the
 *  field's identifier, e.g. "association_accuracy") and unit. Handy for tables
 *  and CSV columns.
 */
const std::vector<MetricField>&
metricFields ();

/** \brief One metric summarised over many scan pairs. */
struct MetricSummary
{
  std::string name;
  std::string unit;
  /** mean over the pairs where the metric is not NaN; NaN when count is 0. */
  double mean;
  /** population standard deviation over the same pairs; NaN when count is 0. */
  double stddev;
  /** number of pairs where the metric is not NaN. */
  int count;
};

/** \brief Mean and population standard deviation of every metric, NaN values
 *  skipped. One row per PairScores field, in the order of metricFields ().
 *
 *  \code
 *  for (const auto& row : pcl_crf::summarize (scores))
 *    std::cout << row.name << ": " << row.mean << " +- " << row.stddev << ' ' << row.unit << '\n';
 *  \endcode
 */
std::vector<MetricSummary>
summarize (const std::vector<PairScores>& scores);

}  // namespace pcl_crf
