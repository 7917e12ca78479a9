#pragma once

#include <pcl_crf/core/scan_pair.h>  // kNoMatch

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {

/** \brief Fraction of source points whose predicted match equals the true
 *  match; kNoMatch against kNoMatch counts as correct.
 *  \param[in] predicted predicted target index (or kNoMatch) of every source point
 *  \param[in] truth true target index (or kNoMatch) of every source point
 *  \return a value in [0, 1]; NaN when there are no points.
 *  \throws std::invalid_argument when the lengths differ.
 */
double
associationAccuracy (const std::vector<int>& predicted, const std::vector<int>& truth);

/** \brief Like associationAccuracy, but a predicted match j also counts as
 *  correct when the true match j* is not kNoMatch and
 *  ||target(:, j) - target(:, j*)|| <= tolerance.
 *  \param[in] predicted predicted target index (or kNoMatch) of every source point
 *  \param[in] truth true target index (or kNoMatch) of every source point
 *  \param[in] target the target scan the indices refer to
 *  \param[in] tolerance largest distance between the two target points [m]
 *  \return a value in [0, 1]; NaN when there are no points.
 *  \throws std::invalid_argument when the lengths differ or an index is
 *          neither kNoMatch nor a column of \a target.
 */
double
associationAccuracyWithin (const std::vector<int>& predicted, const std::vector<int>& truth,
                           const Eigen::Matrix2Xd& target, double tolerance);

/** \brief Outlier counts of an association, as in the tables of the joint
 *  scan-matching / motion-detection paper. All values are percentages in [0, 100].
 */
struct OutlierStatistics
{
  /** source points predicted as kNoMatch, over all source points [%]. */
  double predicted_pct;
  /** source points truly kNoMatch, over all source points [%]. */
  double true_pct;
  /** source points predicted AND truly kNoMatch, over the truly kNoMatch
   *  ones [%]; NaN when there is no true outlier.
   */
  double found_pct;
};

/** \brief Outlier percentages of a predicted association against the truth.
 *  Every value is NaN when there are no points.
 *  \throws std::invalid_argument when the lengths differ.
 */
OutlierStatistics
computeOutlierStatistics (const std::vector<int>& predicted, const std::vector<int>& truth);

/** \brief Percentage [0, 100] of kNoMatch entries of \a matches; NaN when empty. */
double
outlierPercentage (const std::vector<int>& matches);

}  // namespace pcl_crf
