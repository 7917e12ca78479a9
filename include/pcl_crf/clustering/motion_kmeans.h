#pragma once

#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/core/scan_pair.h>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief Settings of the modified K-Means baseline (Tipaldi & Ramos, IROS 2009, Sec. V-C). */
struct MotionKMeansParameters
{
  /** number of clusters k (the paper uses the maximum number of objects) [clusters];
   *  ≥ 1, default 3. */
  int cluster_count = 3;
  /** at most this many assignment/refit rounds; ≥ 1, default 50. */
  int max_iterations = 50;
};

/** \brief Outcome of the K-Means baseline. */
struct MotionKMeansResult
{
  /** cluster of every pair, clusters numbered by decreasing size (empty ones dropped). */
  std::vector<int> labels;
  /** T_target_source of every cluster. */
  std::vector<Rigid2d> motions;
  /** pairs per cluster. */
  std::vector<int> sizes;
  int iterations = 0;
  /** true when the assignment stopped changing before max_iterations. */
  bool converged = false;
};

/** \brief K-Means whose centroids are rigid motions (Sec. V-C).
 *
 *  Deterministic: the k initial clusters are k contiguous, equally long runs of the
 *  pairs in scan order. Then, until the assignment stops changing: every cluster's
 *  motion is its least-squares fit (Eq. (3)) and every pair joins the motion with the
 *  smallest residual ||T_l + R_l s_i − g_i||² (Eq. (10)); ties go to the lower index.
 *  A cluster left empty keeps its last motion and may win pairs back.
 *
 *  \code
 *  pcl_crf::clustering::MotionKMeansParameters parameters;
 *  parameters.cluster_count = 5;
 *  const auto result = pcl_crf::clustering::clusterKMeans (pairs, parameters);
 *  \endcode
 *  \throws std::invalid_argument for cluster_count or max_iterations < 1.
 */
MotionKMeansResult
clusterKMeans (const PointPairs& pairs, const MotionKMeansParameters& parameters = {});

}  // namespace clustering
}  // namespace pcl_crf
