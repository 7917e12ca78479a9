#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Splits points given in scan order into contiguous segments: a new
 *  segment starts where two consecutive points are farther apart than
 *  \a break_distance, or where the current segment already holds
 *  \a max_segment_points points. This is the deliberately over-segmenting
 *  initialisation of CRF-Clustering (Tipaldi & Ramos, IROS 2009, Sec. IV-D) and
 *  the distance segmentation of the consistency-based detector.
 *
 *  \code
 *  const std::vector<int> segment = pcl_crf::clustering::segmentByDistance (pairs.source, 0.5, 20);
 *  \endcode
 *  \param[in] points 2 x n points in scan order [m]
 *  \param[in] break_distance gap that starts a new segment [m], > 0
 *  \param[in] max_segment_points longest segment [points]; ≤ 0: unlimited
 *  \return segment of every point, 0, 1, ... in scan order
 *  \throws std::invalid_argument when break_distance is not > 0.
 */
std::vector<int>
segmentByDistance (const Eigen::Matrix2Xd& points, double break_distance, int max_segment_points = 0);

/** \brief Joins consecutive segments until at most \a max_segments remain: the
 *  segments stay apart at their \a max_segments − 1 widest breaks (the distance
 *  between the last point of a segment and the first of the next; of equal ones the
 *  first in scan order), and are joined at every other break.
 *
 *  \code
 *  std::vector<int> segment = pcl_crf::clustering::segmentByDistance (points, 0.5, 20);
 *  pcl_crf::clustering::mergeNarrowestBreaks (points, 256, segment);
 *  \endcode
 *  \param[in] points 2 x n points in scan order [m]
 *  \param[in] max_segments the most segments to keep, ≥ 1
 *  \param[in,out] segment segment of every point, 0, 1, ... in scan order (as
 *  segmentByDistance () gives), renumbered 0, 1, ... in scan order
 *  \throws std::invalid_argument when \a segment is not one non-decreasing run
 *  0, 1, ... per point or \a max_segments < 1.
 */
void
mergeNarrowestBreaks (const Eigen::Matrix2Xd& points, int max_segments, std::vector<int>& segment);

/** \brief Labels every point of a scan from the labels of some of its points
 *  (the CRF nodes), for the points that have no node (no association).
 *
 *  A point without a label takes the label of the nearer (in space) of the
 *  closest labelled points before and after it in scan order, provided no gap
 *  wider than \a break_distance separates them along the scan; a point cut off
 *  from every labelled point by such gaps gets \a default_label (callers pass the
 *  static world: what no association explains is assumed to stand still, as the
 *  consistency-based detector assumes for unknown points).
 *
 *  \param[in] scan 2 x N scan in scan order [m]
 *  \param[in] labelled_index scan index of every labelled point, increasing
 *  \param[in] labels label of every labelled point
 *  \param[in] break_distance gap that separates segments [m], > 0
 *  \param[in] default_label label of points in segments without a labelled point
 *  \return label of every scan point
 *  \throws std::invalid_argument for a size mismatch, an index out of range or
 *  not increasing, or break_distance not > 0.
 */
std::vector<int>
completeLabels (const Eigen::Matrix2Xd& scan, const std::vector<int>& labelled_index,
                const std::vector<int>& labels, double break_distance, int default_label);

/** \brief completeLabels () within segments given per point: every point labelled
 *  \a unlabelled takes the label of the nearer (in space) of the closest labelled points
 *  before and after it in scan order on its segment, and keeps \a unlabelled when its
 *  segment has none.
 *  \param[in] scan 2 x N scan in scan order [m]
 *  \param[in] segment the segment of every point (runs of equal values)
 *  \param[in] labels the label of every point, \a unlabelled for those to complete
 *  \throws std::invalid_argument when \a segment or \a labels is not one per point. */
std::vector<int>
completeLabelsWithinSegments (const Eigen::Matrix2Xd& scan, const std::vector<int>& segment,
                              const std::vector<int>& labels, int unlabelled);

}  // namespace clustering
}  // namespace pcl_crf
