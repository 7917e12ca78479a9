#include <pcl_crf/metrics/summary.h>

#include <cmath>
#include <limits>

namespace pcl_crf {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

/** The non-NaN values of one field over all pairs. */
std::vector<double>
valuesOf (const std::vector<PairScores>& scores, double PairScores::*field)
{
  std::vector<double> values;
  for (const auto& pair : scores)
    if (!std::isnan (pair.*field))
      values.push_back (pair.*field);
  return values;
}

double
mean (const std::vector<double>& values)
{
  if (values.empty ())
    return kNaN;
  double sum = 0.0;
  for (const double value : values)
    sum += value;
  return sum / static_cast<double> (values.size ());
}

/** sqrt (sum (x - mean)^2 / count): population, not sample, deviation. */
double
populationStddev (const std::vector<double>& values, double mean)
{
  if (values.empty ())
    return kNaN;
  double sum_of_squares = 0.0;
  for (const double value : values)
    sum_of_squares += (value - mean) * (value - mean);
  return std::sqrt (sum_of_squares / static_cast<double> (values.size ()));
}

}  // namespace

const std::vector<MetricField>&
metricFields ()
{
  static const std::vector<MetricField> fields = {
      {"association_accuracy", "fraction", &PairScores::association_accuracy},
      {"association_accuracy_tolerance", "fraction", &PairScores::association_accuracy_tolerance},
      {"association_sed", "edits", &PairScores::association_sed},
      {"predicted_outlier_pct", "%", &PairScores::predicted_outlier_pct},
      {"true_outlier_pct", "%", &PairScores::true_outlier_pct},
      {"found_outlier_pct", "%", &PairScores::found_outlier_pct},
      {"homogeneity", "score", &PairScores::homogeneity},
      {"completeness", "score", &PairScores::completeness},
      {"v_measure", "score", &PairScores::v_measure},
      {"cluster_accuracy", "fraction", &PairScores::cluster_accuracy},
      {"cluster_sed", "edits", &PairScores::cluster_sed},
      {"clusters_found", "count", &PairScores::clusters_found},
      {"objects_true", "count", &PairScores::objects_true},
      {"static_rotation_error", "rad", &PairScores::static_rotation_error},
      {"static_translation_error", "m", &PairScores::static_translation_error},
      {"moving_rotation_error", "rad", &PairScores::moving_rotation_error},
      {"moving_translation_error", "m", &PairScores::moving_translation_error},
      {"ego_rotation_error", "rad", &PairScores::ego_rotation_error},
      {"ego_translation_error", "m", &PairScores::ego_translation_error},
      {"seconds", "s", &PairScores::seconds},
  };
  return fields;
}

std::vector<MetricSummary>
summarize (const std::vector<PairScores>& scores)
{
  std::vector<MetricSummary> rows;
  for (const auto& field : metricFields ()) {
    const std::vector<double> values = valuesOf (scores, field.value);
    const double average = mean (values);
    rows.push_back ({field.name, field.unit, average, populationStddev (values, average),
                     static_cast<int> (values.size ())});
  }
  return rows;
}

}  // namespace pcl_crf
