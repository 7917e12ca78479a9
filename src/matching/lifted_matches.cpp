#include <pcl_crf/matching/lifted_matches.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** Window of kept neighbours (on either side) whose offsets are averaged. */
constexpr int kOffsetWindow = 2;
/** An average offset beyond this many thinned target steps is motion, not sampling. */
constexpr double kOffsetSteps = 2.0;
/** Kept target points between the matches of a dropped point's two neighbours beyond
 *  which they are taken to disagree (bounds the search). */
constexpr int kMaxNeighbourGap = 32;

void
checkSizes (const ThinnedPair& thinned, const Eigen::Matrix2Xd& source, const std::vector<int>& coarse_matches,
            const std::vector<int>& groups, const std::vector<Rigid2d>& motions)
{
  const std::size_t kept = thinned.source.kept.size ();
  if (coarse_matches.size () != kept || groups.size () != kept)
    throw std::invalid_argument ("[pcl_crf::matching::liftMatches] " + std::to_string (coarse_matches.size ()) +
                                 " matches and " + std::to_string (groups.size ()) + " groups for " +
                                 std::to_string (kept) + " kept source points");
  if (thinned.anchors.size () != static_cast<std::size_t> (source.cols ()))
    throw std::invalid_argument ("[pcl_crf::matching::liftMatches] the anchors are not those of this source scan");
  const int target_kept = static_cast<int> (thinned.target.kept.size ());
  for (std::size_t k = 0; k < kept; ++k) {
    if (coarse_matches[k] != kNoMatch && (coarse_matches[k] < 0 || coarse_matches[k] >= target_kept))
      throw std::invalid_argument ("[pcl_crf::matching::liftMatches] match " + std::to_string (coarse_matches[k]) +
                                   " is not a kept target point");
    if (groups[k] >= static_cast<int> (motions.size ()))
      throw std::invalid_argument ("[pcl_crf::matching::liftMatches] group " + std::to_string (groups[k]) +
                                   " has no motion");
  }
}

/** Smallest distance from kept target point c to its kept neighbours [m]. */
double
thinnedStep (const ThinnedScan& target, int c)
{
  const Eigen::Index count = target.points.cols ();
  double step = std::numeric_limits<double>::infinity ();
  if (c > 0)
    step = (target.points.col (c) - target.points.col (c - 1)).norm ();
  if (c + 1 < count)
    step = std::min (step, (target.points.col (c) - target.points.col (c + 1)).norm ());
  return std::isfinite (step) ? step : 0.0;
}

/** Where the motion of kept source point a puts full source point i, corrected by the
 *  mean offset of a's matched neighbours when it exceeds the sampling step. */
Eigen::Vector2d
predictedPosition (const Eigen::Matrix2Xd& source, const ThinnedPair& thinned, const std::vector<int>& coarse_matches,
                   const std::vector<int>& groups, const std::vector<Rigid2d>& motions, int i, int a)
{
  const Rigid2d& T = motions[groups[a]];
  const Eigen::Vector2d position = T * source.col (i);
  const int kept = static_cast<int> (thinned.source.kept.size ());
  Eigen::Vector2d offset = Eigen::Vector2d::Zero ();
  int count = 0;
  for (int k = std::max (0, a - kOffsetWindow); k <= std::min (kept - 1, a + kOffsetWindow); ++k) {
    if (coarse_matches[k] == kNoMatch || groups[k] != groups[a])
      continue;
    offset += thinned.target.points.col (coarse_matches[k]) - T * thinned.source.points.col (k);
    ++count;
  }
  offset /= std::max (count, 1);
  const double gate = kOffsetSteps * thinnedStep (thinned.target, coarse_matches[a]);
  return offset.norm () > gate ? Eigen::Vector2d (position + offset) : position;
}

/** The kept source point on the other side of dropped point i from its anchor a, or −1. */
int
otherNeighbour (const ThinnedScan& source, int i, int a)
{
  const int other = source.kept[a] < i ? a + 1 : a - 1;
  return other >= 0 && other < static_cast<int> (source.kept.size ()) ? other : -1;
}

/** The full target points among which dropped or kept source point i, anchored at
 *  a, takes its match (see liftMatches). \return [first, last] */
