#include <pcl_crf/core/repeated_points.h>

#include "cluster_numbering.h"
#include "lifted_copies.h"

namespace pcl_crf {
namespace joint {

JointResult
detail::liftToCopies (const JointResult& distinct, const std::vector<int>& source_first,
                      const std::vector<int>& target_first)
{
  const std::vector<int> source_kept = firstCopies (source_first), target_kept = firstCopies (target_first);
  std::vector<int> position (source_first.size (), -1);  // a first copy's point in distinct
  for (std::size_t k = 0; k < source_kept.size (); ++k)
    position[static_cast<std::size_t> (source_kept[k])] = static_cast<int> (k);
  std::vector<bool> moved_away (source_kept.size (), false);
  for (const int k : distinct.moved_away)
    moved_away[static_cast<std::size_t> (k)] = true;
  JointResult result = distinct;
  result.source_match.assign (source_first.size (), kNoMatch);
  result.source_cluster.assign (source_first.size (), kOutlierCluster);
  result.moved_away.clear ();
  for (std::size_t i = 0; i < source_first.size (); ++i) {
    const auto k = static_cast<std::size_t> (position[static_cast<std::size_t> (source_first[i])]);
    const int j = distinct.source_match[k];
    result.source_match[i] = j == kNoMatch ? kNoMatch : target_kept[static_cast<std::size_t> (j)];
    result.source_cluster[i] = distinct.source_cluster[k];
    if (moved_away[k])
      result.moved_away.push_back (static_cast<int> (i));
  }
  numberLargestFirst (result);
  return result;
}

}  // namespace joint
}  // namespace pcl_crf
