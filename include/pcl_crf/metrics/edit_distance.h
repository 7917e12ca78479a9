#pragma once

#include <vector>

namespace pcl_crf {

/** \brief Levenshtein (string edit) distance between two label sequences: the
 *  least number of single-element insertions, deletions and substitutions, each
 *  of cost 1, that turn \a a into \a b.
 *
 *  Myers' bit-parallel algorithm (J. ACM 46(3), 1999), 64 rows per machine word:
 *  O(max(|a|, |b|) ⌈min(|a|, |b|) / 64⌉) time and O(min(|a|, |b|)) memory, exact (it
 *  equals the textbook dynamic programme; two scans of 100 000 points take about a
 *  second instead of 20).
 *
 *  \code
 *  pcl_crf::editDistance ({1, 2, 3}, {1, 3});  // 1 (delete the 2)
 *  \endcode
 */
int
editDistance (const std::vector<int>& a, const std::vector<int>& b);

}  // namespace pcl_crf
