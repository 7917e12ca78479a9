#pragma once

#include <vector>

namespace pcl_crf {

/** \brief Levenshtein (string edit) distance between two label sequences: the
 *  least number of single-element insertions, deletions and substitutions, each
 *  of cost 1, that turn \a a into \a b.
 *
 *  Runs in O(|a| |b|) time and O(|b|) memory.
 *
 *  \code
 *  pcl_crf::editDistance ({1, 2, 3}, {1, 3});  // 1 (delete the 2)
 *  \endcode
 */
int
editDistance (const std::vector<int>& a, const std::vector<int>& b);

}  // namespace pcl_crf
