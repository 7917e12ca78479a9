#pragma once

#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/matching/scan_segments.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief Settings of the segment motion hypotheses, the candidate source that
 *  finds the matches of moving objects (cars move metres between scans, so
 *  neither the guess neighbours nor local shape reach their true matches).
 */
struct SegmentMotionParameters
{
  /** candidates per source point under its segment's motion hypothesis [count]
   *  (0 disables the hypotheses); default 2. */
  int neighbours = 2;
  /** worst incidence angle λ of the adaptive breakpoint detector (Borges & Aldon,
   *  2004): consecutive points farther apart than r sin Δφ / sin(λ − Δφ) + 3σ are
   *  on different segments [rad]; default 10° = 0.1745. */
  double breakpoint_angle = 0.17453292519943295;
  /** range noise σ of the laser [m]; default 0.01. */
  double range_noise = 0.01;
  /** fewest points of a segment that gets hypotheses [count]; default 3. */
  int min_segment_points = 3;
  /** largest displacement of an object between the scans beyond the static
   *  motion, about top speed × scan interval [m]; default 6. */
  double max_displacement = 6.0;
  /** top speed of a moving object [m/s]: when the time between the scans is known
   *  (MotionGuess::interval), an object moves at most max_speed × interval, and the
   *  hypotheses and searches reach no farther than the smaller of that and
   *  max_displacement (limitToInterval ()); 0: no such bound. Default 30 (108 km/h,
   *  twice the fastest car of the simulator, so that its pairs, 0.2–0.4 s apart, keep
   *  the 6 m bound). */
  double max_speed = 30.0;
  /** the longest run of beams without a return that one surface may have dropped
   *  [beams]: the joint model's free-space steps, which split scans across missing
   *  returns (BeamGaps::MissingReturns), take a longer run for an opening between two
   *  surfaces. A dark surface may drop half its returns; ten in a row then happen once
   *  in a thousand runs. A pedestrian 20 m away and a wall 30 m away, 33 empty
   *  0.25° beams apart, pass the breakpoint bound across the gap (one step's distance
   *  per beam) but are not one surface. −1: no bound, as models written before this
   *  setting; default 10. */
  int max_missing_returns = 10;
  /** the most a moved source point may lie from a target point and still be
   *  explained [m]; default 0.15 (about two beam spacings at 10 m). */
  double overlap_radius = 0.15;
  /** the overlap radius in point spacings: a moved source point is explained when a
   *  target point lies within this many times the point's spacing on its surface
   *  (the larger distance to its neighbours on its segment), at least 3 range_noise
   *  and at most overlap_radius (see overlapRadius ()). A point on the same surface
   *  has a target point within about one spacing whatever the scene's scale, so the
   *  radius follows the sensor's resolution (0.15 m reaches 5–10 beams on a
   *  1/10-scale car 0.5 m away). 0: overlap_radius everywhere, as models written
   *  before this setting [spacings]; default 2. */
  double overlap_spacings = 2.0;
};

/** \brief What makes segment parameters unusable, or "" when nothing does: each
 *  setting outside the range its documentation gives (a NaN included).
 *  \code
 *  const std::string problem = pcl_crf::matching::segmentParametersProblem (parameters);
 *  \endcode */
std::string
segmentParametersProblem (const SegmentMotionParameters& parameters);

/** \brief The radius within which a target point explains a moved source point
 *  whose neighbours on its surface lie up to \a point_spacing away:
 *  min(overlap_radius, max(3 range_noise, overlap_spacings · point_spacing)), or
 *  overlap_radius when overlap_spacings is 0 [m].
 *
 *  \code
 *  const double spacing = pcl_crf::matching::pointSpacing (source, i, 0, source.cols ());
 *  const double radius = pcl_crf::matching::overlapRadius (parameters, spacing);
 *  \endcode
 */
double
overlapRadius (const SegmentMotionParameters& parameters, double point_spacing);

