#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/evaluation/method.h>

#include <memory>
#include <vector>

namespace pcl_crf {

/** \brief Whether a point at \a range [m] is a return of a laser whose maximum range
 *  is \a range_max [m]: farther than 0 (a point at the sensor itself is no surface:
 *  drivers report a range of 0 for a beam without a return, which a conversion to x, y
 *  puts at the origin) and nearer than range_max (ROS's sensor_msgs/LaserScan
 *  convention, which the log readers follow; a laser reports range_max or more for a
 *  beam without one), by more than 1e-5 of it (a point stored at range_max in single
 *  precision may read back a few ulp nearer). Without a positive finite range_max every
 *  point but the origin is a return. */
bool
isReturn (double range, double range_max);

/** \brief A pair reduced to its returns (isReturn with the pair's SensorInfo::range_max),
 *  each position once, with where each kept point came from. The reduced pair's labels
 *  and true matches are the kept points' (a true match onto a point left out becomes
 *  kNoMatch).
 *
 *  A dataset should leave beams without a return out (data/README.md); one converted
 *  with them kept as points at the maximum range would otherwise show every method an
 *  arc that moves with the sensor, and points at the origin (a range of 0) would be
 *  links of every chain. A point at the exact coordinates of a return before
 *  it in beam order (beamOrder (), so a scan listed either way round keeps the same
 *  copy; a converter's placeholder for a beam without a return, say) is left out too: it is no return of another beam, and tens of thousands of them made
 *  every kd-tree search visit them all (exact ties at distance 0 prune nothing: a
 *  minute per pair).
 *
 *  A scan in no beam order (inBeamOrder () in pcl_crf/core/beam_order.h: shuffled, or
 *  sorted by a voxel grid) is put in one (beamOrder ()): the chains follow the order of
 *  the points, and in no order they lost most movers (V 0.19 on the shuffled test split).
 *  A scan listed clockwise is read backwards, counter-clockwise as the models learned.
 */
struct PairReturns
{
  ScanPair pair;
  /** per kept source / target point: its index in the original scan, increasing (in
   *  beam order, beamOrder (), when the scan was in no beam order or listed clockwise). */
  std::vector<int> source_index;
  std::vector<int> target_index;
  /** the original scans' sizes. */
  int source_size = 0;
  int target_size = 0;

  /** \brief true when the reduced pair is the pair: no point left out or reordered. */
  bool
  keepsEveryPoint () const
  {
    const auto inOrder = [] (const std::vector<int>& index, int size) {
      for (std::size_t k = 0; k < index.size (); ++k)
        if (index[k] != static_cast<int> (k))
          return false;
      return static_cast<int> (index.size ()) == size;
    };
    return inOrder (source_index, source_size) && inOrder (target_index, target_size);
  }
};

/** \brief The returns of \a pair (see PairReturns). */
PairReturns
keepReturns (const ScanPair& pair);

/** \brief A prediction for the reduced pair of \a returns as one for the original pair:
 *  the points left out saw the background (or repeat a kept point), so they join the
 *  predicted static world (outliers when there is none) without a match; matches index
 *  the original target scan.
 *  \throws std::invalid_argument when \a reduced does not fit the reduced pair. */
Prediction
liftToAllPoints (const Prediction& reduced, const PairReturns& returns);

/** \brief The prediction for a pair one of whose scans holds no return (a laser
 *  blinded for a scan, say), which leaves nothing to estimate from: the odometry is the
 *  sensor's motion, and every source point is in the static world, moved by it, with
 *  no match made (an empty Prediction::source_match: the pair's association is not
 *  scored).
 *  \throws std::invalid_argument naming the pair when its odometry is unusable. */
Prediction
predictFromOdometry (const ScanPair& pair);

/** \brief \a method seeing only the returns of every pair (keepReturns) when it learns
 *  and when it predicts; its predictions are lifted back to every point
 *  (liftToAllPoints: the others join the static world, unmatched). Pairs without points
 *  at or beyond the maximum range, without repeated points and in beam order go to
 *  \a method unchanged. A pair with no return in one of its scans is predicted from its
 *  odometry (predictFromOdometry) and left out of training (std::invalid_argument when
 *  every training pair is such a pair). createEvaluationMethod () wraps every method
 *  in it. */
std::unique_ptr<EvaluationMethod>
ignoringNoReturnPoints (std::unique_ptr<EvaluationMethod> method);

}  // namespace pcl_crf
