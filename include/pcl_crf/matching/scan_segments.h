#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief A run [begin, end) of consecutive scan points between two breakpoints
 *  (see segmentScan for an example). */
struct ScanSegment
{
  int begin = 0;
  int end = 0;

  int
  size () const { return end - begin; }
};

/** \brief What a bearing gap between consecutive points wider than the sensor's step
 *  means to segmentScan (). */
enum class BeamGaps
{
  /** Δφ is measured from the points, whatever the gap (CRF-Matching's segments, which
   *  only propose motion hypotheses; its shipped models were trained on them). */
  Measured,
  /** A gap wider than 1.5 steps (the step: the median bearing step between consecutive
   *  points) spans missing returns: the beams in it saw no surface, so each allows one
   *  step's breakpoint distance. Measured, the bound over the whole gap grows without
   *  limit as the gap nears λ (r sin 9° / sin 1° ≈ 9 r): a 1/10-scale car 0.4 m away
   *  and a wall 3 m behind it, 9 one-degree beams apart, would be one segment. */
  MissingReturns
};

/** \brief Splits a scan in beam order at the breakpoints of the adaptive
 *  breakpoint detector (Borges & Aldon, 2004): consecutive points p, q are on
 *  different segments when ||q − p|| > r sin Δφ / sin(λ − Δφ) + 3σ, with r the
 *  smaller range and Δφ their bearing difference (across missing returns, see
 *  \a gaps), and whenever Δφ ≥ λ.
 *  \param[in] points 2 x N points in the scan's own sensor frame [m]
 *  \param[in] breakpoint_angle λ, the worst incidence angle on one surface [rad]
 *  \param[in] range_noise σ, the laser's range noise [m]
 *  \param[in] gaps how a gap wider than the sensor's step is bridged
 *  \param[in] max_missing_returns with BeamGaps::MissingReturns, the most beams
 *  without a return that a gap within one segment may span (a longer run is a
 *  breakpoint); −1: any (SegmentMotionParameters::max_missing_returns)
 *  \throws std::invalid_argument for a max_missing_returns below −1, a breakpoint angle
 *  outside (0, π/2] or a range noise that is not a distance ≥ 0 (NaN included)
 *
 *  \code
 *  const auto segments = pcl_crf::matching::segmentScan (pair.source, 0.1745, 0.01);
 *  \endcode
 */
std::vector<ScanSegment>
segmentScan (const Eigen::Matrix2Xd& points, double breakpoint_angle, double range_noise,
             BeamGaps gaps = BeamGaps::Measured, int max_missing_returns = -1);

/** \brief Throws std::invalid_argument naming \a function when a segment of
 *  \a segments is not a run [begin, end), begin < end, of a scan of \a points points. */
void
checkSegments (const char* function, const std::vector<ScanSegment>& segments, Eigen::Index points);

/** \brief The index into \a segments of every one of \a points points (−1 for a point
 *  in none of them). \throws std::invalid_argument for a segment outside the scan
 *  (checkSegments ()). */
std::vector<int>
segmentOfEachPoint (const std::vector<ScanSegment>& segments, Eigen::Index points);

/** \brief The longest run of beams without a return between consecutive points of
 *  \a segment: round (Δφ / step) − 1 for each bearing difference Δφ, as segmentScan ()
 *  counts missing returns; 0 when the sensor returned from every beam across it.
 *  \param[in] points the scan in its own sensor frame, beam order [m]
 *  \param[in] segment a run of its points
 *  \param[in] step the sensor's angular step [rad] (RangeProfile::step)
 *  \throws std::invalid_argument when the segment is not a run of the scan's points or
 *          the step is not positive
 *
 *  \code
 *  // a surface the sensor skipped more than single beams on
 *  const bool drops = pcl_crf::matching::longestMissingRun (scan, segment, profile.step) > 1;
 *  \endcode
 */
int
longestMissingRun (const Eigen::Matrix2Xd& points, const ScanSegment& segment, double step);

/** \brief Per segment of segmentScan (..., BeamGaps::MissingReturns), the surface it
 *  belongs to (the index of the surface's first segment): a segment continues an
 *  earlier one hidden behind an occluder, when every point between the earlier one's
 *  last point a and its first point b is nearer to the sensor than both, and a and b
 *  pass the breakpoint test across the occluded beams, each allowing one step's
 *  distance as a missing return does. A car behind a pedestrian shows as two segments
 *  with the pedestrian between them, one surface.
 *  \param[in] points the scan in its own sensor frame, beam order [m]
 *  \param[in] segments its segments (segmentScan () with the same λ and σ)
 *  \param[in] breakpoint_angle λ [rad]
 *  \param[in] range_noise σ [m]
 *  \throws std::invalid_argument when the segments are not consecutive runs of the scan's
 *  points, or for λ and σ out of range as segmentScan ()
 *
 *  \code
 *  const auto segments = pcl_crf::matching::segmentScan (scan, 0.1745, 0.01, pcl_crf::matching::BeamGaps::MissingReturns);
 *  const std::vector<int> surface = pcl_crf::matching::occludedSurfaces (scan, segments, 0.1745, 0.01);
 *  \endcode
 */
std::vector<int>
occludedSurfaces (const Eigen::Matrix2Xd& points, const std::vector<ScanSegment>& segments, double breakpoint_angle,
                  double range_noise);

/** \brief Which ends of a segment are an object's ends rather than an occlusion
 *  or the border of the scan: the point across the breakpoint lies farther from
 *  the sensor (background behind the object's end).
 *  \param[in] points the scan, in its own sensor frame [m]
 */
struct SegmentEnds
{
  bool start = false;
  bool finish = false;
};

SegmentEnds
objectEnds (const Eigen::Matrix2Xd& points, const ScanSegment& segment);

/** \brief Unit normal of the scan's line at every point: perpendicular to the
 *  chord between the points two places before and after it within its segment
 *  (one-sided at the segment's ends); zero for single-point segments.
 */
Eigen::Matrix2Xd
segmentNormals (const Eigen::Matrix2Xd& points, const std::vector<ScanSegment>& segments);

}  // namespace matching
}  // namespace pcl_crf