/** \brief \a parameters with max_displacement bounded by how far an object moving at
 *  max_speed travels in \a interval seconds (unchanged when the interval is unknown, 0,
 *  or max_speed is 0). Every estimator that takes the interval goes through here.
 *  \throws std::invalid_argument for a negative or non-finite interval.
 *
 *  \code
 *  const pcl_crf::matching::SegmentMotionParameters bounded =
 *      pcl_crf::matching::limitToInterval (parameters, pair.odometry.interval);  // 0.1 s: 3 m
 *  \endcode
 */
SegmentMotionParameters
limitToInterval (SegmentMotionParameters parameters, double interval);

/** \brief The larger distance from point i to its neighbours i − 1 and i + 1 within
 *  the run [begin, end) of \a points (0 when it has none there) [m].
 *  \throws std::invalid_argument when i is not in the run, or the run not in the scan. */
double
pointSpacing (const Eigen::Matrix2Xd& points, Eigen::Index i, Eigen::Index begin, Eigen::Index end);

/** \brief Candidate translations (target frame) of a source segment whose ends lie at
 *  \a start and \a finish: the zero translation (the current motion itself) first, then
 *  every one that puts a trusted object end (objectEnds ()) of the segment onto the same
 *  trusted end of a target segment (≥ min_segment_points) within max_displacement.
 *
 *  \param[in] start the segment's first point moved by the current motion [m]
 *  \param[in] finish its last point moved by the current motion [m]
 *  \param[in] trusted which of its ends are object ends (objectEnds () of the source)
 *  \param[in] target_scan target points [m]
 *  \param[in] target_segments segmentScan of the target
 *  \param[in] parameters max_displacement, min_segment_points
 */
std::vector<Eigen::Vector2d>
endAlignments (const Eigen::Vector2d& start, const Eigen::Vector2d& finish, const SegmentEnds& trusted,
               const Eigen::Matrix2Xd& target_scan, const std::vector<ScanSegment>& target_segments,
               const SegmentMotionParameters& parameters);

/** \brief Per source point: its segment's motion hypothesis and how well it and
 *  the current motion explain the segment.
 *
 *  \code
 *  const pcl_crf::matching::SegmentMotions motions = pcl_crf::matching::segmentMotionHypotheses (
 *      source, T_current * source, target, target_segments, target_index, {});
 *  if (motions.has_hypothesis[i])
 *    const Eigen::Vector2d predicted = T_current * source.col (i) + motions.translation.col (i);
 *  \endcode
 */
struct SegmentMotions
{
  /** the hypothesis, a translation beyond the current motion [m] (0 when none). */
  Eigen::Matrix2Xd translation;
  /** whether the point's segment has a hypothesis. */
  std::vector<bool> has_hypothesis;
  /** fraction of the segment's scoring samples explained by the current motion
   *  (1 for segments too short to score). */
  Eigen::VectorXd current_support;
  /** same for the hypothesis (= current_support without one). */
  Eigen::VectorXd hypothesis_support;
};

/** \brief The translation hypothesis (target frame) of every source point's
 *  segment, beyond the current motion.
 *
 *  For every source segment (≥ min_segment_points) the hypotheses align one of its
 *  end points with the same end of a target segment within max_displacement
 *  (Borges & Aldon's segments, matched by their ends); each is scored by the
 *  fraction of (up to 10 evenly spread) segment points with a target point within
 *  their overlap radius (overlapRadius () of their spacing on the segment), and the
 *  best one is kept when it explains more than the current motion does. All scores come from one batched kNN query.
 *
 *  \param[in] source_scan source points in the source frame (for the breakpoints) [m]
 *  \param[in] source_current the same points moved by the current motion estimate [m]
 *  \param[in] target_scan target points [m]
 *  \param[in] target_segments segmentScan of the target
 *  \param[in] target_index kNN index over the target points
 *  \param[in] parameters the settings
 */
SegmentMotions
segmentMotionHypotheses (const Eigen::Matrix2Xd& source_scan, const Eigen::Matrix2Xd& source_current,
                         const Eigen::Matrix2Xd& target_scan, const std::vector<ScanSegment>& target_segments,
                         const KnnIndex& target_index, const SegmentMotionParameters& parameters);

}  // namespace matching
}  // namespace pcl_crf
