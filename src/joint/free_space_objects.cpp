#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Which surface every target point and every target segment lies on. */
struct TargetSurfaces
{
  std::vector<int> of_point;    // per target point: its surface, -1 for none
  std::vector<int> of_segment;  // per target segment: its surface

  /** Numbers the points by \a of_segment. */
  TargetSurfaces (const std::vector<matching::ScanSegment>& segments, Eigen::Index points, std::vector<int> surface)
    : of_point (static_cast<std::size_t> (points), -1), of_segment (std::move (surface))
  {
    for (std::size_t g = 0; g < segments.size (); ++g)
      std::fill (of_point.begin () + segments[g].begin, of_point.begin () + segments[g].end, of_segment[g]);
  }

  TargetSurfaces () = default;

  /** Target segment \a segment's surface holds another segment. */
  bool
  joinsOthers (int segment) const
  {
    return std::count (of_segment.begin (), of_segment.end (), of_segment[segment]) > 1;
  }
};

/** Everything the search for moved-in objects reads: both scans with their segments,
 *  what each sensor saw and the target's kd-tree (\a views), and per point the
 *  segments and the target's overlap radii (completeScene ()). */
struct FreeSpaceScene
{
  const detail::ScanViews& views;
  const Eigen::Matrix2Xd& source;
  const Eigen::Matrix2Xd& target;
  const matching::SegmentMotionParameters& parameters;
  std::vector<int> source_segment_of;  // per source point: its segment
  TargetSurfaces segments;              // each target segment a surface of its own
  TargetSurfaces occluded;              // target segments joined behind occluders (occludedSurfaces ())
  std::vector<double> target_spacing;  // per target point: its pointSpacing () on its segment
  std::vector<double> target_radius;   // per target point: its overlap radius on its segment
  const TargetSurfaces* surfaces = &segments;  // the surfaces the search reads
};

/** The per-point part of the scene, needed only once a segment has points the source
 *  saw through. */
void
completeScene (FreeSpaceScene& scene)
{
  const std::vector<matching::ScanSegment>& target_segments = scene.views.targetSegments ();
  scene.source_segment_of = matching::segmentOfEachPoint (scene.views.sourceSegments (), scene.source.cols ());
  std::vector<int> own (target_segments.size ());
  std::iota (own.begin (), own.end (), 0);
  scene.segments = TargetSurfaces (target_segments, scene.target.cols (), std::move (own));
  scene.occluded = TargetSurfaces (target_segments, scene.target.cols (),
                                   matching::occludedSurfaces (scene.target, target_segments,
                                                               scene.parameters.breakpoint_angle,
                                                               scene.parameters.range_noise));
  scene.target_spacing.assign (static_cast<std::size_t> (scene.target.cols ()), 0.0);
  scene.target_radius.assign (static_cast<std::size_t> (scene.target.cols ()), 0.0);
  for (const matching::ScanSegment& segment : target_segments)
    for (int j = segment.begin; j < segment.end; ++j) {
      scene.target_spacing[j] = matching::pointSpacing (scene.target, j, segment.begin, segment.end);
      scene.target_radius[j] = matching::overlapRadius (scene.parameters, scene.target_spacing[j]);
    }
}

/** No limit on a count of points seen through. */
constexpr int kNoLimit = std::numeric_limits<int>::max ();

/** What a sensor's view says of a point in its frame: matching::seesThrough () or
 *  matching::seesThroughFirmly (). */
using ViewTest = bool (*) (const matching::RangeProfile&, const Eigen::Vector2d&, const matching::BreakpointDistance&);

/** \a counted plus the target points of \a segment the source saw through (\a test)
 *  when moved back by T⁻¹ (T_target_source): under T they were not there, so they moved
 *  in. Counting stops once the sum exceeds \a limit (the sum returned is then above it
 *  but may fall short of the full count). */
int
segmentSeenThrough (const FreeSpaceScene& scene, const matching::ScanSegment& segment, const Rigid2d& T,
                    int counted = 0, int limit = kNoLimit, ViewTest test = matching::seesThrough)
{
  const Rigid2d T_inverse = T.inverse ();
  const detail::SensorView& seen = scene.views.sourceView ();
  for (int j = segment.begin; j < segment.end && counted <= limit; ++j)
    counted += test (seen.profile, T_inverse * scene.target.col (j), seen.breakpoint);
  return counted;
}

