#pragma once

#include <pcl_crf/core/knn_index.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief The shape neighbours of every source point (its nearest target points in
 *  shape space, shapeEmbedding) with one spare, so that a later pass, whose source
 *  points moved only a little, can prove that its own nearest ones are among them
 *  (updateShapeNeighbours) instead of searching the index again.
 *
 *  \code
 *  using namespace pcl_crf::matching;
 *  const ShapeNeighbours first = searchShapeNeighbours (embedding_pass_1, target.index.shapes, 2);
 *  const ShapeNeighbours second = updateShapeNeighbours (first, embedding_pass_2, target.index.shapes, 2);
 *  \endcode
 */
struct ShapeNeighbours
{
  /** the embedding searched, one column per source point. */
  Eigen::MatrixXd queries;
  /** (k + 1) x n target indices, nearest first; −1 where the target has fewer points. */
  Eigen::MatrixXi indices;
  /** per source point: a lower bound of the distance (not squared, embedding units)
   *  from its query to every target point not in its column (+inf when the column
   *  holds every target point). */
  Eigen::VectorXd outside_distance;

  /** \brief Number of neighbours used (k; the column holds k + 1). */
  int
  used () const { return static_cast<int> (indices.rows ()) - 1; }
};

/** \brief The k + 1 nearest target points of every column of \a embedding (one batched query).
 *  \param[in] embedding shapeEmbedding of the source points (kept as ShapeNeighbours::queries)
 *  \param[in] shapes the target's shape index (TargetIndex::shapes)
 *  \param[in] k neighbours used (≥ 1)
 */
ShapeNeighbours
searchShapeNeighbours (Eigen::MatrixXd embedding, const KnnIndex& shapes, int k);

/** \brief The same k nearest neighbours as searchShapeNeighbours (embedding, shapes, k),
 *  taken from \a before where that is provably exact: a query moved by δ is nearer than
 *  outside_distance − δ to nothing outside its old column (triangle inequality), so when
 *  its k-th nearest among the old column (re-ranked under the new query) is nearer than
 *  that, no other target point can enter. The other points are searched again, in one
 *  batch. (Ties of equal distances may be ordered differently from a fresh search.)
 *  \param[in] before the neighbours of an earlier placement of the same source points
 *  \param[in] embedding shapeEmbedding of the source at the new placement
 *  \param[in] shapes the same target shape index as for \a before
 *  \param[in] k neighbours used (≤ before.used ())
 *  \throws std::invalid_argument when the sizes do not fit or \a before indexes points
 *          \a shapes does not hold.
 */
ShapeNeighbours
updateShapeNeighbours (const ShapeNeighbours& before, Eigen::MatrixXd embedding, const KnnIndex& shapes, int k);

}  // namespace matching
}  // namespace pcl_crf
