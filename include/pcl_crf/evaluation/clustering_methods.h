#pragma once

#include <pcl_crf/clustering/consistency_detection.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/evaluation/method.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Gives the associations a clustering method works on: per source point the
 *  index of its target point or kNoMatch (the form of ScanPair::source_match). */
using AssociationProvider = std::function<std::vector<int> (const ScanPair&)>;

/** \brief CRF-Clustering (Tipaldi & Ramos, IROS 2009) on the associations of
 *  \a associations, as an evaluation method named \a name; learned: train() runs
 *  maximum pseudo-likelihood on the provider's associations of the training pairs
 *  labelled with their true objects (so the weights see the association errors they
 *  will meet), the prior chosen by cross-validation (clustering::learnWithCrossValidation);
 *  saveModel / loadModel use the clustering::CrfClusteringModel text format.
 *
 *  Prediction: source_cluster for every source point (points without an association
 *  take the cluster of the nearest clustered point of their distance segment, or the
 *  static cluster), the clusters' motions, the static cluster nearest to the odometry,
 *  T_source_target = the inverse of the static motion; source_match = the associations
 *  when \a report_associations, else empty.
 *
 *  \code
 *  auto crf_m = pcl_crf::makeCrfClusteringMethod ("crf-m", [&matcher] (const pcl_crf::ScanPair& pair) {
 *    return matcher.match (pair);   // any association method
 *  }, true);
 *  crf_m->loadModel ("data/models/crf-t.model");
 *  const pcl_crf::Prediction prediction = crf_m->predict (pair);
 *  \endcode
 *  \param[in] name the method's name
 *  \param[in] associations the associations of each pair
 *  \param[in] report_associations copy the associations into Prediction::source_match
 *  \param[in] parameters the inference settings (a loaded model brings its feature settings)
 */
std::unique_ptr<EvaluationMethod>
makeCrfClusteringMethod (const std::string& name, AssociationProvider associations, bool report_associations,
                         const clustering::CrfClusteringParameters& parameters = {});

/** \brief "crf-t": CRF-Clustering given the true associations (ScanPair::source_match). */
std::unique_ptr<EvaluationMethod>
makeCrfClusteringTrueAssociationsMethod (const clustering::CrfClusteringParameters& parameters = {});

/** \brief "kmeans": the modified K-Means of Sec. V-C on the true associations, the
 *  static cluster nearest to the odometry, points without an association labelled as
 *  by CRF-Clustering.
 *  \param[in] cluster_count k > 0; 0: learned, k = the largest number of objects
 *             among the associated points of one training pair (train(), or a model
 *             file "pcl_crf_kmeans_model 1" / "cluster_count K")
 */
std::unique_ptr<EvaluationMethod>
makeKMeansMethod (int cluster_count = 0);

/** \brief The modified K-Means of Sec. V-C on the associations of \a associations, as
 *  an evaluation method named \a name (k and its model file as makeKMeansMethod (int);
 *  a learned k still comes from the training pairs' true objects).
 *
 *  \code
 *  // runIcpBaseline: #include <pcl_crf/baselines/icp_baseline.h>
 *  auto icp_kmeans = pcl_crf::makeKMeansMethod ("icp+kmeans", [] (const pcl_crf::ScanPair& pair) {
 *    return pcl_crf::runIcpBaseline (pair).source_match;
 *  }, true);
 *  \endcode
 *  \param[in] name the method's name
 *  \param[in] associations the associations of each pair
 *  \param[in] report_associations copy the associations into Prediction::source_match
 *  \param[in] cluster_count k > 0; 0: learned
 *  \throws std::invalid_argument when \a associations is empty
 */
std::unique_ptr<EvaluationMethod>
makeKMeansMethod (const std::string& name, AssociationProvider associations, bool report_associations,
                  int cluster_count = 0);

/** \brief Where the consistency-based detector takes the ego motion from. */
enum class EgoMotionSource
{
  /** the pair's odometry; its covariance widens the free-space test. */
  Odometry,
  /** PCL ICP started at the odometry (runIcpBaseline), as Wang et al. match scans first. */
  Icp
};

/** \brief "cbd": consistency-based detection (Wang et al., IJRR 2007): static cluster
 *  0 with the ego motion, one cluster per dynamic segment of the source scan (motion:
 *  identity, the detector does not estimate it).
 */
std::unique_ptr<EvaluationMethod>
makeConsistencyMethod (EgoMotionSource ego = EgoMotionSource::Odometry,
                       const clustering::ConsistencyParameters& parameters = {});

}  // namespace pcl_crf
