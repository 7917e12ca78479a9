#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/matching/range_profile.h>
#include <pcl_crf/matching/scan_segments.h>

#include "cluster_numbering.h"
#include "scan_views.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {
namespace joint {

namespace {

/** The median of χ² with one degree of freedom: a Gaussian residual's squared median
 *  over its variance. */
constexpr double kChiSquare1Median = 0.454936423119572;

/** Throws std::invalid_argument unless \a test and \a min_points are in range, naming \a function. */
void
checkTest (const char* function, const SlightMotionTest& test, int min_points)
{
  const auto fail = [function] (const std::string& what) {
    throw std::invalid_argument (std::string ("[pcl_crf::joint::") + function + "] " + what);
  };
  if (!(test.min_deviance > 0.0) || !std::isfinite (test.min_deviance))
    fail ("min_deviance must be > 0, got " + std::to_string (test.min_deviance));
  if (!(test.min_mean_deviance >= 0.0) || !std::isfinite (test.min_mean_deviance))
    fail ("min_mean_deviance must be >= 0, got " + std::to_string (test.min_mean_deviance));
  if (!(test.along_beam_steps >= 0.0) || !std::isfinite (test.along_beam_steps))
    fail ("along_beam_steps must be >= 0, got " + std::to_string (test.along_beam_steps));
  if (min_points < 1)
    fail ("min_points must be >= 1, got " + std::to_string (min_points));
}

/** The target's outline: per target point, the index of its segment
 *  (detail::ScanViews::targetSegments (); −1 for a point on none, an outline of its own). */
struct TargetOutline
{
  std::vector<int> segment_of;

  explicit TargetOutline (const detail::ScanViews& views)
    : segment_of (matching::segmentOfEachPoint (views.targetSegments (), views.target ().cols ()))
  {}