/** \a counted plus the object's points the target saw through (\a test) when moved by T
 *  (under T they are no longer there); stops above \a limit as segmentSeenThrough () does. */
int
objectSeenThrough (const FreeSpaceScene& scene, const std::vector<int>& object, const Rigid2d& T,
                   int counted = 0, int limit = kNoLimit, ViewTest test = matching::seesThrough)
{
  const detail::SensorView& seen = scene.views.targetView ();
  for (std::size_t k = 0; k < object.size () && counted <= limit; ++k)
    counted += test (seen.profile, T * scene.source.col (object[k]), seen.breakpoint);
  return counted;
}

/** The firm evidence under motion T that the object moved: the points of target
 *  \a segment and of the object seen through by matching::seesThroughFirmly (). Beams a
 *  surface's edges dropped are none: a parked car's edge returns, dropped at one end in
 *  one scan and at the other in the next, look like a slide of one beam. */
int
firmlySeenThrough (const FreeSpaceScene& scene, const matching::ScanSegment& segment, const std::vector<int>& object,
                   const Rigid2d& T)
{
  const int on_segment = segmentSeenThrough (scene, segment, T, 0, kNoLimit, matching::seesThroughFirmly);
  return objectSeenThrough (scene, object, T, on_segment, kNoLimit, matching::seesThroughFirmly);
}

/** Per point of \a points: its nearest target point when T puts it within that
 *  point's overlap radius, or -1. */
std::vector<int>
landedTargetPoints (const FreeSpaceScene& scene, const std::vector<int>& points, const Rigid2d& T)
{
  std::vector<int> landed (points.size (), -1);
  if (points.empty ())
    return landed;
  const KnnIndex::Result nearest = scene.views.targetPoints ().search (detail::movedPoints (scene.source, points, T), 1);  // one batch
  for (std::size_t k = 0; k < points.size (); ++k) {
    const auto column = static_cast<Eigen::Index> (k);
    const int j = nearest.indices (0, column);
    if (j >= 0 && nearest.squared_distances (0, column) <= scene.target_radius[j] * scene.target_radius[j])
      landed[k] = j;
  }
  return landed;
}

/** Target point \a j (-1: none) lies on the surface of target segment \a segment (the
 *  scene's current surfaces: the segment itself, or with the segments it continues
 *  behind occluders). */
bool
onSurfaceOf (const FreeSpaceScene& scene, int j, int segment)
{
  return j >= 0 && scene.surfaces->of_point[j] == scene.surfaces->of_segment[segment];
}

/** How many of \a landed (landedTargetPoints ()) lie on the surface of target segment \a segment. */
int
landedOnSurfaceOf (const FreeSpaceScene& scene, const std::vector<int>& landed, int segment)
{
  return static_cast<int> (
      std::count_if (landed.begin (), landed.end (), [&] (int j) { return onSurfaceOf (scene, j, segment); }));
}

/** Per source point: for the points of \a free, their landedTargetPoints () under the
 *  static motion (one batched query for all candidate objects); -1 for the others. */
std::vector<int>
staticTargets (const FreeSpaceScene& scene, const std::vector<int>& free, const Rigid2d& T_static)
{
  std::vector<int> target_of (static_cast<std::size_t> (scene.source.cols ()), -1);
  const std::vector<int> landed = landedTargetPoints (scene, free, T_static);
  for (std::size_t k = 0; k < free.size (); ++k)
    target_of[free[k]] = landed[k];
  return target_of;
}

/** How many of the object's points the static motion puts on the surface of target
 *  segment \a segment (\a static_target, staticTargets ()). */
int
explainedByStatic (const FreeSpaceScene& scene, const std::vector<int>& object, int segment,
                   const std::vector<int>& static_target)
{
  return static_cast<int> (std::count_if (object.begin (), object.end (), [&] (int i) {
    return onSurfaceOf (scene, static_target[i], segment);
  }));
}

/** The candidate object of target segment \a segment: the points of \a free (static
 *  or unclustered) on the source segments of those the static motion puts on its
 *  surface (\a static_target, staticTargets ()). */
