#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

namespace pcl_crf {
namespace matching {

/** \brief What a scan's sensor saw in every direction: the range of each return by
 *  bearing, for asking whether the sensor saw through a point (a free-space test, as
 *  in range-image differencing).
 *
 *  Scans store returns only, so a direction without a return nearby is one whose beam
 *  saw nothing up to the sensor's range: free up to the farthest return of the scan.
 *
 *  \code
 *  const pcl_crf::matching::RangeProfile seen = pcl_crf::matching::makeRangeProfile (source_points);
 *  // a target point the static motion maps where the source saw through has moved in
 *  const bool moved_in = pcl_crf::matching::seesThrough (seen, T_static.inverse () * t, 0.1745, 0.01);
 *  \endcode
 */
struct RangeProfile
{
  /** bearings atan2 (y, x) of the returns, increasing [rad, (−π, π]]. */
  Eigen::VectorXd bearings;
  /** ranges of the returns in the same order [m]. */
  Eigen::VectorXd ranges;
  /** the typical angle between neighbouring returns, their median step [rad]
   *  (0 with fewer than two returns). */
  double step = 0.0;
  /** the farthest return [m]: beyond it, a direction without a return says nothing. */
  double max_range = 0.0;
  /** true when the field of view goes all round: bearings wrap. Either no gap between
   *  the returns is wider than 1.5 steps, or the sensor's beams go all round. Otherwise
   *  the field of view runs from the first to the last bearing, the widest gap between
   *  the returns being the sensor's back. */
  bool full_circle = false;
};

/** \brief The range profile of a scan in its own sensor frame (any point order).
 *  \throws std::invalid_argument for a non-finite point. */
RangeProfile
makeRangeProfile (const Eigen::Matrix2Xd& scan);

/** \brief Whether \a sensor describes its beams: false for beam_count 0 (unknown).
 *  \throws std::invalid_argument for a beam_count of 1 or below 0, a non-finite
 *          angle_min, or a non-finite or zero angle_increment. */
bool
describesBeams (const SensorInfo& sensor);

/** \brief The range profile of a scan whose sensor is known (SensorInfo: beam_count
 *  beams from angle_min, angle_increment apart). A sensor whose beams go all round has
 *  no back: its profile is a full circle whatever its returns, so that a sector a 360°
 *  laser saw nothing in (open space beyond its range, or a dark surface) is not taken
 *  for its back, and a point there counts as seen through by seesThrough () (not by
 *  seesThroughToAReturn ()). For other sensors, and for beam_count 0 (unknown), the
 *  profile is makeRangeProfile (scan): the widest gap between the returns is the back
 *  (beams at the edge of the view that saw nothing stay outside it).
 *  \throws std::invalid_argument for a non-finite point, or a sensor describesBeams ()
 *          rejects. */
RangeProfile
makeRangeProfile (const Eigen::Matrix2Xd& scan, const SensorInfo& sensor);

/** \brief true when the profile's sensor saw through \a point (in its frame): the
 *  point lies inside the field of view and either every return within one step of
 *  its bearing lies farther than it by more than the breakpoint distance
 *  r sin Δφ / sin(λ − Δφ) + 3σ of the adaptive breakpoint detector (so it is on no
 *  surface the sensor saw; Δφ the step, r the point's range), or no return lies within
 *  one step and the point lies nearer than the farthest return by that distance (the
 *  beams there saw nothing in range). False for profiles of fewer than two returns.
 *  \param[in] breakpoint_angle λ, the worst incidence angle on one surface [rad]
 *  \param[in] range_noise σ, the laser's range noise [m] */
bool
seesThrough (const RangeProfile& profile, const Eigen::Vector2d& point, double breakpoint_angle, double range_noise);

/** \brief The breakpoint distance of seesThrough () as slope · r + offset, for asking
 *  about many points: slope sin Δφ / sin(λ − Δφ), offset 3σ (slope +inf when λ ≤ Δφ). */
struct BreakpointDistance
{
  double slope = 0.0;
  double offset = 0.0;
  /** λ [rad], for slopeAcross (). */
  double breakpoint_angle = 0.0;

  /** \brief The slope across a bearing difference \a apart [rad] instead of one step:
   *  sin(apart) / sin(λ − apart), +inf when λ ≤ apart. */
  double
  slopeAcross (double apart) const;
};

BreakpointDistance
breakpointDistance (const RangeProfile& profile, double breakpoint_angle, double range_noise);

/** \brief Whether the bearing of \a point lies within the scan's field of view: between its
 *  first and last return (after its widest gap), anywhere when it goes all round;
 *  false with fewer than two returns. */
bool
inFieldOfView (const RangeProfile& profile, const Eigen::Vector2d& point);

/** \brief seesThrough () with the breakpoint distance computed once. */
bool
seesThrough (const RangeProfile& profile, const Eigen::Vector2d& point, const BreakpointDistance& distance);

/** \brief seesThrough () without the beams a surface's edge may have dropped. A real
 *  laser drops the return of a beam that grazes an edge (mixed pixels), so a point one
 *  beam past the last return of a surface it continues says nothing of free space there
 *  (a parked car's edge returns, dropped at one end in one scan and at the other in the
 *  next, look like a slide of one beam). False as well
 *  - where no return lies within one step of the point's bearing but the nearest return
 *    on either side, within two steps, lies within the breakpoint distance of it;
 *  - where the returns within one step all lie farther (seen through) but the nearest
 *    return on the other side lies one to two steps away, past a beam without a return,
 *    within the breakpoint distance for their bearing difference Δφ
 *    (BreakpointDistance::slopeAcross ()): the edge of that return's surface may lie
 *    anywhere between the dropped beam and the one that saw past it, and the point
 *    with it (a round post seen from two places shows the second sensor a part of its
 *    outline just past the first one's last return). */
bool
seesThroughFirmly (const RangeProfile& profile, const Eigen::Vector2d& point, const BreakpointDistance& distance);

/** \brief seesThrough () on the evidence of returns only: true when the point lies inside
 *  the field of view, some return lies within one step of its bearing and every such
 *  return lies farther than it by more than the breakpoint distance. A direction without
 *  a return says nothing here: real lasers drop returns (dark, glossy or glass surfaces)
 *  where the scene is not free. */
bool
seesThroughToAReturn (const RangeProfile& profile, const Eigen::Vector2d& point, const BreakpointDistance& distance);

/** \brief The mirror of seesThroughToAReturn (): true when the point lies inside the field
 *  of view, some return lies within one step of its bearing and every such return lies
 *  nearer than it by more than the breakpoint distance (r sin Δφ / sin(λ − Δφ) + 3σ, r the
 *  return's range, the smaller as in the breakpoint detector): the sensor could not have
 *  seen it, something stood in front of it. */
bool
hiddenBehindAReturn (const RangeProfile& profile, const Eigen::Vector2d& point, const BreakpointDistance& distance);

}  // namespace matching
}  // namespace pcl_crf
