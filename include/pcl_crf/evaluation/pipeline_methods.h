#pragma once

#include <pcl_crf/evaluation/clustering_methods.h>
#include <pcl_crf/evaluation/method.h>

#include <functional>
#include <memory>
#include <string>

namespace pcl_crf {

/** \brief Builds a clustering method on the associations a provider gives; it must
 *  report them in Prediction::source_match (report_associations = true). */
using ClusteringFactory = std::function<std::unique_ptr<EvaluationMethod> (AssociationProvider)>;

/** \brief "Associations, then clustering": the Prediction::source_match of
 *  \a associations feeds the clustering \a clustering builds (the two stages unlinked,
 *  as the baselines of the joint paper, Tipaldi & Ramos, ICRA 2010).
 *
 *  Learned when a part is: train() trains the association method on the pairs, then
 *  the clustering on the pairs with the associations the trained method gives them;
 *  the model file holds every learned part (writeCompositeModel,
 *  "pcl_crf_composite_model 1"). Prediction: the clustering's, whose source_match is
 *  the association method's.
 *
 *  \code
 *  auto method = pcl_crf::makeAssociationPipeline ("crf-matching+kmeans", pcl_crf::makeCrfMatchingMethod (),
 *      [] (pcl_crf::AssociationProvider associations) {
 *        return pcl_crf::makeKMeansMethod ("kmeans", std::move (associations), true);
 *      });
 *  method->train (training_pairs);
 *  method->saveModel ("crf-matching+kmeans.model");
 *  \endcode
 *  \param[in] name the method's name
 *  \param[in] associations the association method (its source_match is used)
 *  \param[in] clustering builds the clustering method on the associations
 *  \throws std::invalid_argument when a part is missing
 */
std::unique_ptr<EvaluationMethod>
makeAssociationPipeline (const std::string& name, std::unique_ptr<EvaluationMethod> associations,
                         const ClusteringFactory& clustering);

/** \brief "icp+kmeans": PCL ICP's associations (runIcpBaseline), then K-Means.
 *  \param[in] cluster_count k > 0; 0: learned (as makeKMeansMethod) */
std::unique_ptr<EvaluationMethod>
makeIcpKMeansMethod (int cluster_count = 0);

/** \brief "crf-matching+kmeans": CRF-Matching's associations, then K-Means.
 *  \param[in] cluster_count k > 0; 0: learned (as makeKMeansMethod) */
std::unique_ptr<EvaluationMethod>
makeCrfMatchingKMeansMethod (int cluster_count = 0);

/** \brief "crf-m": CRF-Matching's associations, then CRF-Clustering learned on them
 *  (the joint paper's CRF-M: both CRFs, unlinked). */
std::unique_ptr<EvaluationMethod>
makeCrfMMethod ();

}  // namespace pcl_crf