std::vector<int>
objectOnSegment (const FreeSpaceScene& scene, int segment, const std::vector<int>& free,
                 const std::vector<int>& static_target)
{
  std::vector<bool> on_segment (scene.views.sourceSegments ().size (), false);
  for (int i : free)
    if (onSurfaceOf (scene, static_target[i], segment) && scene.source_segment_of[i] >= 0)
      on_segment[scene.source_segment_of[i]] = true;
  std::vector<int> object;
  for (int i : free)
    if (scene.source_segment_of[i] >= 0 && on_segment[scene.source_segment_of[i]])
      object.push_back (i);
  return object;
}

/** The unit direction along which the target points \a points extend most (their
 *  principal axis). */
Eigen::Vector2d
principalAxis (const Eigen::Matrix2Xd& points)
{
  const Eigen::Matrix2Xd centred = points.colwise () - points.rowwise ().mean ();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver (centred * centred.transpose ());
  return solver.eigenvectors ().col (1);  // eigenvalues increase
}

/** The principal axis of target points \a points (sorted, unique), or of the whole
 *  segment \a whole when fewer than two. */
Eigen::Vector2d
axisOfTargetPoints (const FreeSpaceScene& scene, const std::vector<int>& points, const matching::ScanSegment& whole)
{
  if (points.size () < 2)
    return principalAxis (scene.target.middleCols (whole.begin, whole.size ()));
  Eigen::Matrix2Xd columns (2, static_cast<Eigen::Index> (points.size ()));
  for (std::size_t k = 0; k < points.size (); ++k)
    columns.col (static_cast<Eigen::Index> (k)) = scene.target.col (points[k]);
  return principalAxis (columns);
}

/** The axes the object slides along. First the principal axis of the points of target
 *  segment \a segment's surface the static motion puts the object's points on
 *  (\a static_target, staticTargets ()); then, when it differs, that of those and of the
 *  segment's points the source saw through under the static motion (the newly seen part
 *  of the same surface, in front of what the source saw); the whole segment's when
 *  fewer than two. The few points of another surface the segment runs on into (a wall
 *  behind a car's end, within the breakpoint distance) are neither and do not tilt
 *  them. A car beside the sensor that the static motion moves mostly out of the
 *  target's view overlaps its side in a few points, whose axis the range noise tilts by
 *  degrees: along it, a slide of metres leaves the side; the newly seen metres steady
 *  it. */
std::vector<Eigen::Vector2d>
slideAxes (const FreeSpaceScene& scene, const std::vector<int>& object, int segment,
           const std::vector<int>& static_target, const Rigid2d& T_static)
{
  const matching::ScanSegment& whole = scene.views.targetSegments ()[segment];
  std::vector<int> along;
  for (int i : object)
    if (onSurfaceOf (scene, static_target[i], segment))
      along.push_back (static_target[i]);
  std::sort (along.begin (), along.end ());
  along.erase (std::unique (along.begin (), along.end ()), along.end ());
  std::vector<Eigen::Vector2d> axes{axisOfTargetPoints (scene, along, whole)};
  const Rigid2d T_inverse = T_static.inverse ();
  const detail::SensorView& seen = scene.views.sourceView ();
  for (int j = whole.begin; j < whole.end; ++j)
    if (matching::seesThrough (seen.profile, T_inverse * scene.target.col (j), seen.breakpoint))
      along.push_back (j);
  std::sort (along.begin (), along.end ());
  along.erase (std::unique (along.begin (), along.end ()), along.end ());
  const Eigen::Vector2d with_newly_seen = axisOfTargetPoints (scene, along, whole);
  if (std::abs (with_newly_seen.dot (axes.front ())) < 1.0 - 1e-12)
    axes.push_back (with_newly_seen);
  return axes;
}

/** The object's motions searched: T_static slid along the target segment's axis
 *  within ±\a reach, first on a grid of \a coarse_step, then around its best shift on
 *  a grid of \a fine_step (≤ coarse_step), then between its grid shifts down to
 *  \a finest_step (the segment's point spacing; refineNarrowRun ()). */
struct ShiftSearch
{
  const FreeSpaceScene& scene;
  const std::vector<int>& object;
  int segment;
  Rigid2d T_static;
  Eigen::Vector2d axis;
  double coarse_step;
  double fine_step;
  double finest_step;
  double reach;

  Rigid2d
  motion (double shift) const
  {
    return Eigen::Translation2d (shift * axis) * T_static;
  }

