#pragma once
// Internal: what the free-space steps of estimateJoint read of the two scans (their
// segments, what each sensor saw, the target's kd-tree), built once per pair on first
// use and shared by the steps (refuted_clusters.cpp, free_space_objects.cpp,
// slid_segments.cpp, moved_out_points.cpp): they depend on the scans alone, not on the
// clusters the steps edit.

#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>
#include <pcl_crf/matching/segment_motions.h>

#include <optional>
#include <vector>

namespace pcl_crf {
namespace joint {
namespace detail {

/** What one sensor saw: its range profile and the breakpoint distance asked of it. */
struct SensorView
{
  matching::RangeProfile profile;
  matching::BreakpointDistance breakpoint;
};

/** The scans of a pair and what is derived from them alone, each part built when first
 *  asked for (most pairs need only a few). The scans and parameters are referenced. */
class ScanViews
{
public:
  /** \a sensor: the laser's beams, whose field of view the range profiles take
   *  (beam_count 0: unknown, inferred from the returns). */
  ScanViews (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
             const matching::SegmentMotionParameters& parameters, const SensorInfo& sensor = {});

  const Eigen::Matrix2Xd&
  source () const
  {
    return source_;
  }

  const Eigen::Matrix2Xd&
  target () const
  {
    return target_;
  }

  const matching::SegmentMotionParameters&
  parameters () const
  {
    return parameters_;
  }

  /** matching::segmentScan () of each scan with the parameters' breakpoint settings,
   *  split across missing returns (matching::BeamGaps::MissingReturns, runs of at most
   *  SegmentMotionParameters::max_missing_returns beams): the steps read
   *  segments as the outlines of what each sensor saw. */
  const std::vector<matching::ScanSegment>&
  sourceSegments () const;

  const std::vector<matching::ScanSegment>&
  targetSegments () const;

  /** What the source / target sensor saw (matching::makeRangeProfile () with the sensor). */
  const SensorView&
  sourceView () const;

  const SensorView&
  targetView () const;

  /** A kd-tree over the target's points. */
  const KnnIndex&
  targetPoints () const;

private:
  const std::vector<matching::ScanSegment>&
  segments (std::optional<std::vector<matching::ScanSegment>>& cache, const Eigen::Matrix2Xd& scan) const;

  const SensorView&
  view (std::optional<SensorView>& cache, const Eigen::Matrix2Xd& scan) const;