Eigen::Vector2i
searchSpan (const ThinnedPair& thinned, Eigen::Index target_size, const std::vector<int>& coarse_matches,
            const std::vector<int>& groups, int i, int a)
{
  Eigen::Vector2i span = targetSpan (thinned.target, target_size, coarse_matches[a]);
  if (thinned.source.kept[a] == i)
    return span;
  const int b = otherNeighbour (thinned.source, i, a);
  if (b >= 0 && coarse_matches[b] != kNoMatch && groups[b] == groups[a] &&
      std::abs (coarse_matches[b] - coarse_matches[a]) <= kMaxNeighbourGap) {
    const Eigen::Vector2i other = targetSpan (thinned.target, target_size, coarse_matches[b]);
    return {std::min (span (0), other (0)), std::max (span (1), other (1))};
  }
  return {std::max (0, span (0) - 1), std::min (static_cast<int> (target_size) - 1, span (1) + 1)};
}

}  // namespace

ThinnedPair
thinPair (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, double model_spacing)
{
  ThinnedPair thinned;
  thinned.source = thinToSpacing (source, model_spacing);
  thinned.target = thinToSpacing (target, model_spacing);
  thinned.anchors = thinnedAnchors (source, thinned.source);
  return thinned;
}

std::vector<int>
thinnedAnchors (const Eigen::Matrix2Xd& source, const ThinnedScan& thinned)
{
  std::vector<int> anchors (static_cast<std::size_t> (source.cols ()), -1);
  if (thinned.kept.empty ())
    return anchors;
  int next = 0;  // position of the first kept point at or after i
  for (int i = 0; i < static_cast<int> (source.cols ()); ++i) {
    while (next < static_cast<int> (thinned.kept.size ()) && thinned.kept[next] < i)
      ++next;
    if (next < static_cast<int> (thinned.kept.size ()) && thinned.kept[next] == i) {
      anchors[i] = next;
      continue;
    }
    const int before = next - 1, after = next < static_cast<int> (thinned.kept.size ()) ? next : -1;
    if (before < 0 || after < 0) {
      anchors[i] = before < 0 ? after : before;
      continue;
    }
    const double to_before = (source.col (i) - source.col (thinned.kept[before])).squaredNorm ();
    const double to_after = (source.col (i) - source.col (thinned.kept[after])).squaredNorm ();
    anchors[i] = to_after < to_before ? after : before;
  }
  return anchors;
}

std::vector<int>
liftLabels (const std::vector<int>& anchors, const std::vector<int>& coarse_labels)
{
  std::vector<int> labels (anchors.size ());
  for (std::size_t i = 0; i < anchors.size (); ++i) {
    if (anchors[i] < 0 || static_cast<std::size_t> (anchors[i]) >= coarse_labels.size ())
      throw std::invalid_argument ("[pcl_crf::matching::liftLabels] point " + std::to_string (i) + " is anchored to " +
                                   std::to_string (anchors[i]) + ", not one of the " +
                                   std::to_string (coarse_labels.size ()) + " labelled points");
    labels[i] = coarse_labels[static_cast<std::size_t> (anchors[i])];
  }
  return labels;
}

Eigen::Vector2i
targetSpan (const ThinnedScan& target, Eigen::Index full_size, int kept_position)
{
  const int last_kept = static_cast<int> (target.kept.size ()) - 1;
  if (kept_position < 0 || kept_position > last_kept || target.kept.back () >= full_size)
    throw std::invalid_argument ("[pcl_crf::matching::targetSpan] kept point " + std::to_string (kept_position) +
                                 " of " + std::to_string (last_kept + 1) + " in a scan of " +
                                 std::to_string (full_size) + " points: it must be a kept point of that scan");
  const int first = kept_position > 0 ? target.kept[kept_position - 1] + 1 : 0;
  const int last = kept_position < last_kept ? target.kept[kept_position + 1] - 1 : static_cast<int> (full_size) - 1;
  return {first, last};
}

std::vector<int>
liftMatches (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const ThinnedPair& thinned,
             const std::vector<int>& coarse_matches, const std::vector<int>& groups,
             const std::vector<Rigid2d>& motions)
{
  checkSizes (thinned, source, coarse_matches, groups, motions);
  std::vector<int> matches (static_cast<std::size_t> (source.cols ()), kNoMatch);
  for (int i = 0; i < static_cast<int> (source.cols ()); ++i) {
    const int a = thinned.anchors[i];
    if (a < 0 || coarse_matches[a] == kNoMatch || groups[a] < 0)
      continue;
    const Eigen::Vector2i span = searchSpan (thinned, target.cols (), coarse_matches, groups, i, a);
    const Eigen::Vector2d p = predictedPosition (source, thinned, coarse_matches, groups, motions, i, a);
    int best = span (0);
    for (int j = span (0) + 1; j <= span (1); ++j)
      if ((target.col (j) - p).squaredNorm () < (target.col (best) - p).squaredNorm ())
        best = j;
    matches[i] = best;
  }
  return matches;
}

}  // namespace matching
}  // namespace pcl_crf