  /** The points seen through under motion (shift), exact up to \a limit: counting
   *  stops once it exceeds \a limit (a search that only compares counts with the
   *  fewest so far needs no more). */
  int
  seenThrough (double shift, int limit = kNoLimit) const
  {
    const Rigid2d T = motion (shift);
    const int on_segment = segmentSeenThrough (scene, scene.views.targetSegments ()[segment], T, 0, limit);
    return objectSeenThrough (scene, object, T, on_segment, limit);
  }
};

/** Points seen through at the shifts first + k · step, k = 0 … counts.size () − 1;
 *  exact where they are at most the fewest of the shifts before (so at every shift
 *  with the grid's fewest), above that fewest elsewhere. */
struct ShiftGrid
{
  double first = 0.0;
  double step = 0.0;
  std::vector<int> counts;

  double
  shift (int k) const
  {
    return first + k * step;
  }
};

ShiftGrid
sampleShifts (const ShiftSearch& search, double first, double step, int samples)
{
  ShiftGrid grid{first, step, std::vector<int> (static_cast<std::size_t> (samples))};
  int fewest = kNoLimit;
  for (int k = 0; k < samples; ++k) {
    grid.counts[k] = search.seenThrough (grid.shift (k), fewest);
    fewest = std::min (fewest, grid.counts[k]);
  }
  return grid;
}

/** The run [low, high] of grid shifts around the first one with the fewest points
 *  seen through; false when it reaches either end of the grid (not bounded there). */
bool
boundedFewestRun (const ShiftGrid& grid, int& low, int& high)
{
  const auto& counts = grid.counts;
  low = high = static_cast<int> (std::min_element (counts.begin (), counts.end ()) - counts.begin ());
  while (low > 0 && counts[low - 1] == counts[low])
    --low;
  while (high + 1 < static_cast<int> (counts.size ()) && counts[high + 1] == counts[high])
    ++high;
  return low > 0 && high + 1 < static_cast<int> (counts.size ());
}

/** Bisects between a shift \a inside the fewest points seen through (\a fewest) and
 *  one \a outside, to a sixteenth of their distance: the inside end. */
double
refineEdge (const ShiftSearch& search, double inside, double outside, int fewest)
{
  for (int halving = 0; halving < 4; ++halving) {
    const double middle = 0.5 * (inside + outside);
    (search.seenThrough (middle, fewest) <= fewest ? inside : outside) = middle;
  }
  return inside;
}

/** The grid the run is taken from: the coarse grid over ±reach, or, when the fine
 *  step is finer, the fine grid centred on the coarse best and reaching its
 *  neighbours if its own run is bounded there (a slide shorter than a coarse step
 *  shows only on the fine grid; a run wider than the fine grid is the coarse one's). */
ShiftGrid
searchGrid (const ShiftSearch& search)
{
  constexpr double kMostSteps = 4096.0;  // each way: bounds the work for a huge reach
  const int reach = static_cast<int> (std::min (std::ceil (search.reach / search.coarse_step), kMostSteps));
  ShiftGrid coarse = sampleShifts (search, -reach * search.coarse_step, search.coarse_step, 2 * reach + 1);
  if (!(search.fine_step < search.coarse_step))
    return coarse;
  const int best = static_cast<int> (std::min_element (coarse.counts.begin (), coarse.counts.end ()) -
                                     coarse.counts.begin ());
  const int each_way = static_cast<int> (std::ceil (search.coarse_step / search.fine_step));
  ShiftGrid fine = sampleShifts (search, coarse.shift (best) - each_way * search.fine_step, search.fine_step,
                                 2 * each_way + 1);
  int low = 0, high = 0;
  return boundedFewestRun (fine, low, high) ? fine : coarse;
}

/** A shift between the grid shifts of a narrow fewest run [\a low, \a high] (one
 *  shift, or two equal ones) with fewer points seen through than the run: a slide
 *  between two grid shifts shows its fewest points only there. Found by bisection:
 *  the middle of a two-shift run first, then towards the better side of the best
 *  shift so far, a half grid step (a quarter for two) first, while the step stays no
 *  finer than search.finest_step (the sensor resolves no finer on the segment) nor
 *  than a sixteenth of the grid step (refineEdge ()'s resolution).
 *  \return false when the run is wider or no such shift is found. */