  /** Whether target point \a j lies on the segment of target point \a q (\a q's neighbour). */
  bool
  sameSegment (int q, int j) const
  {
    return j >= 0 && j < static_cast<int> (segment_of.size ()) && segment_of[q] >= 0 && segment_of[j] == segment_of[q];
  }
};

/** Where a point placed in the target frame lies from the target's outline near target
 *  point q: its distance to the nearer of the pieces from q to q's neighbours on its
 *  segment (to q when it has none), and whether it lies beyond the segment's end (q is
 *  its first or last point and the point projects outside it). */
struct OutlineDistance
{
  double distance;
  bool beyond_end;
};

OutlineDistance
distanceToOutline (const Eigen::Vector2d& point, const Eigen::Matrix2Xd& target, const TargetOutline& outline, int q)
{
  const Eigen::Vector2d a = target.col (q);
  OutlineDistance result{(point - a).norm (), !outline.sameSegment (q, q - 1) || !outline.sameSegment (q, q + 1)};
  bool along_a_piece = false;
  for (const int j : {q - 1, q + 1}) {
    if (!outline.sameSegment (q, j))
      continue;
    const Eigen::Vector2d piece = target.col (j) - a;
    const double squared_length = piece.squaredNorm ();
    if (squared_length == 0.0)
      continue;
    const double t = (point - a).dot (piece) / squared_length;
    along_a_piece = along_a_piece || t > 0.0;
    result.distance = std::min (result.distance, (point - (a + std::clamp (t, 0.0, 1.0) * piece)).norm ());
  }
  result.beyond_end = result.beyond_end && !along_a_piece;
  return result;
}

/** One segment's evidence: its static points, and for those T_static places in the
 *  target's view, neither hidden behind a return nor beyond a surface's end, their
 *  squared residual under T_static and squared along-beam uncertainty; then their own
 *  motion (ICP from T_static), and per point whether it too places them in view and their
 *  squared residual under it. */
struct SegmentEvidence
{
  std::vector<int> members;
  /** per member: where T_static puts it, and whether it counts (seen as above). */
  detail::TargetPlacement by_static;
  std::vector<int> counted;
  std::vector<double> static_squared, along_squared;
  Rigid2d motion = Rigid2d::Identity ();
  /** the farthest the own motion moves a member from where the static motion puts it [m]. */
  double largest_move = 0.0;
  /** per counted point: whether the own motion places it in view, and its squared residual. */
  std::vector<bool> own_in_view;
  std::vector<double> own_squared;
};

/** The static half of the evidence of \a members (the static points of one source segment). */
SegmentEvidence
weighUnderStaticMotion (const detail::ScanViews& views, const TargetOutline& outline,
                        std::vector<int> members, const Rigid2d& T_static, double along_beam_steps)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const double cap = views.parameters ().overlap_radius;
  const detail::SensorView& seen = views.targetView ();
  SegmentEvidence evidence;
  evidence.members = std::move (members);
  const std::vector<double> not_read (evidence.members.size (), 0.0);  // the test reads no `explained`
  evidence.by_static = detail::placeInTarget (detail::movedPoints (source, evidence.members, T_static), not_read, views,
                                              detail::SeenThrough::NotAsked);
  for (std::size_t k = 0; k < evidence.members.size (); ++k) {
    const auto c = static_cast<Eigen::Index> (k);
    const Eigen::Vector2d at_static = evidence.by_static.points.col (c);
    if (!evidence.by_static.in_view[k] || matching::hiddenBehindAReturn (seen.profile, at_static, seen.breakpoint))
      continue;
    const OutlineDistance r_static = distanceToOutline (at_static, views.target (), outline,
                                                        static_cast<int> (evidence.by_static.nearest.indices (0, c)));
    if (r_static.beyond_end)
      continue;
    const double along = along_beam_steps * seen.profile.step * at_static.norm ();
    evidence.counted.push_back (static_cast<int> (k));
    evidence.static_squared.push_back (std::pow (std::min (cap, r_static.distance), 2));
    evidence.along_squared.push_back (along * along);
  }
  return evidence;
}

/** The other half: the counted points under motion \a T, taken as the members' own. */
void
weighUnderMotion (const detail::ScanViews& views, const TargetOutline& outline, const Rigid2d& T,
                  SegmentEvidence& evidence)
{
  const Eigen::Matrix2Xd& source = views.source ();
  const double cap = views.parameters ().overlap_radius;
  evidence.motion = T;
  const std::vector<double> not_read (evidence.members.size (), 0.0);  // the test reads no `explained`
  const detail::TargetPlacement by_own = detail::placeInTarget (
      detail::movedPoints (source, evidence.members, evidence.motion), not_read, views, detail::SeenThrough::NotAsked);
  for (Eigen::Index c = 0; c < by_own.points.cols (); ++c)
    evidence.largest_move =
        std::max (evidence.largest_move, (by_own.points.col (c) - evidence.by_static.points.col (c)).norm ());
  for (const int k : evidence.counted) {
    const OutlineDistance r_own =
        distanceToOutline (by_own.points.col (k), views.target (), outline, static_cast<int> (by_own.nearest.indices (0, k)));
    evidence.own_in_view.push_back (by_own.in_view[k]);
    evidence.own_squared.push_back (std::pow (std::min (cap, r_own.distance), 2));
  }
}

/** The own half: ICP of the members from T_static, and the counted points under it. */
void
weighUnderOwnMotion (const detail::ScanViews& views, const TargetOutline& outline, const Rigid2d& T_static,
                     SegmentEvidence& evidence)
{
  weighUnderMotion (views, outline,
                    detail::icpOnNearestPoints (views.source (), evidence.members, views.targetPoints (), T_static,
                                                views.parameters ().overlap_radius),
                    evidence);
}

/** The static half of the evidence of every source segment with at least \a min_points
 *  points in the static world. */
std::vector<SegmentEvidence>
weighStaticSegments (const detail::ScanViews& views, const TargetOutline& outline, const JointResult& result,
                     int min_points, double along_beam_steps)
{
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  std::vector<SegmentEvidence> weighed;
  for (const matching::ScanSegment& segment : views.sourceSegments ()) {
    std::vector<int> members = detail::segmentPointsLabelled (segment, result.source_cluster, result.static_cluster);
    if (static_cast<int> (members.size ()) >= min_points)
      weighed.push_back (weighUnderStaticMotion (views, outline, std::move (members), T_static, along_beam_steps));
  }
  return weighed;
}

/** The static motion's own misfit as a variance: the median squared residual under it
 *  of every counted point, over the median of χ²₁ (0 when none was counted). */
double
staticMisfitVariance (const std::vector<SegmentEvidence>& weighed)
{
  std::vector<double> squared;
  for (const SegmentEvidence& evidence : weighed)
    squared.insert (squared.end (), evidence.static_squared.begin (), evidence.static_squared.end ());
  if (squared.empty ())
    return 0.0;
  const auto middle = squared.begin () + static_cast<std::ptrdiff_t> (squared.size () / 2);
  std::nth_element (squared.begin (), middle, squared.end ());
  return *middle / kChiSquare1Median;
}

/** The variance of counted point k's residual: σ_r² + along_k² + \a misfit_variance. */
double
residualVariance (const SegmentEvidence& evidence, std::size_t k, double range_noise, double misfit_variance)
{
  return range_noise * range_noise + evidence.along_squared[k] + misfit_variance;
}

/** The most the deviance can reach, were the own motion to fit every counted point. */
double
devianceBound (const SegmentEvidence& evidence, double range_noise, double misfit_variance)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < evidence.static_squared.size (); ++k)
    sum += evidence.static_squared[k] / residualVariance (evidence, k, range_noise, misfit_variance);
  return sum;
}

