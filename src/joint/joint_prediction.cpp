#include <pcl_crf/clustering/scan_segmentation.h>
#include <pcl_crf/joint/joint_estimation.h>

#include "cluster_numbering.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** segment gap for labelling the outlier cluster's points, as CRF-Clustering's default [m]. */
constexpr double kBreakDistance = 0.5;

}  // namespace

Prediction
toPrediction (const Eigen::Matrix2Xd& source, const joint::JointResult& result)
{
  detail::checkResultAgainstSource ("toPrediction", source, result);  // its clusters, static cluster and sizes
  Prediction prediction;
  prediction.source_match = result.source_match;
  std::vector<bool> moved_away (result.source_cluster.size (), false);
  for (int i : result.moved_away) {
    if (i < 0 || static_cast<std::size_t> (i) >= moved_away.size ())
      throw std::invalid_argument ("[pcl_crf::joint::toPrediction] moved-away point " + std::to_string (i) +
                                   " is not one of the " + std::to_string (moved_away.size ()) + " source points");
    moved_away[i] = true;
  }
  std::vector<int> clustered, labels;  // labelled points: the clustered ones and those that moved away
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i)
    if (result.source_cluster[i] != kOutlierCluster || moved_away[i]) {
      clustered.push_back (static_cast<int> (i));
      labels.push_back (result.source_cluster[i]);
    }
  prediction.source_cluster = clustering::completeLabels (source, clustered, labels, kBreakDistance,
                                                          result.static_cluster >= 0 ? result.static_cluster
                                                                                     : kOutlierCluster);
  prediction.cluster_motions = result.cluster_motions;
  prediction.static_cluster = result.static_cluster;
  prediction.T_source_target = result.T_source_target;
  return prediction;
}

}  // namespace joint
}  // namespace pcl_crf
