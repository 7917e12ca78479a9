#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/core/rigid_fit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::clustering::makePointPairs] " + what);
}

/** Distance from point i of a scan to the nearer of its scan neighbours. */
double
samplingDistance (const Eigen::Matrix2Xd& scan, Eigen::Index i)
{
  double d = std::numeric_limits<double>::infinity ();
  if (i > 0)
    d = (scan.col (i) - scan.col (i - 1)).norm ();
  if (i + 1 < scan.cols ())
    d = std::min (d, (scan.col (i) - scan.col (i + 1)).norm ());
  return d;
}

}  // namespace

double
estimateAngularResolution (const Eigen::Matrix2Xd& scan)
{
  std::vector<double> steps;
  double previous = scan.cols () > 0 ? std::atan2 (scan (1, 0), scan (0, 0)) : 0.0;  // each bearing once
  for (Eigen::Index i = 1; i < scan.cols (); ++i)
  {
    const double bearing = std::atan2 (scan (1, i), scan (0, i));
    const double step = std::abs (std::remainder (bearing - previous, 2.0 * M_PI));
    previous = bearing;
    if (step > 0.0)
      steps.push_back (step);
  }
  if (steps.empty ())
    return 0.0;
  std::nth_element (steps.begin (), steps.begin () + steps.size () / 2, steps.end ());
  return steps[steps.size () / 2];
}

std::string
pointPairsProblem (const PointPairs& pairs)
{
  const auto n = static_cast<Eigen::Index> (pairs.size ());
  if (pairs.source.cols () != n || pairs.target.cols () != n || pairs.spacing.size () != n)
    return std::to_string (pairs.source.cols ()) + " source points, " + std::to_string (pairs.target.cols ()) +
           " target points, " + std::to_string (pairs.spacing.size ()) + " spacings and " + std::to_string (n) +
           " source indices: one of each per pair";
  if (!pairs.source.allFinite () || !pairs.target.allFinite ())
    return "the pairs hold NaN or infinite points";
  const std::string problem = scanPointsProblem (pairs.source, "the pairs' source");
  return problem.empty () ? scanPointsProblem (pairs.target, "the pairs' target") : problem;
}

PointPairs
makePointPairs (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                const std::vector<int>& source_match)
{
  if (static_cast<Eigen::Index> (source_match.size ()) != source.cols ())
    fail (std::to_string (source_match.size ()) + " matches for " + std::to_string (source.cols ()) +
          " source points");
  const std::string problem = scanPointsProblem (source, "source");
  if (!problem.empty ())
    fail (problem);
  std::vector<int> kept;
  for (std::size_t i = 0; i < source_match.size (); ++i)
  {
    const int m = source_match[i];
    if (m == kNoMatch)
      continue;
    if (m < 0 || m >= target.cols ())
      fail ("match " + std::to_string (m) + " of source point " + std::to_string (i) + " is outside [0, " +
            std::to_string (target.cols ()) + ")");
    if (!target.col (m).allFinite () || target.col (m).cwiseAbs ().maxCoeff () > kMaxCoordinate)
      fail ("source point " + std::to_string (i) + " matches target point " + std::to_string (m) +
            ", which has a NaN, infinite or beyond-1e18-m coordinate");
    kept.push_back (static_cast<int> (i));
  }
  PointPairs pairs;
  pairs.source.resize (2, static_cast<Eigen::Index> (kept.size ()));
  pairs.target.resize (2, static_cast<Eigen::Index> (kept.size ()));
  pairs.spacing.resize (static_cast<Eigen::Index> (kept.size ()));
  for (std::size_t k = 0; k < kept.size (); ++k)
  {
    pairs.spacing (k) = samplingDistance (source, kept[k]);
    pairs.source.col (k) = source.col (kept[k]);
    pairs.target.col (k) = target.col (source_match[kept[k]]);
  }
  pairs.source_index = std::move (kept);
  pairs.angular_resolution = estimateAngularResolution (source);
  return pairs;
}

std::vector<Rigid2d>
fitMotions (const PointPairs& pairs, const std::vector<int>& labels, int cluster_count)
{
  std::vector<RigidFitAccumulator> fits (static_cast<std::size_t> (std::max (cluster_count, 0)));
  for (std::size_t i = 0; i < pairs.size () && i < labels.size (); ++i)
    if (labels[i] >= 0 && labels[i] < cluster_count)
      fits[labels[i]].add (pairs.source.col (i), pairs.target.col (i));  // Eq. (3), w = 1
  std::vector<Rigid2d> motions;
  motions.reserve (fits.size ());
  for (const RigidFitAccumulator& fit : fits)
    motions.push_back (fit.solve ());
  return motions;
}

Eigen::MatrixXd
squaredResiduals (const PointPairs& pairs, const std::vector<Rigid2d>& motions)
{
  Eigen::MatrixXd f (static_cast<Eigen::Index> (motions.size ()), pairs.source.cols ());
  for (std::size_t l = 0; l < motions.size (); ++l)
  {
    const Eigen::Matrix2Xd moved = (motions[l].linear () * pairs.source).colwise () + motions[l].translation ();
    f.row (l) = (moved - pairs.target).colwise ().squaredNorm ();  // Eq. (2)
  }
  return f;
}

std::vector<int>
clusterSizes (const std::vector<int>& labels, int cluster_count)
{
  std::vector<int> sizes (static_cast<std::size_t> (std::max (cluster_count, 0)), 0);
  for (const int l : labels)
    if (l >= 0 && l < cluster_count)
      ++sizes[l];
  return sizes;
}

}  // namespace clustering
}  // namespace pcl_crf
