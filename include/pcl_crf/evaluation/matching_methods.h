#pragma once

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/matching/matching_model.h>

#include <memory>

namespace pcl_crf {

/** \brief "icp": PCL's IterativeClosestPoint from the odometry guess
 *  (runIcpBaseline, pcl_crf/baselines/icp_baseline.h): its correspondences as
 *  source_match, one static cluster; learns nothing. */
std::unique_ptr<EvaluationMethod>
makeIcpMethod ();

/** \brief CRF-Matching (Ramos, Fox & Durrant-Whyte, RSS 2007) as an evaluation
 *  method named "crf-matching": learned (train / saveModel / loadModel).
 *
 *  Its Prediction: source_match = the MAP association (kNoMatch for outliers);
 *  one cluster (0, the static cluster) holding every matched point with the
 *  estimated motion, unmatched points in kOutlierCluster; T_source_target = the
 *  inverse of the estimated T_target_source.
 *
 *  \code
 *  auto method = pcl_crf::makeCrfMatchingMethod ();
 *  method->train (pcl_crf::loadDataset ("data/default/train"));
 *  method->saveModel ("crf-matching.model");
 *  const pcl_crf::Prediction prediction = method->predict (pair);
 *  \endcode
 *  \param[in] parameters the settings used by train() (a loaded model brings its own)
 */
std::unique_ptr<EvaluationMethod>
makeCrfMatchingMethod (const matching::MatchingParameters& parameters = {});

}  // namespace pcl_crf
