#include <pcl_crf/matching/segment_motions.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** Points of a segment whose overlap scores a hypothesis, evenly spread. */
constexpr int kScoringSamples = 10;

/** Indices of up to kScoringSamples evenly spread points of a segment. */
std::vector<int>
scoringSamples (const ScanSegment& segment)
{
  const int count = std::min (segment.size (), kScoringSamples);
  std::vector<int> samples (count);
  for (int k = 0; k < count; ++k)
    samples[k] = segment.begin + (count == 1 ? 0 : k * (segment.size () - 1) / (count - 1));
  return samples;
}

/** The hypotheses of one source segment with the query columns that score them. */
struct SegmentQuery
{
  ScanSegment segment;
  std::vector<Eigen::Vector2d> hypotheses;
  std::vector<int> samples;
  Eigen::Index first_column = 0;
  /** per sample: whether the target sensor could see it under the current motion. */
  std::vector<bool> judged;
  /** per sample: its squared overlap radius (overlapRadius () of its spacing on the segment). */
  std::vector<double> radii_squared;
};

/** The bearings the target scan covers (its field of view): from the return after the
 *  widest gap between its bearings, the sensor's back (as makeRangeProfile () infers
 *  it), round to the one before it; [min, max] when the back lies across ±π (a laser
 *  facing forward), else [min, π] ∪ [−π, max] (one facing elsewhere in the frame of its
 *  points: taken as [min, max] there, all round, points that left the view were judged). */
struct FieldOfView
{
  double min = -M_PI;
  double max = M_PI;
  bool wraps = false;  // through ±π

  bool
  contains (const Eigen::Vector2d& p) const
  {
    const double bearing = std::atan2 (p.y (), p.x ());
    return wraps ? bearing >= min || bearing <= max : bearing >= min && bearing <= max;
  }
};

FieldOfView
fieldOfView (const Eigen::Matrix2Xd& scan)
{
  std::vector<double> bearings (static_cast<std::size_t> (scan.cols ()));
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
    bearings[static_cast<std::size_t> (i)] = std::atan2 (scan (1, i), scan (0, i));
  if (bearings.empty ())
    return {M_PI, -M_PI, false};  // sees nothing
  std::sort (bearings.begin (), bearings.end ());
  double widest = bearings.front () + 2.0 * M_PI - bearings.back ();  // the gap across ±π
  std::size_t after = 0;  // the first return after the widest gap
  for (std::size_t k = 1; k < bearings.size (); ++k)
    if (bearings[k] - bearings[k - 1] > widest) {
      widest = bearings[k] - bearings[k - 1];
      after = k;
    }
  if (after == 0)
    return {bearings.front (), bearings.back (), false};
  return {bearings[after], bearings[after - 1], true};
}

/** The samples a hypothesis is judged on: those the target sensor sees under the
 *  current motion (points leaving the field of view say nothing against it), or
 *  all when it sees none of them. */
std::vector<bool>
judgedSamples (const std::vector<int>& samples, const Eigen::Matrix2Xd& source_current, const FieldOfView& view)
{
  std::vector<bool> judged (samples.size ());
  bool any = false;
  for (std::size_t k = 0; k < samples.size (); ++k)
    any = (judged[k] = view.contains (source_current.col (samples[k]))) || any;
  if (!any)
    judged.assign (samples.size (), true);
  return judged;
}

/** The squared overlap radius of every sample of a segment. */
std::vector<double>
sampleRadiiSquared (const std::vector<int>& samples, const ScanSegment& segment, const Eigen::Matrix2Xd& source_scan,
                    const SegmentMotionParameters& parameters)
{
  std::vector<double> radii (samples.size ());
  for (std::size_t k = 0; k < samples.size (); ++k)
    radii[k] = std::pow (overlapRadius (parameters, pointSpacing (source_scan, samples[k], segment.begin, segment.end)), 2);
  return radii;
}

}  // namespace

std::string
segmentParametersProblem (const SegmentMotionParameters& s)
{
  if (!(s.neighbours >= 0 && s.neighbours <= 64))
    return "segment neighbours must be in [0, 64]";
  if (!(s.breakpoint_angle > 0.0 && s.breakpoint_angle <= M_PI / 2))
    return "breakpoint_angle must be in (0, pi/2] rad";
  if (!(s.range_noise >= 0.0 && std::isfinite (s.range_noise)))
    return "range_noise must be a distance >= 0 m";
  if (s.min_segment_points < 1)
    return "min_segment_points must be >= 1";
  if (!(s.max_displacement >= 0.0 && std::isfinite (s.max_displacement)))
    return "max_displacement must be >= 0 m";
  if (!(s.max_speed >= 0.0 && std::isfinite (s.max_speed)))
    return "max_speed must be >= 0 m/s (0: no bound)";
  if (s.max_missing_returns < -1 || s.max_missing_returns > 100000)
    return "max_missing_returns must be in [0, 100000] beams, or -1 for no bound";
  if (!(s.overlap_radius > 0.0 && std::isfinite (s.overlap_radius)))
    return "overlap_radius must be > 0 m";
  if (!(s.overlap_spacings >= 0.0 && std::isfinite (s.overlap_spacings)))
    return "overlap_spacings must be >= 0 point spacings (0: overlap_radius everywhere)";
  return {};
}

double
overlapRadius (const SegmentMotionParameters& parameters, double point_spacing)
{
  if (parameters.overlap_spacings <= 0.0)
    return parameters.overlap_radius;
  const double resolution = std::max (3.0 * parameters.range_noise, parameters.overlap_spacings * point_spacing);
  return std::min (parameters.overlap_radius, resolution);
}

