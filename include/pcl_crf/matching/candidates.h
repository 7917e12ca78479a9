#pragma once

#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/segment_motions.h>
#include <pcl_crf/matching/shape_neighbours.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief How many candidate target points each source point gets. */
struct CandidateParameters
{
  /** k nearest target points of the source point moved by the current motion
   *  (the odometry guess in pass 1) [count]; default 4. */
  int guess_neighbours = 4;
  /** k nearest target points in shape space (shapeEmbedding) [count]; default 2.
   *  These find matches the motion misses: corners and ends of moving objects. */
  int shape_neighbours = 2;
  /** weight of a point's position in the shape embedding, as the displacement
   *  that counts as much as a unit shape difference [m]; default 10 (a car at
   *  15 m/s moves ~5 m between scans 0.3 s apart). 0 or +inf: shape only. */
  double shape_position_scale = 10.0;
  /** the segment motion hypotheses (moving objects). */
  SegmentMotionParameters segments;
};

/** \brief Candidate target points of every source point, stored flat
 *  (compressed rows): the candidates of source point i are
 *  targets[offsets[i]] … targets[offsets[i + 1] − 1], guess neighbours first
 *  (nearest first), then shape neighbours, then the neighbours under the point's
 *  segment motion hypothesis, without duplicates.
 *
 *  \code
 *  const pcl_crf::matching::PassGeometry pass = pcl_crf::matching::preparePass (source, target, T_guess, T_guess, {});
 *  for (int c = 0; c < pass.candidates.count (i); ++c)
 *    use (pass.candidates.target (i, c));           // target index of candidate c of source point i
 *  const double recall = pcl_crf::matching::candidateRecall (pass.candidates, pair.source_match);
 *  \endcode
 */
struct Candidates
{
  std::vector<int> offsets{0};
  std::vector<int> targets;

  /** \brief Number of source points. */
  int
  size () const { return static_cast<int> (offsets.size ()) - 1; }

  /** \brief Number of candidates of source point i. */
  int
  count (int i) const { return offsets[i + 1] - offsets[i]; }

  /** \brief Target index of candidate c of source point i. */
  int
  target (int i, int c) const { return targets[offsets[i] + c]; }

  /** \brief Position of target point j among the candidates of i, or −1. */
  int
  find (int i, int j) const;
};

/** \brief Rows a shape embedding holds (see shapeEmbedding). */
int
shapeEmbeddingDimension ();

/** \brief Points of a scan in the space where shape neighbours are searched:
 *  the turning angles at offsets 1, 3, 5 [rad], the distances to the 1st and 3rd
 *  neighbour on either side compressed as log(1 + d / 0.1 m), and the position
 *  divided by \a position_scale (omitted as 0 when the scale is 0 or +inf).
 *  \param[in] shape the scan's computeShapeFeatures
 *  \param[in] points the scan's points in a common frame (the target frame) [m]
 *  \param[in] position_scale CandidateParameters::shape_position_scale [m]
 *  \throws std::invalid_argument when \a shape is not kShapeFeatureCount x points.cols ().
 */
Eigen::MatrixXd
shapeEmbedding (const Eigen::MatrixXd& shape, const Eigen::Matrix2Xd& points, double position_scale);

/** \brief Target-scan search structures, built once per target scan. */
struct TargetIndex
{
  KnnIndex points;
  KnnIndex shapes;
};

/** \brief Builds the candidate sets with one batched kNN query per kind.
 *  \param[in] source_in_target source points moved into the target frame by the current motion [m]
 *  \param[in] shape_neighbours the source's shape neighbours (same motion; the first
 *             CandidateParameters::shape_neighbours of each column are used)
 *  \param[in] segment_translation per source point: its segment motion hypothesis [m]
 *  \param[in] has_segment_motion per source point: whether it has one (segmentMotionHypotheses)
 *  \param[in] target the target's indices (points: target points, shapes: their embedding)
 *  \param[in] parameters neighbour counts
 */
Candidates
findCandidates (const Eigen::Matrix2Xd& source_in_target, const ShapeNeighbours& shape_neighbours,
                const Eigen::Matrix2Xd& segment_translation, const std::vector<bool>& has_segment_motion,
                const TargetIndex& target, const CandidateParameters& parameters);

/** \brief The chain state of every source point's match: the position of matches[i]
 *  among i's candidates, or the outlier state (count (i)) for kNoMatch or a target
 *  point that is not a candidate. \throws std::invalid_argument when \a matches is not
 *  one per source point. */
std::vector<int>
matchStates (const Candidates& candidates, const std::vector<int>& matches);

/** \brief Fraction of source points with a true match whose match is a candidate
 *  (1 when no source point has a true match). */
double
candidateRecall (const Candidates& candidates, const std::vector<int>& true_matches);

}  // namespace matching
}  // namespace pcl_crf
