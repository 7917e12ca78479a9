#include <pcl_crf/core/knn_index.h>
#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/segment_motions.h>

#include "cluster_numbering.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** Everything the search for moved-in objects reads: both scans, what each sensor saw,
 *  and their segments. */
struct FreeSpaceScene
{
  const Eigen::Matrix2Xd& source;
  const Eigen::Matrix2Xd& target;
  const matching::SegmentMotionParameters& parameters;
  matching::RangeProfile source_view;
  matching::RangeProfile target_view;
  std::vector<matching::ScanSegment> source_segments;
  std::vector<matching::ScanSegment> target_segments;
  std::vector<int> source_segment_of;  // per source point: its segment
};

std::vector<int>
segmentOfPoints (const std::vector<matching::ScanSegment>& segments, Eigen::Index points)
{
  std::vector<int> of (static_cast<std::size_t> (points), -1);
  for (std::size_t s = 0; s < segments.size (); ++s)
    for (int i = segments[s].begin; i < segments[s].end; ++i)
      of[i] = static_cast<int> (s);
  return of;
}

/** How well a motion hypothesis of a candidate object fits: its source points that
 *  land on the target segment, and the points either sensor saw through. */
struct HypothesisFit
{
  int explained = 0;
  int seen_through = 0;
};

/** Source point i moved by \a T lands within its overlap radius of a point of \a segment. */
bool
landsOn (const FreeSpaceScene& scene, const matching::ScanSegment& segment, const Eigen::Vector2d& moved)
{
  for (int j = segment.begin; j < segment.end; ++j) {
    const double radius = matching::overlapRadius (
        scene.parameters, matching::pointSpacing (scene.target, j, segment.begin, segment.end));
    if ((scene.target.col (j) - moved).squaredNorm () <= radius * radius)
      return true;
  }
  return false;
}

/** The target points of \a segment the source saw through when moved back by T⁻¹
 *  (T_target_source): under T they were not there, so they moved in. */
int
segmentSeenThrough (const FreeSpaceScene& scene, const matching::ScanSegment& segment, const Rigid2d& T)
{
  const Rigid2d T_inverse = T.inverse ();
  int seen_through = 0;
  for (int j = segment.begin; j < segment.end; ++j)
    seen_through += matching::seesThrough (scene.source_view, T_inverse * scene.target.col (j),
                                           scene.parameters.breakpoint_angle, scene.parameters.range_noise);
  return seen_through;
}

/** The fit of T for the object's source points \a object and its target \a segment:
 *  segmentSeenThrough () plus the object's points the target saw through when moved
 *  by T (under T they are no longer there). */
HypothesisFit
fitOf (const FreeSpaceScene& scene, const std::vector<int>& object, const matching::ScanSegment& segment,
       const Rigid2d& T)
{
  HypothesisFit fit;
  fit.seen_through = segmentSeenThrough (scene, segment, T);
  for (int i : object) {
    const Eigen::Vector2d moved = T * scene.source.col (i);
    fit.seen_through += matching::seesThrough (scene.target_view, moved, scene.parameters.breakpoint_angle,
                                               scene.parameters.range_noise);
    fit.explained += landsOn (scene, segment, moved);
  }
  return fit;
}

/** The static world's (or unclustered) source points on the segments of those that
 *  \a T_static puts on the target \a segment: the candidate object. */
std::vector<int>
objectOnSegment (const FreeSpaceScene& scene, const matching::ScanSegment& segment, const Rigid2d& T_static,
                 const std::vector<int>& cluster, int static_cluster)
{
  const auto unclaimed = [&] (int i) { return cluster[i] == static_cluster || cluster[i] == kOutlierCluster; };
  std::vector<bool> on_segment (scene.source_segments.size (), false);
  for (int i = 0; i < static_cast<int> (scene.source.cols ()); ++i)
    if (unclaimed (i) && scene.source_segment_of[i] >= 0 && landsOn (scene, segment, T_static * scene.source.col (i)))
      on_segment[scene.source_segment_of[i]] = true;
  std::vector<int> object;
  for (int i = 0; i < static_cast<int> (scene.source.cols ()); ++i)
    if (unclaimed (i) && scene.source_segment_of[i] >= 0 && on_segment[scene.source_segment_of[i]])
      object.push_back (i);
  return object;
}

/** The unit direction along which the target segment extends most (its principal axis). */
Eigen::Vector2d
principalAxis (const Eigen::Matrix2Xd& target, const matching::ScanSegment& segment)
{
  const auto points = target.middleCols (segment.begin, segment.size ());
  const Eigen::Matrix2Xd centred = points.colwise () - points.rowwise ().mean ();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver (centred * centred.transpose ());
  return solver.eigenvectors ().col (1);  // eigenvalues increase
}

/** The object's motions searched: T_static slid along the target segment's axis. */
struct ShiftSearch
{
  const FreeSpaceScene& scene;
  const std::vector<int>& object;
  const matching::ScanSegment& segment;
  Rigid2d T_static;
  Eigen::Vector2d axis;

  Rigid2d
  motion (double shift) const
  {
    return Eigen::Translation2d (shift * axis) * T_static;
  }

  int
  seenThrough (double shift) const
  {
    return fitOf (scene, object, segment, motion (shift)).seen_through;
  }
};