SegmentMotionParameters
limitToInterval (SegmentMotionParameters parameters, double interval)
{
  if (!std::isfinite (interval) || interval < 0.0)
    throw std::invalid_argument ("[pcl_crf::matching::limitToInterval] the interval between the scans must be a time "
                                 ">= 0 s (0: unknown), not " + std::to_string (interval));
  if (interval > 0.0 && parameters.max_speed > 0.0)
    parameters.max_displacement = std::min (parameters.max_displacement, parameters.max_speed * interval);
  return parameters;
}

double
pointSpacing (const Eigen::Matrix2Xd& points, Eigen::Index i, Eigen::Index begin, Eigen::Index end)
{
  if (begin < 0 || end > points.cols () || i < begin || i >= end)
    throw std::invalid_argument ("[pcl_crf::matching::pointSpacing] point " + std::to_string (i) + " is not in the run [" +
                                 std::to_string (begin) + ", " + std::to_string (end) + ") of the scan's " +
                                 std::to_string (points.cols ()) + " points");
  double spacing = 0.0;
  if (i > begin)
    spacing = (points.col (i) - points.col (i - 1)).norm ();
  if (i + 1 < end)
    spacing = std::max (spacing, (points.col (i + 1) - points.col (i)).norm ());
  return spacing;
}

std::vector<Eigen::Vector2d>
endAlignments (const Eigen::Vector2d& start, const Eigen::Vector2d& finish, const SegmentEnds& trusted,
               const Eigen::Matrix2Xd& target_scan, const std::vector<ScanSegment>& target_segments,
               const SegmentMotionParameters& parameters)
{
  checkSegments ("endAlignments", target_segments, target_scan.cols ());
  std::vector<Eigen::Vector2d> hypotheses (1, Eigen::Vector2d::Zero ());  // the current motion itself
  const double max_squared = parameters.max_displacement * parameters.max_displacement;
  for (const ScanSegment& t : target_segments) {
    if (t.size () < parameters.min_segment_points)
      continue;
    const SegmentEnds target_trusted = objectEnds (target_scan, t);
    const Eigen::Vector2d to_start = target_scan.col (t.begin) - start;
    const Eigen::Vector2d to_finish = target_scan.col (t.end - 1) - finish;
    if (trusted.start && target_trusted.start && to_start.squaredNorm () <= max_squared)
      hypotheses.push_back (to_start);
    if (trusted.finish && target_trusted.finish && to_finish.squaredNorm () <= max_squared)
      hypotheses.push_back (to_finish);
  }
  return hypotheses;
}

SegmentMotions
segmentMotionHypotheses (const Eigen::Matrix2Xd& source_scan, const Eigen::Matrix2Xd& source_current,
                         const Eigen::Matrix2Xd& target_scan, const std::vector<ScanSegment>& target_segments,
                         const KnnIndex& target_index, const SegmentMotionParameters& parameters)
{
  checkSegments ("segmentMotionHypotheses", target_segments, target_scan.cols ());
  SegmentMotions motions;
  const Eigen::Index n = source_scan.cols ();
  motions.translation.setZero (2, n);
  motions.has_hypothesis.assign (static_cast<std::size_t> (n), false);
  motions.current_support.setOnes (n);
  motions.hypothesis_support.setOnes (n);
  if (parameters.neighbours <= 0 || target_index.size () == 0)
    return motions;
  const FieldOfView view = fieldOfView (target_scan);
  std::vector<SegmentQuery> queries;
  Eigen::Index columns = 0;
  for (const ScanSegment& segment :
       segmentScan (source_scan, parameters.breakpoint_angle, parameters.range_noise)) {
    if (segment.size () < parameters.min_segment_points)
      continue;
    SegmentQuery query{segment, {}, scoringSamples (segment), columns, {}, {}};
    query.judged = judgedSamples (query.samples, source_current, view);
    query.radii_squared = sampleRadiiSquared (query.samples, segment, source_scan, parameters);
    query.hypotheses = endAlignments (source_current.col (segment.begin), source_current.col (segment.end - 1),
                                      objectEnds (source_scan, segment), target_scan, target_segments, parameters);

    columns += static_cast<Eigen::Index> (query.hypotheses.size () * query.samples.size ());
    queries.push_back (std::move (query));
  }
  Eigen::Matrix2Xd moved (2, columns);
  for (const SegmentQuery& query : queries) {
    Eigen::Index column = query.first_column;
    for (const Eigen::Vector2d& h : query.hypotheses)
      for (int i : query.samples)
        moved.col (column++) = source_current.col (i) + h;
  }
  const KnnIndex::Result nearest = target_index.search (moved, 1);  // one batched query scores everything
  for (const SegmentQuery& query : queries) {
    int best = 0, best_score = -1, current_score = 0;
    Eigen::Index column = query.first_column;
    for (std::size_t h = 0; h < query.hypotheses.size (); ++h) {
      int score = 0;  // explained judged samples; the current motion (h = 0) wins ties
      for (std::size_t k = 0; k < query.samples.size (); ++k, ++column)
        score += query.judged[k] && nearest.squared_distances (0, column) <= query.radii_squared[k] ? 1 : 0;
      if (h == 0)
        current_score = score;
      if (score > best_score) {
        best_score = score;
        best = static_cast<int> (h);
      }
    }
    const double samples = static_cast<double> (std::count (query.judged.begin (), query.judged.end (), true));
    for (int i = query.segment.begin; i < query.segment.end; ++i) {
      motions.current_support (i) = current_score / samples;
      motions.hypothesis_support (i) = best_score / samples;
      if (best == 0)
        continue;
      motions.translation.col (i) = query.hypotheses[best];
      motions.has_hypothesis[i] = true;
    }
  }
  return motions;
}

}  // namespace matching
}  // namespace pcl_crf
