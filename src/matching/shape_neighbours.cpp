#include <pcl_crf/matching/shape_neighbours.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {
namespace matching {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity ();

/** Relative margin on the proof of updateShapeNeighbours, far above the rounding of
 *  the distances it compares. */
constexpr double kProofMargin = 1e-9;

[[noreturn]] void
fail (const char* function, const std::string& what)
{
  throw std::invalid_argument (std::string ("[pcl_crf::matching::") + function + "] " + what);
}

/** The bound of every query of a fresh (k + 1)-nearest search: its (k + 1)-th distance,
 *  or +inf when the index holds no more than k + 1 points (a column holds them all). */
Eigen::VectorXd
outsideDistances (const KnnIndex::Result& found, const KnnIndex& shapes)
{
  const Eigen::Index k_plus_1 = found.indices.rows ();
  if (shapes.size () <= k_plus_1)
    return Eigen::VectorXd::Constant (found.indices.cols (), kInfinity);
  return found.squared_distances.row (k_plus_1 - 1).transpose ().cwiseSqrt ();
}

/** Searches the columns \a columns of \a out again (one batch of their queries). */
void
searchColumns (const std::vector<Eigen::Index>& columns, const KnnIndex& shapes, ShapeNeighbours& out)
{
  if (columns.empty ())
    return;
  Eigen::MatrixXd queries (out.queries.rows (), static_cast<Eigen::Index> (columns.size ()));
  for (std::size_t q = 0; q < columns.size (); ++q)
    queries.col (q) = out.queries.col (columns[q]);
  const KnnIndex::Result found = shapes.search (queries, static_cast<int> (out.indices.rows ()));
  const Eigen::VectorXd outside = outsideDistances (found, shapes);
  for (std::size_t q = 0; q < columns.size (); ++q) {
    out.indices.col (columns[q]) = found.indices.col (q);
    out.outside_distance (columns[q]) = outside (q);
  }
}

}  // namespace

ShapeNeighbours
searchShapeNeighbours (Eigen::MatrixXd embedding, const KnnIndex& shapes, int k)
{
  if (k < 1)
    fail ("searchShapeNeighbours", "k must be at least 1, got " + std::to_string (k));
  ShapeNeighbours neighbours;
  neighbours.queries = std::move (embedding);
  if (shapes.size () == 0) {  // nothing to find (and nothing to check the dimension against)
    neighbours.indices.setConstant (k + 1, neighbours.queries.cols (), -1);
    neighbours.outside_distance.setConstant (neighbours.queries.cols (), kInfinity);
    return neighbours;
  }
  KnnIndex::Result found = shapes.search (neighbours.queries, k + 1);
  neighbours.outside_distance = outsideDistances (found, shapes);
  neighbours.indices = std::move (found.indices);
  return neighbours;
}

ShapeNeighbours
updateShapeNeighbours (const ShapeNeighbours& before, Eigen::MatrixXd embedding, const KnnIndex& shapes, int k)
{
  if (k < 1 || k > before.used ())
    fail ("updateShapeNeighbours", "k must be in [1, " + std::to_string (before.used ()) + "], got " +
                                       std::to_string (k));
  if (embedding.rows () != before.queries.rows () || embedding.cols () != before.queries.cols ())
    fail ("updateShapeNeighbours", "the embedding is " + std::to_string (embedding.rows ()) + " x " +
                                       std::to_string (embedding.cols ()) + ", the earlier queries " +
                                       std::to_string (before.queries.rows ()) + " x " +
                                       std::to_string (before.queries.cols ()));
  const Eigen::MatrixXd& targets = shapes.points ();
  const Eigen::Index k_plus_1 = before.indices.rows ();
  ShapeNeighbours after;
  after.queries = std::move (embedding);
  after.indices = before.indices;
  after.outside_distance.resize (after.queries.cols ());
  std::vector<Eigen::Index> unproven;
  std::vector<std::pair<double, int>> ranked;  // (new squared distance, target), old order kept on ties
  for (Eigen::Index i = 0; i < after.queries.cols (); ++i) {
    const auto query = after.queries.col (i);
    const double moved = (query - before.queries.col (i)).norm ();
    const double bound = before.outside_distance (i) - moved;  // nothing outside the column is nearer
    ranked.clear ();
    for (Eigen::Index r = 0; r < k_plus_1; ++r) {
      const int j = before.indices (r, i);
      if (j >= static_cast<int> (targets.cols ()))
        fail ("updateShapeNeighbours", "the earlier neighbours index target point " + std::to_string (j) +
                                           " of " + std::to_string (targets.cols ()) + ": another target's");
      if (j >= 0)
        ranked.emplace_back ((query - targets.col (j)).squaredNorm (), j);
    }
    std::stable_sort (ranked.begin (), ranked.end (),
                      [] (const std::pair<double, int>& a, const std::pair<double, int>& b) { return a.first < b.first; });
    const bool proven = static_cast<int> (ranked.size ()) <= k || std::isinf (bound) ||
                        std::sqrt (ranked[k - 1].first) < bound - kProofMargin * (1.0 + std::abs (bound));
    if (!proven) {
      unproven.push_back (i);
      continue;
    }
    for (std::size_t r = 0; r < ranked.size (); ++r)
      after.indices (static_cast<Eigen::Index> (r), i) = ranked[r].second;
    after.outside_distance (i) = bound;
  }
  searchColumns (unproven, shapes, after);
  return after;
}

}  // namespace matching
}  // namespace pcl_crf