bool
refineNarrowRun (const ShiftSearch& search, const ShiftGrid& grid, int low, int high, double& shift, int& fewest)
{
  const int run = grid.counts[low];
  if (high - low > 1)  // a wider run: the grid resolves it
    return false;
  const auto resolved = [&] (double half) { return half >= search.finest_step && half >= grid.step / 16.0; };
  double centre = grid.shift (low), half = 0.5 * grid.step;
  int least = run;
  if (high > low) {  // two equal shifts: their middle
    if (!resolved (half))
      return false;
    centre += half;
    least = search.seenThrough (centre);
    half *= 0.5;
  }
  for (; resolved (half); half *= 0.5) {
    const int below = search.seenThrough (centre - half, least), above = search.seenThrough (centre + half, least);
    if (below < least && below <= above) {
      centre -= half;
      least = below;
    }
    else if (above < least) {
      centre += half;
      least = above;
    }
  }
  if (least >= run)
    return false;
  shift = centre;
  fewest = least;
  return true;
}

/** The shifts along the axis that both sensors' free space allows best, [from, to]:
 *  slid too little, the target's end sticks out where the source saw through; too far,
 *  the source's end sticks out where the target saw through. */
struct FreeSpaceRun
{
  double from = 0.0;
  double to = 0.0;

  /** The slide taken: free space tells no shift of the run from another. */
  double
  middle () const
  {
    return 0.5 * (from + to);
  }
};

/** The run of shifts with the fewest points seen through (searchGrid (); a narrow one
 *  refined by refineNarrowRun ()), its ends refined.
 *  \return false unless the run has fewer such points than the static motion
 *  (\a static_count) and ends within reach on both sides (otherwise the motion along
 *  the axis is not observed). */
bool
freeSpaceRun (const ShiftSearch& search, int static_count, FreeSpaceRun& run)
{
  if (!(search.coarse_step > 0.0) || !(search.fine_step > 0.0) || !(search.reach > 0.0))
    return false;
  const ShiftGrid grid = searchGrid (search);
  int low = 0, high = 0;
  if (!boundedFewestRun (grid, low, high))
    return false;
  double inside_low = grid.shift (low), inside_high = grid.shift (high);
  double outside_low = grid.shift (low - 1), outside_high = grid.shift (high + 1);
  int fewest = grid.counts[low];
  double refined = 0.0;
  if (refineNarrowRun (search, grid, low, high, refined, fewest)) {
    // Every grid shift sees more: the refined shift's neighbours on the grid lie outside.
    inside_low = inside_high = refined;
    outside_low = grid.shift (static_cast<int> (std::floor ((refined - grid.first) / grid.step)));
    outside_high = outside_low + grid.step;
  }
  if (2 * fewest > static_count || static_count - fewest < 2)  // resolves at least two, and half, of them
    return false;
  run.from = refineEdge (search, inside_low, outside_low, fewest);
  run.to = refineEdge (search, inside_high, outside_high, fewest);
  return true;
}

/** Whether a shift of \a run, its middle first and then outwards at the segment's point
 *  spacing (search.finest_step; coarser for a run more than 64 spacings wide each way,
 *  which bounds the work), lands at least \a count of the object's points on the
 *  segment (landedTargetPoints ()). Within the run free space does not place the object,
 *  and points sampled along a side land on the target's samples only at some shifts. */
bool
landsAtLeast (const ShiftSearch& search, const FreeSpaceRun& run, int count)
{
  constexpr double kMostSamples = 64.0;  // each way
  const auto lands = [&] (double shift) {
    const std::vector<int> landed = landedTargetPoints (search.scene, search.object, search.motion (shift));
    return landedOnSurfaceOf (search.scene, landed, search.segment) >= count;
  };
  if (lands (run.middle ()))
    return true;
  const double half = 0.5 * (run.to - run.from);
  const double step = std::max (search.finest_step, half / kMostSamples);
  for (double offset = step; step > 0.0 && offset <= half; offset += step)
    if (lands (run.middle () - offset) || lands (run.middle () + offset))
      return true;
  return false;
}

/** The upper median of \a values (not empty). */
double
median (std::vector<double> values)
{
  std::nth_element (values.begin (), values.begin () + values.size () / 2, values.end ());
  return values[values.size () / 2];
}

