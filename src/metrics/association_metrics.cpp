#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/metrics/association_metrics.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

void
checkSameLength (const std::vector<int>& predicted, const std::vector<int>& truth,
                 const char* function)
{
  if (predicted.size () != truth.size ())
    throw std::invalid_argument (std::string ("[pcl_crf::") + function + "] " +
                                 std::to_string (predicted.size ()) + " predicted matches but " +
                                 std::to_string (truth.size ()) + " true matches");
}

void
checkTargetIndex (int index, const Eigen::Matrix2Xd& target)
{
  if (index != kNoMatch && (index < 0 || index >= target.cols ()))
    throw std::invalid_argument ("[pcl_crf::associationAccuracyWithin] target index " +
                                 std::to_string (index) + " is out of range [0, " +
                                 std::to_string (target.cols ()) + ") and not kNoMatch");
}

bool
isWithinTolerance (int predicted, int truth, const Eigen::Matrix2Xd& target, double tolerance)
{
  if (predicted == truth)
    return true;
  if (predicted == kNoMatch || truth == kNoMatch)
    return false;
  return (target.col (predicted) - target.col (truth)).norm () <= tolerance;
}

double
percentage (std::size_t part, std::size_t whole)
{
  return whole == 0 ? kNaN : 100.0 * static_cast<double> (part) / static_cast<double> (whole);
}

}  // namespace

double
associationAccuracy (const std::vector<int>& predicted, const std::vector<int>& truth)
{
  checkSameLength (predicted, truth, "associationAccuracy");
  if (truth.empty ())
    return kNaN;
  std::size_t correct = 0;
  for (std::size_t i = 0; i < truth.size (); ++i)
    correct += predicted[i] == truth[i] ? 1 : 0;
  return static_cast<double> (correct) / static_cast<double> (truth.size ());
}

double
associationAccuracyWithin (const std::vector<int>& predicted, const std::vector<int>& truth,
                           const Eigen::Matrix2Xd& target, double tolerance)
{
  checkSameLength (predicted, truth, "associationAccuracyWithin");
  if (truth.empty ())
    return kNaN;
  std::size_t correct = 0;
  for (std::size_t i = 0; i < truth.size (); ++i) {
    checkTargetIndex (predicted[i], target);
    checkTargetIndex (truth[i], target);
    correct += isWithinTolerance (predicted[i], truth[i], target, tolerance) ? 1 : 0;
  }
  return static_cast<double> (correct) / static_cast<double> (truth.size ());
}

double
outlierPercentage (const std::vector<int>& matches)
{
  std::size_t outliers = 0;
  for (const int match : matches)
    outliers += match == kNoMatch ? 1 : 0;
  return percentage (outliers, matches.size ());
}

OutlierStatistics
computeOutlierStatistics (const std::vector<int>& predicted, const std::vector<int>& truth)
{
  checkSameLength (predicted, truth, "computeOutlierStatistics");
  std::size_t true_outliers = 0;
  std::size_t found_outliers = 0;
  for (std::size_t i = 0; i < truth.size (); ++i) {
    if (truth[i] != kNoMatch)
      continue;
    ++true_outliers;
    found_outliers += predicted[i] == kNoMatch ? 1 : 0;
  }
  return {outlierPercentage (predicted), outlierPercentage (truth),
          percentage (found_outliers, true_outliers)};
}

}  // namespace pcl_crf
