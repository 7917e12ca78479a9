#pragma once

#include <pcl_crf/crf/adaboost_stumps.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/pass_geometry.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief The boosted local evidence of one pass, the inputs of the CRF's unary
 *  features (Ramos et al., RSS 2007, Sec. IV-B: AdaBoost outputs as CRF features).
 *
 *  \code
 *  const pcl_crf::matching::BoostedScores scores =
 *      pcl_crf::matching::scorePass (model.stages[0], source, target.scan, pass);
 *  \endcode
 */
struct BoostedScores
{
  /** data-boosting margin H(x) of every candidate pair (flat, as Candidates::targets). */
  Eigen::VectorXd data_margins;
  /** outlier-boosting margin of every source point. */
  Eigen::VectorXd outlier_margins;
};

/** \brief The margin H(x) = Σ_t α_t h_t(x) of every column of \a features,
 *  one vectorised pass per stump (same values as AdaBoostStumps::margin).
 *  \throws std::invalid_argument when the classifier needs more rows than given. */
Eigen::VectorXd
boostedMargins (const crf::AdaBoostStumps& classifier, const Eigen::MatrixXd& features);

/** \brief Raw features and both classifiers' margins of a pass. */
BoostedScores
scorePass (const StageModel& stage, const ScanShape& source, const ScanShape& target, const PassGeometry& pass);

}  // namespace matching
}  // namespace pcl_crf
