#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Effective number of clusters of one point, N_eff = 1 / Σ_c p_c² (Eq. (8)),
 *  for probabilities p (normalised here, so any non-negative weights do): 1 when
 *  the point is sure of its cluster, S when it is spread evenly over S clusters.
 *  0 for an all-zero vector.
 */
double
effectiveClusterCount (const Eigen::Ref<const Eigen::VectorXd>& p);

/** \brief Chooses the clusters to keep (Tipaldi & Ramos, IROS 2009, Sec. IV-E).
 *
 *  A cluster whose points (the nodes it labels) have an average N_eff (Eq. (8))
 *  above \a max_average_neff explains nothing the other clusters do not: the
 *  worst such cluster is removed and its points move to their second-best cluster
 *  (by \a probabilities); N_eff is recomputed over the remaining clusters and the
 *  next worst removed, until no cluster exceeds the threshold. Clusters left
 *  without a point vanish too.
 *
 *  \param[in] probabilities S x n, column i = how well each cluster explains node i
 *              (normalised or not: N_eff normalises)
 *  \param[in,out] labels cluster of every node, in [0, S); points of removed
 *                  clusters are relabelled (old numbering)
 *  \param[in] max_average_neff threshold on a cluster's average N_eff, > 1 (paper: 1.7)
 *  \return the kept clusters, increasing
 *  \throws std::invalid_argument for a size mismatch or a label out of range.
 */
std::vector<int>
selectClusters (const Eigen::MatrixXd& probabilities, std::vector<int>& labels, double max_average_neff);

/** \brief Keeps the rows of \a kept (renumbered 0, 1, ...), renormalises the columns
 *  and renumbers \a labels (which must all be kept clusters). */
void
keepClusters (const std::vector<int>& kept, Eigen::MatrixXd& marginals, std::vector<int>& labels);

/** \brief selectClusters () on the marginals, then keepClusters ().
 *
 *  \code
 *  const std::vector<int> kept = pcl_crf::clustering::mergeAmbiguousClusters (marginals, labels, 1.7);
 *  \endcode
 *  \param[in,out] marginals S x n, column i = cluster probabilities of node i
 *  \param[in,out] labels cluster of every node (MAP), in [0, S)
 *  \param[in] max_average_neff threshold on a cluster's average N_eff, > 1 (paper: 1.7)
 *  \return previous index of every kept cluster
 */
std::vector<int>
mergeAmbiguousClusters (Eigen::MatrixXd& marginals, std::vector<int>& labels, double max_average_neff);

}  // namespace clustering
}  // namespace pcl_crf
