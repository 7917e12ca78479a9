#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/repeated_points.h>

#include <flann/flann.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {

/** The points, and, when some are equal, the distinct ones with the copies of each:
 *  FLANN's kd-tree cannot split a set of equal points, so a leaf of thousands of
 *  copies made every query near them scan them all (20 000 copies of one point took
 *  seconds, 100 000 minutes). The tree holds the distinct points; a search expands
 *  each into its copies. Without copies the tree holds the points as given. */
struct KnnIndex::Impl
{
  Eigen::MatrixXd points;  // column-major d x N == row-major N x d for FLANN
  Eigen::MatrixXd distinct;  // empty when every point is distinct
  std::vector<int> copy_offsets;  // distinct u: its copies are copies[copy_offsets[u] .. copy_offsets[u + 1])
  std::vector<int> copies;        // point indices, increasing within each distinct point
  std::unique_ptr<flann::Index<flann::L2_Simple<double>>> index;

  void
  groupCopies ()
  {
    const Eigen::Index n = points.cols ();
    const std::vector<int> distinct_of = firstCopyColumns (firstOfEqualPoints (points));
    const int count = n == 0 ? 0 : *std::max_element (distinct_of.begin (), distinct_of.end ()) + 1;
    distinct.resize (0, 0);
    copy_offsets.clear ();
    copies.clear ();
    if (count == n)
      return;
    distinct.resize (points.rows (), count);
    copy_offsets.assign (static_cast<std::size_t> (count) + 1, 0);
    for (Eigen::Index c = 0; c < n; ++c)
      ++copy_offsets[distinct_of[c] + 1];
    for (int u = 0; u < count; ++u)
      copy_offsets[u + 1] += copy_offsets[u];
    copies.resize (static_cast<std::size_t> (n));
    std::vector<int> next (copy_offsets.begin (), copy_offsets.end () - 1);
    for (Eigen::Index c = 0; c < n; ++c) {
      const int u = distinct_of[c];
      if (next[u] == copy_offsets[u])
        distinct.col (u) = points.col (c);
      copies[next[u]++] = static_cast<int> (c);
    }
  }

  bool
  hasCopies () const
  {
    return distinct.cols () > 0;
  }

  /** The matrix the tree holds. */
  Eigen::MatrixXd&
  treePoints ()
  {
    return hasCopies () ? distinct : points;
  }
  const Eigen::MatrixXd&
  treePoints () const
  {
    return hasCopies () ? distinct : points;
  }
};

KnnIndex::KnnIndex () : impl_ (std::make_unique<Impl> ()) {}

KnnIndex::KnnIndex (const Eigen::MatrixXd& points) : KnnIndex () { build (points); }

KnnIndex::~KnnIndex () = default;
KnnIndex::KnnIndex (KnnIndex&&) noexcept = default;
KnnIndex&
KnnIndex::operator= (KnnIndex&&) noexcept = default;

void
KnnIndex::build (const Eigen::MatrixXd& points)
{
  if (!points.allFinite ())
    throw std::invalid_argument ("[pcl_crf::KnnIndex::build] points hold NaN or infinite values");
  impl_->points = points;
  impl_->index.reset ();
  impl_->groupCopies ();
  if (points.cols () == 0)
    return;
  Eigen::MatrixXd& tree_points = impl_->treePoints ();
  flann::Matrix<double> data (tree_points.data (), tree_points.cols (), tree_points.rows ());
  impl_->index = std::make_unique<flann::Index<flann::L2_Simple<double>>> (
      data, flann::KDTreeSingleIndexParams (10));
  impl_->index->buildIndex ();
}

Eigen::Index
KnnIndex::size () const
{
  return impl_->points.cols ();
}

const Eigen::MatrixXd&
KnnIndex::points () const
{
  return impl_->points;
}

KnnIndex::Result
KnnIndex::search (const Eigen::MatrixXd& queries, int k) const
{
  if (k <= 0 || k > kMaxNeighbours)
    throw std::invalid_argument ("[pcl_crf::KnnIndex::search] k = " + std::to_string (k) + " must be in [1, " +
                                 std::to_string (kMaxNeighbours) + "]");
  if (queries.cols () > 0 && queries.rows () != impl_->points.rows ())
    throw std::invalid_argument ("[pcl_crf::KnnIndex::search] queries have " + std::to_string (queries.rows ()) +
                                 " rows, the index " + std::to_string (impl_->points.rows ()));
  if (!queries.allFinite ())
    throw std::invalid_argument ("[pcl_crf::KnnIndex::search] queries hold NaN or infinite values");
  Result result;
  result.indices.setConstant (k, queries.cols (), -1);
  result.squared_distances.setConstant (k, queries.cols (), std::numeric_limits<double>::infinity ());
  const int found = static_cast<int> (std::min<Eigen::Index> (k, size ()));
  if (found == 0 || queries.cols () == 0)
    return result;
  const Eigen::MatrixXd& tree_points = std::as_const (*impl_).treePoints ();
  const int tree_found = static_cast<int> (std::min<Eigen::Index> (k, tree_points.cols ()));
  Eigen::MatrixXd query_copy = queries;
  // FLANN writes row-major (query x k) arrays: exactly our column-major (k x query) layout.
  constexpr std::size_t kUnwritten = std::numeric_limits<std::size_t>::max ();
  Eigen::Matrix<std::size_t, Eigen::Dynamic, Eigen::Dynamic> indices =
      Eigen::Matrix<std::size_t, Eigen::Dynamic, Eigen::Dynamic>::Constant (tree_found, queries.cols (), kUnwritten);
  Eigen::MatrixXd distances (tree_found, queries.cols ());
  flann::Matrix<double> query_matrix (query_copy.data (), queries.cols (), queries.rows ());
  flann::Matrix<std::size_t> index_matrix (indices.data (), queries.cols (), tree_found);
  flann::Matrix<double> distance_matrix (distances.data (), queries.cols (), tree_found);
  flann::SearchParams params (flann::FLANN_CHECKS_UNLIMITED);
  params.cores = 1;
  impl_->index->knnSearch (query_matrix, index_matrix, distance_matrix, tree_found, params);
  if ((indices.array () == kUnwritten).any ())  // FLANN keeps no neighbour at an infinite distance
    throw std::invalid_argument ("[pcl_crf::KnnIndex::search] squared distances overflow to infinity: coordinates "
                                 "(points, queries, motions) of 1e154 or more are not distances in metres");
  if (!impl_->hasCopies ()) {
    result.indices.topRows (found) = indices.cast<int> ();
    result.squared_distances.topRows (found) = distances;
    return result;
  }
  for (Eigen::Index q = 0; q < queries.cols (); ++q) {  // each distinct point gives its copies, in order
    int filled = 0;
    for (int r = 0; r < tree_found && filled < found; ++r) {
      const auto u = static_cast<std::size_t> (indices (r, q));
      for (int c = impl_->copy_offsets[u]; c < impl_->copy_offsets[u + 1] && filled < found; ++c, ++filled) {
        result.indices (filled, q) = impl_->copies[c];
        result.squared_distances (filled, q) = distances (r, q);
      }
    }
  }
  return result;
}

}  // namespace pcl_crf
