#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/metrics/cluster_matching.h>

#include <vector>

namespace pcl_crf {

/** \brief Fraction [0, 1] of source points whose predicted cluster maps to
 *  their true object id ("motion detection accuracy").
 *  \param[in] mapped_objects per source point, the object its cluster is paired
 *             with, -1 for outliers and unpaired clusters (see mapClustersToObjects)
 *  \param[in] true_objects per source point, its true object id
 *  \return NaN when there are no points.
 *  \throws std::invalid_argument when the lengths differ.
 */
double
clusterAccuracy (const std::vector<int>& mapped_objects, const std::vector<int>& true_objects);

/** \brief Number of distinct cluster labels used, kOutlierCluster excluded. */
int
countClusters (const std::vector<int>& clusters);

/** \brief Number of distinct object ids present. */
int
countObjects (const std::vector<int>& objects);

/** \brief Mean motion errors over the correctly clustered objects of a pair,
 *  NaN for a group without any.
 */
struct ObjectMotionErrors
{
  /** static world: mean |angle(T_est^-1 T_true)| [rad]. */
  double static_rotation;
  /** static world: mean ||translation(T_est^-1 T_true)|| [m]. */
  double static_translation;
  /** moving objects: mean |angle(T_est^-1 T_true)| [rad]. */
  double moving_rotation;
  /** moving objects: mean ||translation(T_est^-1 T_true)|| [m]. */
  double moving_translation;
};

/** \brief Motion errors of the correctly clustered objects.
 *
 *  An object is correctly clustered when its pair in \a matching is a mutual
 *  majority (ClusterObjectPair::isMutualMajority). Its error compares
 *  T_est = prediction.cluster_motions[cluster] with T_true = the object's
 *  T_target_source (computeMotionError). Errors are averaged separately over the
 *  static world and over the moving objects.
 *
 *  \throws std::invalid_argument when a paired cluster has no motion or a
 *          paired object id is not among truth.objects.
 */
ObjectMotionErrors
computeObjectMotionErrors (const ScanPair& truth, const Prediction& prediction,
                           const ClusterObjectMatching& matching);

}  // namespace pcl_crf
