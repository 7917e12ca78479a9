#pragma once

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief Rows of the per-point shape descriptor of a scan (computeShapeFeatures).
 *
 *  The local shape around point i of a scan in beam order, at the neighbour
 *  offsets k = 1, 3, 5 (the CRF-Matching features of Ramos, Fox & Durrant-Whyte,
 *  RSS 2007, Sec. IV-A; the joint paper, ICRA 2010, Sec. IV-C 1):
 *  - distance ||p_i − p_{i∓k}|| to the k-th neighbour before / after i [m];
 *  - turning angle between the directions p_i − p_{i−k} and p_{i+k} − p_i [rad],
 *    signed in (−π, π], 0 on a straight line;
 *  - geodesic distance Σ ||p_{m+1} − p_m|| along the scan to the k-th neighbour
 *    before / after i [m];
 *  - radius ||p_i|| (range from the sensor) [m].
 *  Neighbour indices are clamped to the scan ends.
 */
enum ShapeFeature : int
{
  kDistanceBefore1 = 0,
  kDistanceAfter1,
  kDistanceBefore3,
  kDistanceAfter3,
  kDistanceBefore5,
  kDistanceAfter5,
  kAngle1,
  kAngle3,
  kAngle5,
  kGeodesicBefore1,
  kGeodesicAfter1,
  kGeodesicBefore3,
  kGeodesicAfter3,
  kGeodesicBefore5,
  kGeodesicAfter5,
  kRadius,
  kShapeFeatureCount
};

/** \brief The neighbour offsets k of the descriptor, in row order. */
constexpr int kShapeOffsets[3] = {1, 3, 5};

/** \brief Shape descriptor of every point of a scan.
 *  \param[in] scan 2 x N points in beam order, in the scan's sensor frame [m]
 *  \return kShapeFeatureCount x N matrix, column i describing point i (see ShapeFeature)
 *
 *  \code
 *  const Eigen::MatrixXd shape = pcl_crf::matching::computeShapeFeatures (pair.source);
 *  const double corner = shape (pcl_crf::matching::kAngle3, 42);   // turning angle at point 42 [rad]
 *  \endcode
 */
Eigen::MatrixXd
computeShapeFeatures (const Eigen::Matrix2Xd& scan);

}  // namespace matching
}  // namespace pcl_crf
