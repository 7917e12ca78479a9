#pragma once

#include <Eigen/Core>

#include <memory>

namespace pcl_crf {

/** \brief Exact k-nearest-neighbour search over the columns of a d x N matrix
 *  (FLANN's single kd-tree), answering a whole batch of queries in one call.
 *
 *  pcl::search::KdTree opens an OpenMP region for every single query; building
 *  candidate lists for a whole scan through one batched FLANN call avoids that
 *  overhead.
 *
 *  \code
 *  pcl_crf::KnnIndex index (target_xy);          // 2 x M
 *  const auto result = index.search (queries_xy, 5);  // 5 neighbours of every query column
 *  \endcode
 */
class KnnIndex
{
public:
  /** \brief Neighbours of every query: column q holds query q's neighbours,
   *  nearest first; unused slots (fewer than k points) hold -1 / +inf. */
  struct Result
  {
    Eigen::MatrixXi indices;
    Eigen::MatrixXd squared_distances;
  };

  /** \brief The most neighbours one search returns per query (its result holds k rows
   *  per query however few points the index holds). */
  static constexpr int kMaxNeighbours = 65536;

  KnnIndex ();
  /** \brief Builds the index over the columns of \a points (copied). */
  explicit KnnIndex (const Eigen::MatrixXd& points);
  ~KnnIndex ();
  KnnIndex (KnnIndex&&) noexcept;
  KnnIndex&
  operator= (KnnIndex&&) noexcept;

  /** \brief Rebuilds the index over the columns of \a points.
   *  \throws std::invalid_argument on non-finite values. */
  void
  build (const Eigen::MatrixXd& points);

  /** \brief Number of indexed points. */
  Eigen::Index
  size () const;

  /** \brief The indexed points (d x N, as given to build ()). */
  const Eigen::MatrixXd&
  points () const;

  /** \brief The k nearest indexed points of every column of \a queries
   *  (rows must equal the indexed dimension).
   *  \throws std::invalid_argument for k outside [1, kMaxNeighbours], queries of another dimension, non-finite
   *  queries, or squared distances that overflow to infinity (no neighbour found). */
  Result
  search (const Eigen::MatrixXd& queries, int k) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcl_crf