/** The median over the points of target \a segment of a per-target-point value
 *  (FreeSpaceScene::target_spacing, target_radius). */
double
segmentMedian (const std::vector<double>& per_point, const matching::ScanSegment& segment)
{
  return median (std::vector<double> (per_point.begin () + segment.begin, per_point.begin () + segment.end));
}

/** The farthest shift searched: max_displacement, or less where the object and the
 *  target segment, both projected on \a axis, no longer overlap beyond it (no shift
 *  past that puts any of the object's points on the segment), plus one coarse step. */
double
shiftReach (const FreeSpaceScene& scene, const std::vector<int>& object, const matching::ScanSegment& segment,
            const Rigid2d& T_static, const Eigen::Vector2d& axis)
{
  constexpr double kInfinity = std::numeric_limits<double>::infinity ();
  double low = kInfinity, high = -kInfinity, object_low = kInfinity, object_high = -kInfinity;
  for (int j = segment.begin; j < segment.end; ++j) {
    const double along = axis.dot (scene.target.col (j));
    low = std::min (low, along);
    high = std::max (high, along);
  }
  for (int i : object) {
    const double along = axis.dot (T_static * scene.source.col (i));
    object_low = std::min (object_low, along);
    object_high = std::max (object_high, along);
  }
  const double no_overlap = std::max (high - object_low, object_high - low) + 2.0 * scene.parameters.overlap_radius;
  return std::min (scene.parameters.max_displacement, no_overlap);
}

/** The object's points join a new cluster of motion T: those T puts on target segment
 *  \a segment matched to the target point they landed on (\a landed,
 *  landedTargetPoints () under T: their nearest), the others unmatched. */
void
addCluster (const FreeSpaceScene& scene, const std::vector<int>& object, int segment, const Rigid2d& T,
            const std::vector<int>& landed, JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  for (std::size_t k = 0; k < object.size (); ++k) {
    result.source_cluster[object[k]] = cluster;
    result.source_match[object[k]] = onSurfaceOf (scene, landed[k], segment) ? landed[k] : kNoMatch;
  }
}

/** The static world's and the unclustered points. */
std::vector<int>
freePoints (const JointResult& result)
{
  std::vector<int> free;
  for (int i = 0; i < static_cast<int> (result.source_cluster.size ()); ++i)
    if (detail::inStaticWorldOrOutliers (result, static_cast<std::size_t> (i)))
      free.push_back (i);
  return free;
}

/** The object of moved-in target segment \a g (objectOnSegment () on the scene's current
 *  surfaces, less the points an earlier segment's object took) made a cluster when a slide
 *  of the static motion along the segment resolves the points either sensor saw through
 *  (see separateObjectsInFreeSpace ()). \a static_seen the segment's points the source saw
 *  through under the static motion. \return true when a cluster was added. */
