#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief The associated point pairs (s_i → g_i) of a scan pair in scan order:
 *  the hidden nodes of the CRF-Clustering chain (Tipaldi & Ramos, IROS 2009, Sec. IV).
 *
 *  Column i of \c source is a source point s_i (source sensor frame), column i of
 *  \c target its associated target point g_i (target sensor frame). Source points
 *  without an association have no pair.
 *
 *  \code
 *  const pcl_crf::clustering::PointPairs pairs =
 *      pcl_crf::clustering::makePointPairs (pair.source, pair.target, pair.source_match);
 *  const std::vector<pcl_crf::Rigid2d> motions = pcl_crf::clustering::fitMotions (pairs, labels, 2);
 *  \endcode
 */
struct PointPairs
{
  Eigen::Matrix2Xd source;
  Eigen::Matrix2Xd target;
  /** index of s_i in the source scan. */
  std::vector<int> source_index;
  /** sampling distance of the source scan at s_i: the distance to the nearer of
   *  its two neighbours in the scan [m] (+inf for a scan of one point). */
  Eigen::VectorXd spacing;
  /** angle between consecutive beams, estimated from the source scan as the median
   *  bearing step of consecutive points [rad] (0 when it has fewer than 2 points). */
  double angular_resolution = 0.0;

  /** \brief Number of pairs (nodes). */
  std::size_t
  size () const { return source_index.size (); }
};

/** \brief The pairs of every source point with an association, in source order,
 *  with the scan's sampling distance at every pair and its angular resolution.
 *  \param[in] source 2 x N source scan
 *  \param[in] target 2 x M target scan
 *  \param[in] source_match per source point: target index or kNoMatch
 *  \throws std::invalid_argument for a size mismatch, an index out of range, a
 *  non-finite source point or a match to a non-finite target point.
 */
PointPairs
makePointPairs (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                const std::vector<int>& source_match);

/** \brief What makes \a pairs inconsistent, or an empty string when nothing does:
 *  source, target, source_index and spacing of different lengths, or a non-finite
 *  point. makePointPairs () always gives consistent pairs; the estimators check pairs
 *  built by hand.
 *
 *  \code
 *  const std::string problem = pcl_crf::clustering::pointPairsProblem (pairs);
 *  \endcode
 */
std::string
pointPairsProblem (const PointPairs& pairs);

/** \brief The median bearing step between consecutive points of a scan in beam order
 *  [rad]: the beam spacing when fewer than half the beams are missing. 0 for fewer
 *  than two points. */
double
estimateAngularResolution (const Eigen::Matrix2Xd& scan);

/** \brief Least-squares motion T_target_source of each cluster from hard labels
 *  (Eq. (3) with weights 1 for the cluster's pairs, 0 for the others).
 *  A cluster without pairs gets the identity.
 *  \param[in] labels cluster of every pair, in [0, cluster_count); other values are ignored
 */
std::vector<Rigid2d>
fitMotions (const PointPairs& pairs, const std::vector<int>& labels, int cluster_count);

/** \brief Squared residuals f_dist(i, l) = ||T_l s_i − g_i||² (Eq. (2)), S x n [m²]. */
Eigen::MatrixXd
squaredResiduals (const PointPairs& pairs, const std::vector<Rigid2d>& motions);

/** \brief Points per cluster of a labelling (labels outside [0, cluster_count) are ignored). */
std::vector<int>
clusterSizes (const std::vector<int>& labels, int cluster_count);

}  // namespace clustering
}  // namespace pcl_crf
