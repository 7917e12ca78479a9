#pragma once

#include <vector>

namespace pcl_crf {
namespace joint {

/** \brief The MAP states of the ladder after its last two iterations, to recognise
 *  oscillation.
 *
 *  Loopy max-product can settle into states that a few nodes alternate between: a
 *  node flips, its pair moves its cluster's refit, and the new motion flips it back.
 *  Once no node reaches a state it did not hold in the two iterations before, further
 *  iterations only alternate between the same states, so the inference may stop.
 *
 *  \code
 *  pcl_crf::joint::MapHistory history;
 *  while (…) {
 *    …  // one iteration
 *    if (history.repeats (association, cluster))
 *      break;
 *  }
 *  \endcode
 */
class MapHistory
{
public:
  /** \brief Records one iteration's MAP states (one association and one cluster state per node).
   *  \return true when every node holds the pair of states it held one or two records
   *  before, the records before being two of the same length. */
  bool
  repeats (const std::vector<int>& association, const std::vector<int>& cluster);

private:
  std::vector<int> association_[2], cluster_[2];  // [0] the last record, [1] the one before
};

}  // namespace joint
}  // namespace pcl_crf
