#include <pcl_crf/metrics/edit_distance.h>

#include <algorithm>
#include <numeric>

namespace pcl_crf {

int
editDistance (const std::vector<int>& a, const std::vector<int>& b)
{
  // previous[j] = distance between the first i-1 elements of a and the first j of b.
  std::vector<int> previous (b.size () + 1);
  std::iota (previous.begin (), previous.end (), 0);
  std::vector<int> current (b.size () + 1);
  for (std::size_t i = 1; i <= a.size (); ++i) {
    current[0] = static_cast<int> (i);
    for (std::size_t j = 1; j <= b.size (); ++j) {
      const int substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      const int deletion = previous[j] + 1;
      const int insertion = current[j - 1] + 1;
      current[j] = std::min ({substitution, deletion, insertion});
    }
    std::swap (previous, current);
  }
  return previous.back ();
}

}  // namespace pcl_crf
