#include <pcl_crf/core/repeated_points.h>

#include "cluster_numbering.h"
#include "lifted_copies.h"

namespace pcl_crf {
namespace joint {

JointResult
detail::liftToCopies (const JointResult& distinct, const std::vector<int>& source_first,
                      const std::vector<int>& target_first)
{
  const std::vector<int> target_kept = firstCopies (target_first);
  const std::vector<int> column = firstCopyColumns (source_first);  // a point's first copy in distinct
  std::vector<bool> moved_away (distinct.source_cluster.size (), false);
  for (const int k : distinct.moved_away)
    moved_away[static_cast<std::size_t> (k)] = true;
  JointResult result = distinct;
  result.source_match.assign (source_first.size (), kNoMatch);
  result.source_cluster.assign (source_first.size (), kOutlierCluster);
  result.moved_away.clear ();
  for (std::size_t i = 0; i < source_first.size (); ++i) {
    const auto k = static_cast<std::size_t> (column[i]);
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
