#include <pcl_crf/core/knn_index.h>

#include <flann/flann.hpp>

#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {

struct KnnIndex::Impl
{
  Eigen::MatrixXd points;  // column-major d x N == row-major N x d for FLANN
  std::unique_ptr<flann::Index<flann::L2_Simple<double>>> index;
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
  if (points.cols () == 0)
    return;
  flann::Matrix<double> data (impl_->points.data (), points.cols (), points.rows ());
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
  Eigen::MatrixXd query_copy = queries;
  // FLANN writes row-major (query x k) arrays: exactly our column-major (k x query) layout.
  constexpr std::size_t kUnwritten = std::numeric_limits<std::size_t>::max ();
  Eigen::Matrix<std::size_t, Eigen::Dynamic, Eigen::Dynamic> indices =
      Eigen::Matrix<std::size_t, Eigen::Dynamic, Eigen::Dynamic>::Constant (found, queries.cols (), kUnwritten);
  Eigen::MatrixXd distances (found, queries.cols ());
  flann::Matrix<double> query_matrix (query_copy.data (), queries.cols (), queries.rows ());
  flann::Matrix<std::size_t> index_matrix (indices.data (), queries.cols (), found);
  flann::Matrix<double> distance_matrix (distances.data (), queries.cols (), found);
  flann::SearchParams params (flann::FLANN_CHECKS_UNLIMITED);
  params.cores = 1;
  impl_->index->knnSearch (query_matrix, index_matrix, distance_matrix, found, params);
  if ((indices.array () == kUnwritten).any ())  // FLANN keeps no neighbour at an infinite distance
    throw std::invalid_argument ("[pcl_crf::KnnIndex::search] squared distances overflow to infinity: coordinates "
                                 "(points, queries, motions) of 1e154 or more are not distances in metres");
  result.indices.topRows (found) = indices.cast<int> ();
  result.squared_distances.topRows (found) = distances;
  return result;
}

}  // namespace pcl_crf
