#include <pcl_crf/core/prediction.h>
#include <pcl_crf/metrics/cluster_matching.h>
#include <pcl_crf/metrics/contingency_table.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

/** Every overlapping (cluster, object) with its sizes; outlier points excluded. */
std::vector<ClusterObjectPair>
overlappingPairs (const ContingencyTable& cluster_by_object)
{
  std::vector<ClusterObjectPair> candidates;
  for (const auto& cell : cluster_by_object.cells ()) {
    const int cluster = cell.first.first;
    const int object = cell.first.second;
    if (cluster == kOutlierCluster)
      continue;
    candidates.push_back ({cluster, object, cell.second,
                           cluster_by_object.rowTotals ().at (cluster),
                           cluster_by_object.columnTotals ().at (object)});
  }
  return candidates;
}

/** Largest overlap first, then smaller cluster label, then smaller object id. */
bool
comesFirst (const ClusterObjectPair& a, const ClusterObjectPair& b)
{
  if (a.overlap != b.overlap)
    return a.overlap > b.overlap;
  if (a.cluster != b.cluster)
    return a.cluster < b.cluster;
  return a.object < b.object;
}

}  // namespace

int
ClusterObjectMatching::objectOf (int cluster) const
{
  for (const auto& pair : pairs)
    if (pair.cluster == cluster)
      return pair.object;
  return -1;
}

ClusterObjectMatching
matchClustersToObjects (const std::vector<int>& clusters, const std::vector<int>& objects)
{
  if (clusters.size () != objects.size ())
    throw std::invalid_argument ("[pcl_crf::matchClustersToObjects] " +
                                 std::to_string (clusters.size ()) + " cluster labels but " +
                                 std::to_string (objects.size ()) + " object ids");
  std::vector<ClusterObjectPair> candidates =
      overlappingPairs (ContingencyTable (clusters, objects));
  std::sort (candidates.begin (), candidates.end (), comesFirst);

  // Walking the sorted list and keeping a pair when both sides are still free
  // is the same as repeatedly taking the largest remaining overlap.
  ClusterObjectMatching matching;
  std::set<int> paired_clusters, paired_objects;
  for (const auto& candidate : candidates) {
    if (paired_clusters.count (candidate.cluster) || paired_objects.count (candidate.object))
      continue;
    paired_clusters.insert (candidate.cluster);
    paired_objects.insert (candidate.object);
    matching.pairs.push_back (candidate);
  }
  return matching;
}

std::vector<int>
mapClustersToObjects (const std::vector<int>& clusters, const ClusterObjectMatching& matching)
{
  std::vector<int> objects;
  objects.reserve (clusters.size ());
  for (const int cluster : clusters)
    objects.push_back (cluster == kOutlierCluster ? -1 : matching.objectOf (cluster));
  return objects;
}

}  // namespace pcl_crf