  const Eigen::Matrix2Xd& source_;
  const Eigen::Matrix2Xd& target_;
  const matching::SegmentMotionParameters& parameters_;
  const SensorInfo sensor_;
  mutable std::optional<std::vector<matching::ScanSegment>> source_segments_, target_segments_;
  mutable std::optional<SensorView> source_view_, target_view_;
  mutable std::optional<KnnIndex> target_points_;
};

/** Per point of a segment placed in the target frame (\a points, in the segment's
 *  order): whether the target's beam to it grazes the segment, meeting its local
 *  direction (through its neighbours on the segment) at less than the breakpoint angle.
 *  There a range difference of a few centimetres moves the surface by whole beams, so
 *  neither a return beyond the point nor one on it tells whether the segment is there. */
std::vector<bool>
grazedPoints (const Eigen::Matrix2Xd& points, double breakpoint_angle);

/** Which of the target's beams say that it saw through a point placed in its frame. */
enum class SeenThrough
{
  /** a return beyond it (matching::seesThroughToAReturn ()): a beam without a return
   *  says nothing, real lasers drop returns where the scene is not free. */
  ToAReturn,
  /** matching::seesThroughFirmly (): a return beyond it, or beams without one that
   *  are not beside the return of a surface whose edge they may have dropped. */
  Firmly,
  /** not asked (TargetPlacement::seen_through all false): for a caller that does not read it. */
  NotAsked
};

/** Whether the sensor of \a seen saw through \a point (in its frame) by \a test (false
 *  when not asked). */
bool
sawThrough (const SensorView& seen, const Eigen::Vector2d& point, SeenThrough test);

/** What the target scan says of points placed in its frame. */
struct TargetPlacement
{
  /** the points [m, target frame]. */
  Eigen::Matrix2Xd points;
  /** the nearest target point of each. */
  KnnIndex::Result nearest;
  /** per point: in the target's field of view and not grazed (grazedPoints ()), so that
   *  the target's beams tell whether it is there. */
  std::vector<bool> in_view;
  /** per point: a target point within its overlap radius. */
  std::vector<bool> explained;
  /** per point: the target saw through it (SeenThrough, the test asked for). */
  std::vector<bool> seen_through;
};

/** \a points (consecutive points of one surface, in the segment's order, placed in the
 *  target frame) as the target sees them; \a radii_squared their squared overlap
 *  radii (squaredOverlapRadii ()), \a test which beams saw through them. One batched
 *  nearest-point query. */
TargetPlacement
placeInTarget (Eigen::Matrix2Xd points, const std::vector<double>& radii_squared, const ScanViews& views,
               SeenThrough test = SeenThrough::ToAReturn);

/** The squared overlap radius (matching::overlapRadius () of its spacing on the segment)
 *  of every source point of \a segment. */
std::vector<double>
squaredOverlapRadii (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
                     const matching::SegmentMotionParameters& parameters);

/** The same for \a members only, points of \a segment, in their order. */
std::vector<double>
squaredOverlapRadii (const Eigen::Matrix2Xd& source, const matching::ScanSegment& segment,
                     const std::vector<int>& members, const matching::SegmentMotionParameters& parameters);

/** The points of \a segment labelled \a l in \a labels (one per source point), in order. */
inline std::vector<int>
segmentPointsLabelled (const matching::ScanSegment& segment, const std::vector<int>& labels, int l)
{
  std::vector<int> points;
  for (int i = segment.begin; i < segment.end; ++i)
    if (labels[i] == l)
      points.push_back (i);
  return points;
}

/** Point-to-point ICP of the source points \a members from T: each round pairs every
 *  point with its nearest target point (one batched query), drops the pairs farther
 *  apart than \a gate, and refits the motion in closed form (eq. 6); at most 20 rounds,
 *  until no entry of the motion's matrix changes by 1e-6. */
Rigid2d
icpOnNearestPoints (const Eigen::Matrix2Xd& source, const std::vector<int>& members, const KnnIndex& target_points,
                    Rigid2d T, double gate);

/** The free-space steps of joint_estimation.h on shared views (estimateJoint runs them
 *  in turn on one pair); the public functions build their own. */
int
removeClustersTheTargetSeesThrough (const ScanViews& views, JointResult& result);

int
removeClustersOnTheStaticOutline (const ScanViews& views, JointResult& result);

/** The static world's answer to a motion that separateObjectsInFreeSpace () found for
 *  some of its points: the slight-motion test with the roles swapped (staticFitRefutes ()). */
struct StaticFitCheck
{
  SlightMotionTest test;
  /** the fewest static points a source segment needs to count in the static motion's
   *  misfit (as separateSegmentsThatMovedSlightly ()'s min_points). */
  int min_points = 1;
};

/** Whether the static motion fits the source points \a members to the target's outline
 *  better than motion \a T does, by the evidence separateSegmentsThatMovedSlightly ()
 *  asks of the opposite decision: over the members the static motion places in the
 *  target's view, neither hidden behind a return nor beyond a surface's end, and that T
 *  places in view too, D = Σ (r(T)² − r(T_static)²) / σ² ≥ test.min_deviance and
 *  ≥ test.min_mean_deviance per point (r the distance to the outline, capped at
 *  overlap_radius; σ² as that test takes it, with the static world's current misfit).
 *  False without a static world. \a check is taken as valid (checkStaticFitCheck ()). */
bool
staticFitRefutes (const ScanViews& views, const JointResult& result, const std::vector<int>& members, const Rigid2d& T,
                  const StaticFitCheck& check);

/** Throws std::invalid_argument, naming \a function, unless \a check's test and
 *  min_points are in range (as separateSegmentsThatMovedSlightly () asks them). */
void
checkStaticFitCheck (const char* function, const StaticFitCheck& check);

/** \a check, when given, drops every motion found that the static fit refutes
 *  (staticFitRefutes ()). */
int
separateObjectsInFreeSpace (const ScanViews& views, JointResult& result, const StaticFitCheck* check = nullptr);

int
separateSegmentsTheTargetSeesThrough (const ScanViews& views, int min_seen_through, JointResult& result);

int
separatePointsTheTargetSeesThrough (const ScanViews& views, JointResult& result);

int
mergeAdjacentClustersThatMoveAlike (const ScanViews& views, JointResult& result);
int
extendMovingClustersOverTheirSurfaces (const ScanViews& views, JointResult& result);

int
markPointsThatMovedAway (const ScanViews& views, JointResult& result);

/** separateSegmentsThatMovedSlightly () on shared views. */
int
separateSegmentsThatMovedSlightly (const ScanViews& views, const SlightMotionTest& test, int min_points,
                                   JointResult& result);

/** keepLadderClustersTheFinalClusteringMerged () with \a min_points for min_segment_points
 *  (estimateJoint counts at the model's resolution: k times as many on scans thinned by k). */
int
keepLadderClustersTheFinalClusteringMerged (const ScanViews& views, const JointResult& ladder, int min_points,
                                            JointResult& result);

}  // namespace detail
}  // namespace joint
}  // namespace pcl_crf