/** Bisects between a shift \a inside the fewest points seen through (\a fewest) and
 *  one \a outside, to a sixteenth of their distance: the inside end. */
double
refineEdge (const ShiftSearch& search, double inside, double outside, int fewest)
{
  for (int halving = 0; halving < 4; ++halving) {
    const double middle = 0.5 * (inside + outside);
    (search.seenThrough (middle) <= fewest ? inside : outside) = middle;
  }
  return inside;
}

/** The shift along the axis that both sensors' free space allows best: on a grid of
 *  overlap_radius steps within ±max_displacement, the run of shifts with the fewest
 *  points seen through, its ends refined, and \a shift its middle (slid too little,
 *  the target's end sticks out where the source saw through; too far, the source's
 *  end sticks out where the target saw through). \return false unless the run has
 *  fewer such points than the static motion (\a static_count) and ends within reach
 *  on both sides (otherwise the motion along the axis is not observed). */
bool
freeSpaceShift (const ShiftSearch& search, int static_count, double& shift)
{
  constexpr double kMostSteps = 4096.0;  // each way: bounds the work for a huge max_displacement
  const double step = search.scene.parameters.overlap_radius;
  const double steps = std::ceil (search.scene.parameters.max_displacement / step);
  if (!(step > 0.0) || !(steps >= 1.0))
    return false;
  const int reach = static_cast<int> (std::min (steps, kMostSteps));
  std::vector<int> counts (static_cast<std::size_t> (2 * reach + 1));
  for (int k = 0; k < static_cast<int> (counts.size ()); ++k)
    counts[k] = search.seenThrough ((k - reach) * step);
  const int best = static_cast<int> (std::min_element (counts.begin (), counts.end ()) - counts.begin ());
  const int fewest = counts[best];
  if (2 * fewest > static_count || static_count - fewest < 2)  // resolves at least two, and half, of them
    return false;
  int low = best, high = best;
  while (low > 0 && counts[low - 1] == fewest)
    --low;
  while (high + 1 < static_cast<int> (counts.size ()) && counts[high + 1] == fewest)
    ++high;
  if (low == 0 || high + 1 == static_cast<int> (counts.size ()))
    return false;
  const double from = refineEdge (search, (low - reach) * step, (low - 1 - reach) * step, fewest);
  const double to = refineEdge (search, (high - reach) * step, (high + 1 - reach) * step, fewest);
  shift = 0.5 * (from + to);
  return true;
}

/** The object's points join a new cluster of motion T: those it puts on the target
 *  segment matched to the nearest target point, the others unmatched. */
void
addCluster (const FreeSpaceScene& scene, const std::vector<int>& object, const matching::ScanSegment& segment,
            const Rigid2d& T, const KnnIndex& target_points, JointResult& result)
{
  const int cluster = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (T);
  std::vector<int> landed;
  for (int i : object) {
    result.source_cluster[i] = cluster;
    result.source_match[i] = kNoMatch;
    if (landsOn (scene, segment, T * scene.source.col (i)))
      landed.push_back (i);
  }
  associateUnderClusterMotions (scene.source, target_points, landed, result.source_cluster, result.cluster_motions,
                                result.source_match);
}

}  // namespace

int
separateObjectsInFreeSpace (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                            const matching::SegmentMotionParameters& parameters, JointResult& result)
{
  detail::checkResultAgainstTarget ("separateObjectsInFreeSpace", target, result);
  if (static_cast<Eigen::Index> (result.source_cluster.size ()) != source.cols ())
    throw std::invalid_argument ("[pcl_crf::joint::separateObjectsInFreeSpace] " + std::to_string (source.cols ()) +
                                 " source points but " + std::to_string (result.source_cluster.size ()) + " clusters");
  if (result.static_cluster < 0 || source.cols () < 2 || target.cols () < 2)
    return 0;
  FreeSpaceScene scene{source, target, parameters, matching::makeRangeProfile (source),
                       matching::makeRangeProfile (target),
                       matching::segmentScan (source, parameters.breakpoint_angle, parameters.range_noise),
                       matching::segmentScan (target, parameters.breakpoint_angle, parameters.range_noise), {}};
  scene.source_segment_of = segmentOfPoints (scene.source_segments, source.cols ());
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  KnnIndex target_points;
  int added = 0;
  for (const matching::ScanSegment& segment : scene.target_segments) {
    if (segment.size () < parameters.min_segment_points || segmentSeenThrough (scene, segment, T_static) == 0)
      continue;
    const std::vector<int> object = objectOnSegment (scene, segment, T_static, result.source_cluster,
                                                     result.static_cluster);
    if (static_cast<int> (object.size ()) < parameters.min_segment_points)
      continue;
    const HypothesisFit as_static = fitOf (scene, object, segment, T_static);
    const ShiftSearch search{scene, object, segment, T_static, principalAxis (target, segment)};
    double shift = 0.0;
    if (!freeSpaceShift (search, as_static.seen_through, shift))
      continue;
    const Rigid2d T_best = search.motion (shift);
    if (fitOf (scene, object, segment, T_best).explained < as_static.explained)
      continue;
    if (target_points.size () == 0)
      target_points.build (target);
    addCluster (scene, object, segment, T_best, target_points, result);
    ++added;
  }
  if (added > 0)
    detail::numberLargestFirst (result);
  return added;
}

}  // namespace joint
}  // namespace pcl_crf