bool
separateObjectOfSegment (const FreeSpaceScene& scene, int g, int static_seen, const std::vector<int>& free,
                         const std::vector<int>& static_target, const detail::StaticFitCheck* check,
                         JointResult& result)
{
  const matching::SegmentMotionParameters& parameters = scene.parameters;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  std::vector<int> object = objectOnSegment (scene, g, free, static_target);
  object.erase (std::remove_if (object.begin (), object.end (),
                                [&] (int i) { return result.source_cluster[i] != result.static_cluster &&
                                                     result.source_cluster[i] != kOutlierCluster; }),
                object.end ());  // points an earlier segment's object took
  if (static_cast<int> (object.size ()) < parameters.min_segment_points)
    return false;
  const int seen_through = static_seen + objectSeenThrough (scene, object, T_static);
  const matching::ScanSegment& segment = scene.views.targetSegments ()[g];
  if (seen_through < 2)  // freeSpaceRun () must resolve two
    return false;
  const int firm = firmlySeenThrough (scene, segment, object, T_static);
  if (firm == 0)  // the slide must resolve a firm one
    return false;
  // The slide is sought along each of slideAxes (); the run leaving fewer points seen
  // through is tried first.
  struct Candidate
  {
    ShiftSearch search;
    FreeSpaceRun run;
    int fewest;
  };
  std::vector<Candidate> candidates;
  const double coarse_step = 2.0 * parameters.overlap_radius;
  for (const Eigen::Vector2d& axis : slideAxes (scene, object, g, static_target, T_static)) {
    const ShiftSearch search{scene,
                             object,
                             g,
                             T_static,
                             axis,
                             coarse_step,
                             // two overlap radii: what the sensor resolves on the segment (a
                             // 1/10-scale car half a metre away slides a few centimetres, a truck
                             // at 10 m a metre or more)
                             std::min (2.0 * segmentMedian (scene.target_radius, segment), coarse_step),
                             segmentMedian (scene.target_spacing, segment),
                             shiftReach (scene, object, segment, T_static, axis)};
    FreeSpaceRun run;
    if (freeSpaceRun (search, seen_through, run))
      candidates.push_back ({search, run, search.seenThrough (run.middle ())});
  }
  std::vector<std::size_t> order (candidates.size ());
  std::iota (order.begin (), order.end (), 0);
  std::stable_sort (order.begin (), order.end (),
                    [&] (std::size_t a, std::size_t b) { return candidates[a].fewest < candidates[b].fewest; });
  const int explained = explainedByStatic (scene, object, g, static_target);
  for (const std::size_t k : order) {
    const Candidate& candidate = candidates[k];
    if (!landsAtLeast (candidate.search, candidate.run, explained))
      continue;
    const Rigid2d T_moved = candidate.search.motion (candidate.run.middle ());
    if (firmlySeenThrough (scene, segment, object, T_moved) >= firm)  // it explains only dropped edge returns
      continue;
    if (check != nullptr && detail::staticFitRefutes (scene.views, result, object, T_moved, *check))
      continue;  // free space saw the noise of a rough surface the static motion fits
    addCluster (scene, object, g, T_moved, landedTargetPoints (scene, object, T_moved), result);
    return true;
  }
  return false;
}

}  // namespace

int
detail::separateObjectsInFreeSpace (const ScanViews& views, JointResult& result, const StaticFitCheck* check)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const Eigen::Matrix2Xd& target = views.target ();
  const matching::SegmentMotionParameters& parameters = views.parameters ();
  checkResultAgainstScans ("separateObjectsInFreeSpace", source, target, result);
  if (check != nullptr)
    checkStaticFitCheck ("separateObjectsInFreeSpace", *check);
  if (!canSeparateFromStaticWorld (source, target, result))
    return 0;
  FreeSpaceScene scene{views, source, target, parameters, {}, {}, {}, {}, {}};
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  // The target segments with points the source saw through under the static motion, and how many.
  const std::vector<matching::ScanSegment>& target_segments = views.targetSegments ();
  std::vector<int> moved_in;
  std::vector<int> static_seen_through (target_segments.size (), 0);
  for (int g = 0; g < static_cast<int> (target_segments.size ()); ++g) {
    const matching::ScanSegment& segment = target_segments[g];
    if (segment.size () >= parameters.min_segment_points)
      static_seen_through[g] = segmentSeenThrough (scene, segment, T_static);
    if (static_seen_through[g] > 0)
      moved_in.push_back (g);
  }
  if (moved_in.empty ())
    return 0;
  completeScene (scene);
  const std::vector<int> free = freePoints (result);
  const std::vector<int> static_target = staticTargets (scene, free, T_static);
  int added = 0;
  for (int g : moved_in) {
    scene.surfaces = &scene.segments;  // the moved-in segment alone
    if (separateObjectOfSegment (scene, g, static_seen_through[g], free, static_target, check, result)) {
      ++added;
      continue;
    }
    if (!scene.occluded.joinsOthers (g))
      continue;
    scene.surfaces = &scene.occluded;  // with the segments it continues behind occluders
    added += separateObjectOfSegment (scene, g, static_seen_through[g], free, static_target, check, result);
  }
  if (added > 0)
    numberLargestFirst (result);
  return added;
}

int
separateObjectsInFreeSpace (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                            const matching::SegmentMotionParameters& parameters, JointResult& result,
                            const SlightMotionTest* static_fit)
{
  const std::optional<detail::StaticFitCheck> check =
      static_fit != nullptr ? std::optional (detail::StaticFitCheck{*static_fit, parameters.min_segment_points})
                            : std::nullopt;
  return detail::separateObjectsInFreeSpace (detail::ScanViews (source, target, parameters), result,
                                             check ? &*check : nullptr);
}

}  // namespace joint
}  // namespace pcl_crf
