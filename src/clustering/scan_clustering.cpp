#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/clustering/scan_segmentation.h>

#include <algorithm>
#include <numeric>

namespace pcl_crf {
namespace clustering {

namespace {

/** Renumbers the clusters by decreasing number of source points (ties: previous order). */
void
sortBySourcePoints (ScanClustering& result)
{
  const int s = static_cast<int> (result.motions.size ());
  const std::vector<int> sizes = clusterSizes (result.source_cluster, s);
  std::vector<int> order (static_cast<std::size_t> (s));
  std::iota (order.begin (), order.end (), 0);
  std::stable_sort (order.begin (), order.end (), [&sizes] (int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank (order.size ());
  std::vector<Rigid2d> motions;
  Eigen::MatrixXd marginals (result.marginals.rows (), result.marginals.cols ());
  result.sizes.clear ();
  for (int k = 0; k < s; ++k)
  {
    rank[order[k]] = k;
    motions.push_back (result.motions[order[k]]);
    marginals.row (k) = result.marginals.row (order[k]);
    result.sizes.push_back (sizes[order[k]]);
  }
  for (int& l : result.source_cluster)
    l = l >= 0 ? rank[l] : l;
  if (result.static_cluster >= 0)
    result.static_cluster = rank[result.static_cluster];
  result.motions.swap (motions);
  result.marginals.swap (marginals);
}

}  // namespace

ScanClustering
clusterScan (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const std::vector<int>& source_match,
             const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters, const Odometry* odometry,
             UnpairedLabelling unpaired, double unpaired_break_distance)
{
  ScanClustering result;
  result.pairs = makePointPairs (source, target, source_match);
  const CrfClusteringResult crf = clusterPointPairs (result.pairs, weights, parameters, odometry);
  result.motions = crf.motions;
  result.static_cluster = crf.static_cluster;
  result.marginals = crf.marginals;
  result.iterations = crf.iterations;
  result.converged = crf.converged;
  if (unpaired == UnpairedLabelling::NearestSegmentNeighbour)
    result.source_cluster =
        completeLabels (source, result.pairs.source_index, crf.labels, unpaired_break_distance,
                        crf.static_cluster >= 0 ? crf.static_cluster : kOutlierCluster);
  else
  {
    result.source_cluster.assign (static_cast<std::size_t> (source.cols ()), kOutlierCluster);
    for (std::size_t k = 0; k < crf.labels.size (); ++k)
      result.source_cluster[result.pairs.source_index[k]] = crf.labels[k];
  }
  sortBySourcePoints (result);
  return result;
}

Prediction
toPrediction (const ScanClustering& clustering, const Rigid2d& fallback_T_source_target)
{
  if (clustering.static_cluster >= static_cast<int> (clustering.motions.size ()))
    throw std::invalid_argument ("[pcl_crf::clustering::toPrediction] the static cluster " +
                                 std::to_string (clustering.static_cluster) + " is not one of the " +
                                 std::to_string (clustering.motions.size ()) + " clusters");
  Prediction prediction;
  prediction.source_cluster = clustering.source_cluster;
  prediction.cluster_motions = clustering.motions;
  prediction.static_cluster = clustering.static_cluster;
  prediction.T_source_target = clustering.static_cluster >= 0
                                   ? Rigid2d (clustering.motions[clustering.static_cluster].inverse ())
                                   : fallback_T_source_target;
  return prediction;
}

}  // namespace clustering
}  // namespace pcl_crf
