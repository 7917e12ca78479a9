#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <vector>

namespace pcl_crf {

/** \brief Cluster label of points a method declares outliers (no cluster). */
constexpr int kOutlierCluster = -1;

/** \brief A method's answer for one scan pair, in the frames of ScanPair.
 *
 *  Every estimator (ICP, CRF-Matching, CRF-Clustering, the joint model and the
 *  baselines) fills what it computes; the metrics read it. A method that does not
 *  associate leaves \c source_match empty; one that does not cluster leaves
 *  \c source_cluster empty.
 */
struct Prediction
{
  /** per source point: index of the matched target point, or kNoMatch. */
  std::vector<int> source_match;
  /** per source point: cluster label in [0, cluster_motions.size()), or kOutlierCluster. */
  std::vector<int> source_cluster;
  /** per cluster: its rigid motion T_target_source. */
  std::vector<Rigid2d> cluster_motions;
  /** the cluster taken as the static world, or -1. */
  int static_cluster = -1;
  /** the estimated sensor motion: pose at target time in the source frame. */
  Rigid2d T_source_target = Rigid2d::Identity ();
  /** wall-clock time the method spent on this pair [s]. */
  double seconds = 0.0;
};

}  // namespace pcl_crf
