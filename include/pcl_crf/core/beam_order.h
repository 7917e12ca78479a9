#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {

/** \brief How far a scan's points turn back on their way round the sensor: the bearing
 *  steps between consecutive points (each wrapped into (−π, π]) against the direction
 *  most of the way goes, as a fraction of that way (0: every step goes one way).
 *  Points at the sensor's origin have no bearing and are passed over. 0 with fewer
 *  than three points that have one.
 */
double
bearingBacktrack (const Eigen::Matrix2Xd& points);

/** \brief Whether a scan's points are in the order the CRF chains read: beam order,
 *  counter-clockwise. Their bearings go round counter-clockwise, starting anywhere,
 *  and turn back by at most kBeamOrderBacktrack of their way (bearingBacktrack ()).
 *
 *  A scan as a laser measures it turns back by nothing, or by a little where its
 *  bearings jitter or its points sit in a frame off the sensor's; points in no order
 *  turn back about as much as they go forward (1). Measured: every scan of the shipped
 *  splits, the nine CARMEN logs and the two car bags 0; the test split's scans
 *  shuffled 0.96–1.00, sorted by x in 0.5 m columns (as a voxel grid leaves them)
 *  0.93–0.98; the CARMEN intel scans moved 0.3 m off their sensor up to 0.22, 1 m off
 *  up to 0.53. The chains on the shuffled and x-sorted test split found V 0.19 and 0.44,
 *  where beam order gives 0.86.
 *
 *  A scan in beam order whose bearings go clockwise (a laser mounted upside down, or a
 *  converter that lists the beams the other way) is not: its shape features (turning
 *  angles, the neighbours before and after a point) would read mirrored against the
 *  counter-clockwise scans the models learned from. beamOrder () reads it backwards.
 */
bool
inBeamOrder (const Eigen::Matrix2Xd& points);

/** \brief The largest bearingBacktrack () of a scan in beam order (inBeamOrder ()):
 *  halfway between a laser's order (0) and no order (1). */
constexpr double kBeamOrderBacktrack = 0.5;

/** \brief The order to read a scan's points in for the CRF chains: 0, 1, …, n − 1 when
 *  it is in beam order counter-clockwise (inBeamOrder ()); n − 1, …, 0 when it is in
 *  beam order clockwise; otherwise its points sorted by bearing, counter-clockwise,
 *  from the one after the widest gap between bearings (a partial field of view's
 *  back), points at the origin first and equal bearings in their index order
 *  (decreasing when the scan's bearings go mostly clockwise). A scan whose listing
 *  starts between two neighbouring beams that both returned (a 360° laser listing its
 *  circle from any beam) starts instead after its widest break: the widest gap between
 *  the bearings of neighbouring points (a sector without a return), or, with a return
 *  on every beam, the widest jump between neighbouring points. Its chains are then cut
 *  where its surfaces break, from whichever such beam the listing starts, and not
 *  through the object in front of that beam. A scan and the same scan
 *  listed the other way round are read alike, but for a scan whose steps all go no way
 *  (every point on one bearing), which is read as listed.
 *
 *  \code
 *  const std::vector<int> order = pcl_crf::beamOrder (scan);
 *  Eigen::Matrix2Xd chain (2, scan.cols ());
 *  for (Eigen::Index k = 0; k < scan.cols (); ++k)
 *    chain.col (k) = scan.col (order[k]);  // a result for chain point k is one for scan point order[k]
 *  \endcode
 */
std::vector<int>
beamOrder (const Eigen::Matrix2Xd& points);

}  // namespace pcl_crf
