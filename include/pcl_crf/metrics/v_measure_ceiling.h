#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <vector>

namespace pcl_crf {

/** \brief The labels of an oracle that finds every object of at least \a min_points
 *  items exactly and leaves every smaller object in \a background (the static world).
 *  \param[in] objects the true object of every item
 *  \param[in] min_points the smallest object the oracle finds, >= 1 (1 finds all)
 *  \param[in] background the label smaller objects take
 *  \throws std::invalid_argument when \a min_points < 1.
 *
 *  \code
 *  pcl_crf::labelsWithoutSmallObjects ({0, 0, 0, 1, 1, 2}, 2, 0);  // {0, 0, 0, 1, 1, 0}
 *  \endcode
 */
std::vector<int>
labelsWithoutSmallObjects (const std::vector<int>& objects, int min_points, int background);

/** \brief How far V can go on a dataset for a method that never finds objects smaller
 *  than min_points source points: the mean over the pairs of
 *  V (truth, labelsWithoutSmallObjects (truth, min_points, static object)).
 *
 *  V rewards finding small movers as much as large ones (a pair whose only mover has two
 *  points scores V = 0 when the mover is left in the static world), so this says which
 *  V a dataset allows once the movers too small to observe are given up.
 */
struct VMeasureCeiling
{
  /** the smallest object the oracle finds [source points]. */
  int min_points = 1;
  /** its V averaged over the pairs (as pcl_crf_eval averages a method's). */
  double mean_v = 0.0;
  /** the pairs where its V reaches the threshold given to vMeasureCeilings (). */
  int pairs_reaching = 0;
};

/** \brief One VMeasureCeiling per entry of \a min_points over the labelled \a pairs.
 *  \param[in] pairs labelled scan pairs (each with one object label per source point)
 *  \param[in] min_points the oracles' smallest objects, each >= 1
 *  \param[in] threshold the V counted as reached (pairs_reaching), e.g. 0.95
 *  \throws std::invalid_argument when \a pairs is empty, a pair has no labels for its
 *          source points or no points, or a min_points is < 1. */
std::vector<VMeasureCeiling>
vMeasureCeilings (const std::vector<ScanPair>& pairs, const std::vector<int>& min_points, double threshold);

}  // namespace pcl_crf