/** The deviance D = Σ_i (r_i(T_s)² − r_i(T)²) / σ_i² of the static motion against the
 *  segment's own, over the counted points the own motion also places in view, and
 *  their number. */
std::pair<double, int>
deviance (const SegmentEvidence& evidence, double range_noise, double misfit_variance)
{
  double sum = 0.0;
  int used = 0;
  for (std::size_t k = 0; k < evidence.own_squared.size (); ++k)
    if (evidence.own_in_view[k]) {
      sum += (evidence.static_squared[k] - evidence.own_squared[k]) /
             residualVariance (evidence, k, range_noise, misfit_variance);
      ++used;
    }
  return {sum, used};
}

/** Whether the segment moved slightly: the test of separateSegmentsThatMovedSlightly (),
 *  its own motion fitted only where the bound leaves it a chance. */
bool
movedSlightly (const detail::ScanViews& views, const TargetOutline& outline, const Rigid2d& T_static,
               const SlightMotionTest& test, int min_points, double misfit_variance, SegmentEvidence& evidence)
{
  const double range_noise = views.parameters ().range_noise;
  if (static_cast<int> (evidence.counted.size ()) < min_points ||
      devianceBound (evidence, range_noise, misfit_variance) < test.min_deviance)
    return false;
  weighUnderOwnMotion (views, outline, T_static, evidence);
  const auto [d, used] = deviance (evidence, range_noise, misfit_variance);
  return used >= min_points && evidence.largest_move <= views.parameters ().overlap_radius && d >= test.min_deviance &&
         d >= test.min_mean_deviance * used;
}

/** The segment's static points become a cluster of their own motion, and the matched
 *  ones take the target point nearest to where it puts them. */
void
addClusterOf (const SegmentEvidence& evidence, const detail::ScanViews& views, JointResult& result)
{
  for (const int i : evidence.members)
    result.source_cluster[i] = static_cast<int> (result.cluster_motions.size ());
  result.cluster_motions.push_back (evidence.motion);
  std::vector<int> matched;
  for (const int i : evidence.members)
    if (result.source_match[i] != kNoMatch)
      matched.push_back (i);
  associateUnderClusterMotions (views.source (), views.targetPoints (), matched, result.source_cluster,
                                result.cluster_motions, result.source_match);
}

}  // namespace

int
detail::separateSegmentsThatMovedSlightly (const ScanViews& views, const SlightMotionTest& test, int min_points,
                                           JointResult& result)
{
  checkResultAgainstScans ("separateSegmentsThatMovedSlightly", views.source (), views.target (), result);
  checkTest ("separateSegmentsThatMovedSlightly", test, min_points);
  if (!canSeparateFromStaticWorld (views.source (), views.target (), result))
    return 0;
  const Rigid2d T_static = result.cluster_motions[result.static_cluster];
  const TargetOutline outline (views);
  std::vector<SegmentEvidence> weighed = weighStaticSegments (views, outline, result, min_points, test.along_beam_steps);
  const double misfit_variance = staticMisfitVariance (weighed);
  int separated = 0;
  for (SegmentEvidence& evidence : weighed)
    if (movedSlightly (views, outline, T_static, test, min_points, misfit_variance, evidence)) {
      addClusterOf (evidence, views, result);
      ++separated;
    }
  if (separated > 0)
    numberLargestFirst (result);
  return separated;
}

void
detail::checkStaticFitCheck (const char* function, const StaticFitCheck& check)
{
  checkTest (function, check.test, check.min_points);
}

bool
detail::staticFitRefutes (const ScanViews& views, const JointResult& result, const std::vector<int>& members,
                          const Rigid2d& T, const StaticFitCheck& check)
{
  if (result.static_cluster < 0)
    return false;
  const TargetOutline outline (views);
  const SlightMotionTest& test = check.test;
  const double misfit_variance =
      staticMisfitVariance (weighStaticSegments (views, outline, result, check.min_points, test.along_beam_steps));
  SegmentEvidence evidence = weighUnderStaticMotion (views, outline, members,
                                                     result.cluster_motions[result.static_cluster],
                                                     test.along_beam_steps);
  weighUnderMotion (views, outline, T, evidence);
  const auto [d, used] = deviance (evidence, views.parameters ().range_noise, misfit_variance);
  return -d >= test.min_deviance && -d >= test.min_mean_deviance * used;  // the roles of the motions swapped
}

int
separateSegmentsThatMovedSlightly (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                                   const matching::SegmentMotionParameters& parameters, const SlightMotionTest& test,
                                   int min_points, JointResult& result)
{
  return detail::separateSegmentsThatMovedSlightly (detail::ScanViews (source, target, parameters), test, min_points,
                                                    result);
}

}  // namespace joint
}  // namespace pcl_crf
