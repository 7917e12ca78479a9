#pragma once

#include <pcl_crf/clustering/clustering_features.h>

#include <Eigen/Core>

#include <iosfwd>
#include <string>

namespace pcl_crf {
namespace clustering {

/** \brief Format version written in the first line of a CRF-Clustering model file. */
constexpr int kModelVersion = 1;

/** \brief A learned CRF-Clustering model: the weights and the feature settings they
 *  were learned with.
 *
 *  Text format (one `key value` per line, `#` starts a comment line):
 *  \code{.unparsed}
 *  pcl_crf_crf_clustering_model 1
 *  # learned with a Gaussian prior of sigma 10
 *  spacing_residual 0.0289
 *  beam_residual -3.28
 *  neighbour 0.0606
 *  weighted_neighbour 4.47
 *  stiffness -0.724
 *  min_neighbour_distance 0.01
 *  min_spacing 0.01
 *  \endcode
 *  \code
 *  pcl_crf::clustering::CrfClusteringModel model;
 *  model.weights = pcl_crf::clustering::learnWeights (chains).x;
 *  pcl_crf::clustering::saveModel (model, "crf-t.model");
 *  const auto loaded = pcl_crf::clustering::loadModel ("crf-t.model");
 *  \endcode
 */
struct CrfClusteringModel
{
  /** [w_spacing_residual, w_beam_residual, w_neighbour, w_weighted_neighbour, w_stiffness]. */
  Eigen::VectorXd weights = Eigen::VectorXd::Zero (kWeightCount);
  FeatureOptions features;
  /** σ of the Gaussian prior the weights were learned with (informative only, written
   *  as a comment; 0: unknown). */
  double prior_sigma = 0.0;
};

/** \brief Writes the model (every number round-trips exactly). */
void
writeModel (std::ostream& os, const CrfClusteringModel& model);

/** \brief Reads a model written by writeModel ().
 *  \param[in] is the stream
 *  \param[in] where the file name, for messages
 *  \throws std::runtime_error naming the line and the problem: wrong magic word or
 *  version, unknown, repeated or missing key, malformed, NaN or infinite number,
 *  feature settings not > 0.
 */
CrfClusteringModel
readModel (std::istream& is, const std::string& where);

/** \brief writeModel () to a file. \throws std::runtime_error when it cannot be written. */
void
saveModel (const CrfClusteringModel& model, const std::string& path);

/** \brief readModel () from a file. \throws std::runtime_error when it cannot be read or is invalid. */
CrfClusteringModel
loadModel (const std::string& path);

}  // namespace clustering
}  // namespace pcl_crf
