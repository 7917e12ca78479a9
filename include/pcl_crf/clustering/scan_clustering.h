#pragma once

#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/clustering/scan_pair_clustering.h>
#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief CRF-Clustering of a whole scan: every source point's cluster, not only the
 *  associated ones. */
struct ScanClustering
{
  /** cluster of every source point, or kOutlierCluster; clusters numbered by
   *  decreasing number of source points. */
  std::vector<int> source_cluster;
  /** T_target_source of every cluster. */
  std::vector<Rigid2d> motions;
  /** source points per cluster. */
  std::vector<int> sizes;
  /** the static world, or −1. */
  int static_cluster = -1;
  /** the CRF nodes (associated pairs). */
  PointPairs pairs;
  /** clusters x nodes: p(x_i = l) of every node, rows in the numbering above. */
  Eigen::MatrixXd marginals;
  int iterations = 0;
  bool converged = false;
};

/** \brief Runs CRF-Clustering (clusterPointPairs ()) on the associated points of a
 *  scan pair and labels the whole source scan.
 *
 *  \code
 *  const pcl_crf::clustering::ScanClustering result = pcl_crf::clustering::clusterScan (
 *      pair.source, pair.target, pair.source_match, weights, {}, &pair.odometry,
 *      pcl_crf::clustering::UnpairedLabelling::NearestSegmentNeighbour);
 *  \endcode
 *  \param[in] source 2 x N source scan in beam order
 *  \param[in] target 2 x M target scan
 *  \param[in] source_match per source point: target index or kNoMatch
 *  \param[in] weights the CRF weights (kWeightCount)
 *  \param[in] parameters inference settings
 *  \param[in] odometry the sensor motion, or null
 *  \param[in] unpaired how points without an association are labelled
 *  \param[in] unpaired_break_distance gap that separates the distance segments within
 *  which labels spread to points without an association [m]; default 0.5
 *  \throws std::invalid_argument for invalid input (see makePointPairs (), clusterPointPairs ()).
 */
ScanClustering
clusterScan (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const std::vector<int>& source_match,
             const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters, const Odometry* odometry,
             UnpairedLabelling unpaired, double unpaired_break_distance = 0.5);

/** \brief The Prediction of a scan clustering (source_match left empty);
 *  T_source_target = the inverse of the static motion, or \a fallback without one. */
Prediction
toPrediction (const ScanClustering& clustering, const Rigid2d& fallback_T_source_target);

}  // namespace clustering
}  // namespace pcl_crf
