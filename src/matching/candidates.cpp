#include <pcl_crf/matching/candidates.h>
#include <pcl_crf/matching/shape_features.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace matching {

namespace {

constexpr int kAngleRows = 3;
constexpr int kDistanceRows = 4;
/** distance below which the log compression is ~linear [m]. */
constexpr double kDistanceKnee = 0.1;

bool
usesPosition (double position_scale)
{
  return position_scale > 0.0 && std::isfinite (position_scale);
}

/** Appends the first \a rows neighbours in column i of \a indices that are not yet
 *  candidates of the last point. */
void
appendNew (const Eigen::MatrixXi& indices, Eigen::Index rows, Eigen::Index i, Candidates& candidates)
{
  if (i < 0 || i >= indices.cols ())
    return;
  const auto begin = candidates.targets.begin () + candidates.offsets.back ();
  for (Eigen::Index r = 0; r < std::min (rows, indices.rows ()); ++r) {
    const int j = indices (r, i);
    if (j >= 0 && std::find (begin, candidates.targets.end (), j) == candidates.targets.end ())
      candidates.targets.push_back (j);
  }
}

}  // namespace

int
Candidates::find (int i, int j) const
{
  for (int c = offsets[i]; c < offsets[i + 1]; ++c)
    if (targets[c] == j)
      return c - offsets[i];
  return -1;
}

int
shapeEmbeddingDimension ()
{
  return kAngleRows + kDistanceRows + 2;
}

Eigen::MatrixXd
shapeEmbedding (const Eigen::MatrixXd& shape, const Eigen::Matrix2Xd& points, double position_scale)
{
  if (shape.rows () != kShapeFeatureCount || shape.cols () != points.cols ())
    throw std::invalid_argument ("[pcl_crf::matching::shapeEmbedding] " + std::to_string (shape.rows ()) + " x " +
                                 std::to_string (shape.cols ()) + " shape features for " +
                                 std::to_string (points.cols ()) + " points: give computeShapeFeatures of the scan (" +
                                 std::to_string (kShapeFeatureCount) + " rows, one column per point)");
  Eigen::MatrixXd embedding (shapeEmbeddingDimension (), shape.cols ());
  embedding.topRows (kAngleRows) = shape.middleRows (kAngle1, kAngleRows);
  embedding.middleRows (kAngleRows, kDistanceRows) =
      (shape.middleRows (kDistanceBefore1, kDistanceRows).array () / kDistanceKnee).log1p ().matrix ();
  if (usesPosition (position_scale))
    embedding.bottomRows (2) = points / position_scale;
  else
    embedding.bottomRows (2).setZero ();
  return embedding;
}

Candidates
findCandidates (const Eigen::Matrix2Xd& source_in_target, const ShapeNeighbours& shape_neighbours,
                const Eigen::Matrix2Xd& segment_translation, const std::vector<bool>& has_segment_motion,
                const TargetIndex& target, const CandidateParameters& parameters)
{
  Candidates candidates;
  const Eigen::Index n = source_in_target.cols ();
  candidates.offsets.reserve (n + 1);
  candidates.targets.reserve (
      n * (parameters.guess_neighbours + parameters.shape_neighbours + parameters.segments.neighbours));
  KnnIndex::Result by_guess, by_segment;
  if (parameters.guess_neighbours > 0)
    by_guess = target.points.search (source_in_target, parameters.guess_neighbours);
  // Points with a segment hypothesis, moved by it, as one compact batch.
  std::vector<Eigen::Index> segment_column (static_cast<std::size_t> (n), -1);
  Eigen::Matrix2Xd moved (2, n);
  Eigen::Index moved_count = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (has_segment_motion[i]) {
      segment_column[i] = moved_count;
      moved.col (moved_count++) = source_in_target.col (i) + segment_translation.col (i);
    }
  if (parameters.segments.neighbours > 0 && moved_count > 0)
    by_segment = target.points.search (moved.leftCols (moved_count), parameters.segments.neighbours);
  for (Eigen::Index i = 0; i < n; ++i) {
    appendNew (by_guess.indices, by_guess.indices.rows (), i, candidates);
    appendNew (shape_neighbours.indices, parameters.shape_neighbours, i, candidates);
    appendNew (by_segment.indices, by_segment.indices.rows (), segment_column[i], candidates);
    candidates.offsets.push_back (static_cast<int> (candidates.targets.size ()));
  }
  return candidates;
}

std::vector<int>
matchStates (const Candidates& candidates, const std::vector<int>& matches)
{
  if (static_cast<int> (matches.size ()) != candidates.size ())
    throw std::invalid_argument ("[pcl_crf::matching::matchStates] " + std::to_string (matches.size ()) +
                                 " matches for the candidates of " + std::to_string (candidates.size ()) +
                                 " source points: give one per source point");
  std::vector<int> states (static_cast<std::size_t> (candidates.size ()));
  for (int i = 0; i < candidates.size (); ++i) {
    const int c = matches[i] == kNoMatch ? -1 : candidates.find (i, matches[i]);
    states[i] = c >= 0 ? c : candidates.count (i);
  }
  return states;
}

double
candidateRecall (const Candidates& candidates, const std::vector<int>& true_matches)
{
  int matched = 0, found = 0;
  for (int i = 0; i < candidates.size () && i < static_cast<int> (true_matches.size ()); ++i) {
    if (true_matches[i] < 0)
      continue;
    ++matched;
    found += candidates.find (i, true_matches[i]) >= 0 ? 1 : 0;
  }
  return matched == 0 ? 1.0 : static_cast<double> (found) / matched;
}

}  // namespace matching
}  // namespace pcl_crf
