#include <pcl_crf/metrics/contingency_table.h>
#include <pcl_crf/metrics/v_measure.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

/** H(R) = -sum_r (a_r / n) log (a_r / n), natural log. */
double
entropyOfRows (const ContingencyTable& table)
{
  const double n = static_cast<double> (table.total ());
  double entropy = 0.0;
  for (const auto& row : table.rowTotals ()) {
    const double p = static_cast<double> (row.second) / n;
    entropy -= p * std::log (p);
  }
  return entropy;
}

/** H(R|C) = -sum_{r,c} (a_rc / n) log (a_rc / a_c), natural log. */
double
conditionalEntropyOfRows (const ContingencyTable& table)
{
  const double n = static_cast<double> (table.total ());
  double entropy = 0.0;
  for (const auto& cell : table.cells ()) {
    const double a_rc = static_cast<double> (cell.second);
    const double a_c = static_cast<double> (table.columnTotals ().at (cell.first.second));
    entropy -= (a_rc / n) * std::log (a_rc / a_c);
  }
  return entropy;
}

/** 1 - H(R|C) / H(R), and 1 when H(R) = 0: Rosenberg & Hirschberg's homogeneity h
 *  (rows = classes, columns = clusters) and completeness c (rows = clusters).
 */
double
oneMinusNormalisedConditionalEntropy (const ContingencyTable& table)
{
  const double entropy = entropyOfRows (table);
  if (entropy <= 0.0)
    return 1.0;
  // H(R|C) <= H(R); the clamp only removes rounding below 0.
  return std::max (0.0, 1.0 - conditionalEntropyOfRows (table) / entropy);
}

/** V_beta = (1 + beta) h c / (beta h + c), 0 when the denominator is 0. */
double
weightedHarmonicMean (double homogeneity, double completeness, double beta)
{
  const double denominator = beta * homogeneity + completeness;
  if (denominator <= 0.0)
    return 0.0;
  return (1.0 + beta) * homogeneity * completeness / denominator;
}

void
checkInput (const std::vector<int>& classes, const std::vector<int>& clusters, double beta)
{
  if (classes.size () != clusters.size ())
    throw std::invalid_argument ("[pcl_crf::computeVMeasure] " + std::to_string (classes.size ()) +
                                 " class labels but " + std::to_string (clusters.size ()) +
                                 " cluster labels; give one of each per item");
  if (classes.empty ())
    throw std::invalid_argument ("[pcl_crf::computeVMeasure] no items to score");
  if (!std::isfinite (beta) || beta < 0.0)
    throw std::invalid_argument (
        "[pcl_crf::computeVMeasure] beta must be a finite number >= 0, got " +
        std::to_string (beta));
}

}  // namespace

VMeasure
computeVMeasure (const std::vector<int>& classes, const std::vector<int>& clusters, double beta)
{
  checkInput (classes, clusters, beta);
  VMeasure score;
  score.homogeneity = oneMinusNormalisedConditionalEntropy (ContingencyTable (classes, clusters));
  score.completeness = oneMinusNormalisedConditionalEntropy (ContingencyTable (clusters, classes));
  score.v = weightedHarmonicMean (score.homogeneity, score.completeness, beta);
  return score;
}

}  // namespace pcl_crf
