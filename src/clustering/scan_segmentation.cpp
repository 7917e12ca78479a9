#include <pcl_crf/clustering/scan_segmentation.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace pcl_crf {
namespace clustering {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity ();

void
requirePositive (double break_distance, const char* method)
{
  if (!(break_distance > 0.0))
    throw std::invalid_argument (std::string ("[pcl_crf::clustering::") + method +
                                 "] break_distance must be > 0 [m]");
}

/** For every point, the index of the closest point before it (step −1) or after
 *  it (step +1) in its segment that holds a label, or −1. One pass, O(N). */
std::vector<Eigen::Index>
closestLabelled (const std::vector<int>& segment, const std::vector<bool>& has_label, int step)
{
  const auto n = static_cast<Eigen::Index> (segment.size ());
  std::vector<Eigen::Index> closest (segment.size (), -1);
  Eigen::Index last = -1;
  for (Eigen::Index k = 0; k < n; ++k)
  {
    const Eigen::Index i = step > 0 ? n - 1 - k : k;
    if (last >= 0 && segment[last] != segment[i])
      last = -1;
    closest[i] = last;
    if (has_label[i])
      last = i;
  }
  return closest;
}

/** Every point without a label (\a has_label false) takes the label in \a labels of the
 *  nearer of the closest labelled points before and after it on its segment, if any. */
void
fillFromNearestLabelled (const Eigen::Matrix2Xd& scan, const std::vector<int>& segment,
                         const std::vector<bool>& has_label, std::vector<int>& labels)
{
  const std::vector<Eigen::Index> before = closestLabelled (segment, has_label, -1);
  const std::vector<Eigen::Index> after = closestLabelled (segment, has_label, +1);
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
  {
    if (has_label[i])
      continue;
    const double d_before = before[i] < 0 ? kInf : (scan.col (before[i]) - scan.col (i)).squaredNorm ();
    const double d_after = after[i] < 0 ? kInf : (scan.col (after[i]) - scan.col (i)).squaredNorm ();
    if (d_before < kInf || d_after < kInf)
      labels[i] = labels[d_before <= d_after ? before[i] : after[i]];
  }
}

}  // namespace

std::vector<int>
segmentByDistance (const Eigen::Matrix2Xd& points, double break_distance, int max_segment_points)
{
  requirePositive (break_distance, "segmentByDistance");
  std::vector<int> segment (static_cast<std::size_t> (points.cols ()), 0);
  const double break_squared = break_distance * break_distance;
  int current = 0, length = 0;
  for (Eigen::Index i = 0; i < points.cols (); ++i)
  {
    const bool gap = i > 0 && (points.col (i) - points.col (i - 1)).squaredNorm () > break_squared;
    const bool full = max_segment_points > 0 && length >= max_segment_points;
    if (i > 0 && (gap || full))
    {
      ++current;
      length = 0;
    }
    segment[i] = current;
    ++length;
  }
  return segment;
}

void
mergeNarrowestBreaks (const Eigen::Matrix2Xd& points, int max_segments, std::vector<int>& segment)
{
  const char* where = "[pcl_crf::clustering::mergeNarrowestBreaks] ";
  if (max_segments < 1)
    throw std::invalid_argument (std::string (where) + "max_segments must be >= 1, got " + std::to_string (max_segments));
  if (segment.size () != static_cast<std::size_t> (points.cols ()))
    throw std::invalid_argument (std::string (where) + std::to_string (segment.size ()) + " segment indices for " +
                                 std::to_string (points.cols ()) + " points");
  std::vector<std::pair<double, std::size_t>> breaks;  // (−width, first point after the break)
  for (std::size_t i = 0; i < segment.size (); ++i)
  {
    const int previous = i == 0 ? 0 : segment[i - 1];
    if (segment[i] != previous && (i == 0 || segment[i] != previous + 1))
      throw std::invalid_argument (std::string (where) + "segment index " + std::to_string (segment[i]) + " at point " +
                                   std::to_string (i) + " does not follow " + std::to_string (previous));
    if (i > 0 && segment[i] != previous)
      breaks.emplace_back (-(points.col (i) - points.col (i - 1)).squaredNorm (), i);
  }
  if (breaks.size () < static_cast<std::size_t> (max_segments))
    return;
  const auto kept_end = breaks.begin () + (max_segments - 1);
  std::nth_element (breaks.begin (), kept_end, breaks.end ());  // pairs order ties by scan order
  std::vector<bool> starts (segment.size (), false);
  for (auto b = breaks.begin (); b != kept_end; ++b)
    starts[b->second] = true;
  int current = 0;
  for (std::size_t i = 0; i < segment.size (); ++i)
  {
    if (starts[i])
      ++current;
    segment[i] = current;
  }
}

std::vector<int>
completeLabels (const Eigen::Matrix2Xd& scan, const std::vector<int>& labelled_index,
                const std::vector<int>& labels, double break_distance, int default_label)
{
  requirePositive (break_distance, "completeLabels");
  if (labelled_index.size () != labels.size ())
    throw std::invalid_argument ("[pcl_crf::clustering::completeLabels] " + std::to_string (labels.size ()) +
                                 " labels for " + std::to_string (labelled_index.size ()) + " labelled points");
  std::vector<int> result (static_cast<std::size_t> (scan.cols ()), default_label);
  std::vector<bool> has_label (result.size (), false);
  for (std::size_t k = 0; k < labelled_index.size (); ++k)
  {
    const int i = labelled_index[k];
    if (i < 0 || i >= scan.cols () || (k > 0 && i <= labelled_index[k - 1]))
      throw std::invalid_argument ("[pcl_crf::clustering::completeLabels] labelled index " + std::to_string (i) +
                                   " is out of range or not increasing");
    result[i] = labels[k];
    has_label[i] = true;
  }
  fillFromNearestLabelled (scan, segmentByDistance (scan, break_distance, 0), has_label, result);
  return result;
}

std::vector<int>
completeLabelsWithinSegments (const Eigen::Matrix2Xd& scan, const std::vector<int>& segment,
                              const std::vector<int>& labels, int unlabelled)
{
  const auto n = static_cast<std::size_t> (scan.cols ());
  if (segment.size () != n || labels.size () != n)
    throw std::invalid_argument ("[pcl_crf::clustering::completeLabelsWithinSegments] " + std::to_string (n) +
                                 " points, " + std::to_string (segment.size ()) + " segment indices and " +
                                 std::to_string (labels.size ()) + " labels: give one of each per point");
  std::vector<bool> has_label (n);
  for (std::size_t i = 0; i < n; ++i)
    has_label[i] = labels[i] != unlabelled;
  std::vector<int> completed (labels);
  fillFromNearestLabelled (scan, segment, has_label, completed);
  return completed;
}

}  // namespace clustering
}  // namespace pcl_crf
