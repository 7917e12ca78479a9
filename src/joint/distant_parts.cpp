#include <pcl_crf/joint/joint_estimation.h>

#include "cluster_numbering.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The parts of \a points (indices into \a source): the connected components of the
 *  graph joining two points no farther apart than \a gap (single linkage), each in
 *  increasing index order, the part of the first point first. */
std::vector<std::vector<int>>
partsWithin (const Eigen::Matrix2Xd& source, const std::vector<int>& points, double gap)
{
  const double gap_squared = gap * gap;
  std::vector<int> part (points.size (), -1);
  std::vector<std::vector<int>> parts;
  std::vector<std::size_t> frontier;
  for (std::size_t seed = 0; seed < points.size (); ++seed) {
    if (part[seed] >= 0)
      continue;
    const int id = static_cast<int> (parts.size ());
    part[seed] = id;
    frontier.assign (1, seed);
    while (!frontier.empty ()) {  // flood the part from its seed
      const std::size_t a = frontier.back ();
      frontier.pop_back ();
      for (std::size_t b = 0; b < points.size (); ++b)
        if (part[b] < 0 && (source.col (points[a]) - source.col (points[b])).squaredNorm () <= gap_squared) {
          part[b] = id;
          frontier.push_back (b);
        }
    }
    parts.emplace_back ();
  }
  for (std::size_t k = 0; k < points.size (); ++k)
    parts[part[k]].push_back (points[k]);
  return parts;
}

}  // namespace

int
separateDistantParts (const Eigen::Matrix2Xd& source, double gap, JointResult& result)
{
  if (!(gap > 0.0) || !std::isfinite (gap))
    throw std::invalid_argument ("[pcl_crf::joint::separateDistantParts] the gap must be a distance > 0 m, not " +
                                 std::to_string (gap));
  detail::checkResultAgainstSource ("separateDistantParts", source, result);
  if (result.static_cluster < 0)  // no static world to tell the moving clusters by
    return 0;
  const int clusters = static_cast<int> (result.cluster_motions.size ());
  std::vector<std::vector<int>> members (static_cast<std::size_t> (clusters));
  for (std::size_t i = 0; i < result.source_cluster.size (); ++i)
    if (result.source_cluster[i] != kOutlierCluster)
      members[result.source_cluster[i]].push_back (static_cast<int> (i));
  int added = 0;
  for (int l = 0; l < clusters; ++l) {
    if (l == result.static_cluster)
      continue;
    const std::vector<std::vector<int>> parts = partsWithin (source, members[l], gap);
    for (std::size_t p = 1; p < parts.size (); ++p) {  // the first part keeps the cluster
      const int part_cluster = static_cast<int> (result.cluster_motions.size ());
      result.cluster_motions.push_back (result.cluster_motions[l]);
      for (int i : parts[p])
        result.source_cluster[i] = part_cluster;
      ++added;
    }
  }
  if (added > 0)
    detail::numberLargestFirst (result);
  return added;
}

}  // namespace joint
}  // namespace pcl_crf
