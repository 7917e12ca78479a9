#pragma once

#include <pcl_crf/matching/pass_geometry.h>
#include <pcl_crf/matching/shape_features.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief Rows of the raw features of a (source point i, candidate j) pair, the
 *  input of the data-boosting classifier (joint paper, Sec. IV-C 1):
 *  rows 0 … kShapeFeatureCount − 1 hold |shape_i − shape_j| per ShapeFeature
 *  (distances, angles wrapped to [0, π], geodesic distances, radius), then
 *  - translation ||T_guess s_i − t_j|| [m],
 *  - registered translation ||T_current s_i − t_j|| [m],
 *  - registered excess: the registered translation minus the smallest one among
 *    i's candidates [m] (0 for the nearest target point under T_current),
 *  - motion residual: the smaller of the registered translation and
 *    ||T_current s_i + h_i − t_j||, h_i the segment motion hypothesis of i [m],
 *  - motion excess: the motion residual minus the smallest one among i's candidates [m],
 *  - segment displacement ||h_i|| (0 without a hypothesis) [m],
 *  - the fractions of i's segment explained by the current motion and by h_i
 *    (SegmentMotions::current_support, hypothesis_support).
 */
enum DataFeature : int
{
  kTranslation = kShapeFeatureCount,
  kRegisteredTranslation,
  kRegisteredExcess,
  kMotionResidual,
  kMotionExcess,
  kSegmentDisplacement,
  kSegmentCurrentSupport,
  kSegmentHypothesisSupport,
  kDataFeatureCount
};

/** \brief Rows of the raw features of a source point i, the input of the
 *  outlier-boosting classifier.
 */
enum OutlierFeature : int
{
  kNearestGuessDistance = 0,       ///< min over the candidates of the translation [m]
  kNearestRegisteredDistance,      ///< min over the candidates of the registered translation [m]
  kSourceRadius,                   ///< ||s_i|| [m]
  kSourceDistanceBefore1,          ///< distance to the previous point [m]
  kSourceDistanceAfter1,           ///< distance to the next point [m]
  kSourceAbsoluteAngle3,           ///< |turning angle| at offset 3 [rad]
  kBestDataMargin,                 ///< max over the candidates of the data-boosting margin
  kNearestMotionResidual,          ///< min over the candidates of the motion residual [m]
  kOutlierSegmentDisplacement,     ///< ||h_i||, the segment displacement [m]
  kOutlierCurrentSupport,          ///< SegmentMotions::current_support of i
  kOutlierHypothesisSupport,       ///< SegmentMotions::hypothesis_support of i
  kOutlierFeatureCount
};

/** \brief Raw features of every (source point, candidate) pair of a pass.
 *
 *  \code
 *  const Eigen::MatrixXd data = pcl_crf::matching::dataFeatures (source, target.scan, pass);
 *  const double t = data (pcl_crf::matching::kRegisteredTranslation, pass.candidates.offsets[i]);
 *  \endcode
 *  \return kDataFeatureCount x (total candidates); column c is the pair
 *  (i, pass.candidates.targets[c]) for offsets[i] ≤ c < offsets[i + 1]
 */
Eigen::MatrixXd
dataFeatures (const ScanShape& source, const ScanShape& target, const PassGeometry& pass);

/** \brief Raw features of every source point of a pass.
 *  \param[in] data_features dataFeatures of the pass
 *  \param[in] data_margins data-boosting margin of every candidate (same order)
 *  \return kOutlierFeatureCount x (source points)
 */
Eigen::MatrixXd
outlierFeatures (const ScanShape& source, const PassGeometry& pass, const Eigen::MatrixXd& data_features,
                 const Eigen::VectorXd& data_margins);

}  // namespace matching
}  // namespace pcl_crf
