#include <pcl_crf/joint/map_history.h>

namespace pcl_crf {
namespace joint {

bool
MapHistory::repeats (const std::vector<int>& association, const std::vector<int>& cluster)
{
  const std::size_t n = association.size ();
  bool same = cluster.size () == n;
  for (int r = 0; r < 2; ++r)  // both earlier records hold one state per node
    same = same && association_[r].size () == n && cluster_[r].size () == n;
  for (std::size_t i = 0; same && i < n; ++i)
    same = (association[i] == association_[0][i] && cluster[i] == cluster_[0][i]) ||
           (association[i] == association_[1][i] && cluster[i] == cluster_[1][i]);
  association_[1].swap (association_[0]);
  cluster_[1].swap (cluster_[0]);
  association_[0] = association;
  cluster_[0] = cluster;
  return same;
}

}  // namespace joint
}  // namespace pcl_crf
