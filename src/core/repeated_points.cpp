#include <pcl_crf/core/repeated_points.h>

#include <functional>
#include <unordered_map>
#include <utility>

namespace pcl_crf {

namespace {

/** Hash of a point's exact coordinates (std::hash<double> gives 0 and −0 one value). */
struct ExactPointHash
{
  std::size_t
  operator() (const std::pair<double, double>& p) const
  {
    const std::size_t x = std::hash<double> () (p.first), y = std::hash<double> () (p.second);
    return x ^ (y + 0x9e3779b97f4a7c15ULL + (x << 6) + (x >> 2));
  }
};

}  // namespace

std::vector<int>
firstOfEqualPoints (const Eigen::Matrix2Xd& points)
{
  const auto n = static_cast<std::size_t> (points.cols ());
  std::vector<int> first (n);
  std::unordered_map<std::pair<double, double>, int, ExactPointHash> seen;
  seen.reserve (n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto index = static_cast<Eigen::Index> (i);
    first[i] = seen.emplace (std::make_pair (points (0, index), points (1, index)), static_cast<int> (i)).first->second;
  }
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

}  // namespace pcl_crf
