#include <pcl_crf/clustering/clustering_learning.h>
#include <pcl_crf/clustering/scan_pair_clustering.h>
#include <pcl_crf/clustering/scan_segmentation.h>

#include <set>
#include <stdexcept>

namespace pcl_crf {
namespace clustering {

Prediction
makePrediction (const ScanPair& pair, const PointPairs& pairs, const std::vector<int>& labels,
                const std::vector<Rigid2d>& motions, int static_cluster, UnpairedLabelling unpaired,
                double break_distance)
{
  Prediction prediction;
  const auto n = static_cast<std::size_t> (pair.source.cols ());
  if (unpaired == UnpairedLabelling::NearestSegmentNeighbour)
    prediction.source_cluster = completeLabels (pair.source, pairs.source_index, labels, break_distance,
                                                static_cluster >= 0 ? static_cluster : kOutlierCluster);
  else
  {
    prediction.source_cluster.assign (n, kOutlierCluster);
    for (std::size_t k = 0; k < pairs.size (); ++k)
      prediction.source_cluster[pairs.source_index[k]] = labels[k];
  }
  prediction.cluster_motions = motions;
  prediction.static_cluster = static_cluster;
  prediction.T_source_target =
      static_cluster >= 0 ? Rigid2d (motions[static_cluster].inverse ()) : pair.odometry.T_source_target;
  return prediction;
}

crf::LabelledChain
trainingChain (const ScanPair& pair, const FeatureOptions& options)
{
  return trainingChain (pair, pair.source_match, options);
}

crf::LabelledChain
trainingChain (const ScanPair& pair, const std::vector<int>& associations, const FeatureOptions& options)
{
  if (!pair.hasTruth ())
    throw std::invalid_argument ("[pcl_crf::clustering::trainingChain] pair '" + pair.name + "' has no truth");
  const PointPairs pairs = makePointPairs (pair.source, pair.target, associations);
  std::vector<int> labels;
  labels.reserve (pairs.size ());
  for (const int i : pairs.source_index)
    labels.push_back (pair.source_object[i]);
  return makeTrainingChain (pairs, labels, options);
}

int
associatedObjectCount (const ScanPair& pair)
{
  std::set<int> objects;
  for (std::size_t i = 0; i < pair.source_match.size () && i < pair.source_object.size (); ++i)
    if (pair.source_match[i] != kNoMatch)
      objects.insert (pair.source_object[i]);
  return static_cast<int> (objects.size ());
}

}  // namespace clustering
}  // namespace pcl_crf
