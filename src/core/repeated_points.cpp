#include <pcl_crf/core/repeated_points.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace pcl_crf {

namespace {

/** Hash and equality of the columns of one matrix, by value (std::hash<double> gives 0
 *  and −0 one value). */
struct ColumnHash
{
  const Eigen::Ref<const Eigen::MatrixXd>* m;
  std::size_t
  operator() (Eigen::Index c) const
  {
    std::size_t h = 0;
    for (Eigen::Index r = 0; r < m->rows (); ++r)
      h = h * 1000003u ^ std::hash<double> () ((*m) (r, c));
    return h;
  }
};

struct ColumnEqual
{
  const Eigen::Ref<const Eigen::MatrixXd>* m;
  bool
  operator() (Eigen::Index a, Eigen::Index b) const
  {
    return (m->col (a).array () == m->col (b).array ()).all ();
  }
};

}  // namespace

std::vector<int>
firstOfEqualPoints (const Eigen::Ref<const Eigen::MatrixXd>& points)
{
  const Eigen::Index n = points.cols ();
  std::unordered_map<Eigen::Index, int, ColumnHash, ColumnEqual> seen (static_cast<std::size_t> (n),
                                                                       ColumnHash{&points}, ColumnEqual{&points});
  std::vector<int> first (static_cast<std::size_t> (n));
  for (Eigen::Index i = 0; i < n; ++i)
    first[static_cast<std::size_t> (i)] = seen.emplace (i, static_cast<int> (i)).first->second;
  return first;
}

bool
repeatsAPoint (const std::vector<int>& first)
{
  for (std::size_t i = 0; i < first.size (); ++i)
    if (first[i] != static_cast<int> (i))
      return true;
  return false;
}

std::vector<int>
firstCopies (const std::vector<int>& first)
{
  std::vector<int> copies;
  for (std::size_t i = 0; i < first.size (); ++i)
    if (first[i] == static_cast<int> (i))
      copies.push_back (static_cast<int> (i));
  return copies;
}

std::vector<int>
firstCopyColumns (const std::vector<int>& first)
{
  std::vector<int> column (first.size ());
  int count = 0;
  for (std::size_t i = 0; i < first.size (); ++i) {
    const auto f = static_cast<std::size_t> (first[i]);
    if (first[i] < 0 || f > i || static_cast<std::size_t> (first[f]) != f)
      throw std::invalid_argument ("[pcl_crf::firstCopyColumns] point " + std::to_string (i) + "'s first copy " +
                                   std::to_string (first[i]) + " is not a first copy at or before it");
    column[i] = f == i ? count++ : column[f];
  }
  return column;
}

}  // namespace pcl_crf
