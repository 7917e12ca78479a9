#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {

/** \brief Per point of \a points (the columns of a 2 x N scan, or of any d x N matrix):
 *  the index of the first point with exactly its coordinates, its own index for the
 *  first of its copies (0 and −0 alike).
 *
 *  A laser measures one return per beam, so a point repeated exactly is no return of
 *  its own: a converter's placeholder for a beam without one, or a scan copied into
 *  itself. The estimators work on the first copies and give the others their results
 *  (joint::estimateJoint (), matching::matchScans () at the model's resolution); tens
 *  of thousands of copies of one point otherwise made hundreds of clusters of it, and
 *  copies between the returns of a scan changed a sixth of CRF-Matching's matches.
 *
 *  \code
 *  const std::vector<int> first = pcl_crf::firstOfEqualPoints (scan);
 *  if (pcl_crf::repeatsAPoint (first)) ...   // some point is a copy of an earlier one
 *  \endcode
 */
std::vector<int>
firstOfEqualPoints (const Eigen::Ref<const Eigen::MatrixXd>& points);

/** \brief Whether \a first (firstOfEqualPoints ()) names a point that repeats an earlier one. */
bool
repeatsAPoint (const std::vector<int>& first);

/** \brief The indices of the first copies in \a first (firstOfEqualPoints ()), increasing. */
std::vector<int>
firstCopies (const std::vector<int>& first);

/** \brief Per point of \a first (firstOfEqualPoints ()): the column its first copy holds
 *  among the first copies alone (firstCopies ()), where a result on them is found.
 *  \throws std::invalid_argument when an entry is not a first copy at or before its point. */
std::vector<int>
firstCopyColumns (const std::vector<int>& first);

}  // namespace pcl_crf
