#include <pcl_crf/core/scan_thinning.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {

namespace {

/** a − b wrapped to (−π, π] [rad]. */
double
angleBetween (double a, double b)
{
  return std::remainder (a - b, 2.0 * M_PI);
}

/** The bearing of every point seen from the origin [rad]. */
std::vector<double>
bearingsOf (const Eigen::Matrix2Xd& points)
{
  std::vector<double> bearings (static_cast<std::size_t> (points.cols ()));
  for (Eigen::Index i = 0; i < points.cols (); ++i)
    bearings[static_cast<std::size_t> (i)] = std::atan2 (points (1, i), points (0, i));
  return bearings;
}

double
medianSpacing (const Eigen::Matrix2Xd& points, const std::vector<double>& bearings)
{
  std::vector<double> steps;
  steps.reserve (bearings.size ());
  Eigen::Index previous = -1;
  for (Eigen::Index i = 0; i < points.cols (); ++i) {
    if (points.col (i).squaredNorm () == 0.0)
      continue;  // no bearing at the sensor
    if (previous >= 0)
      steps.push_back (std::abs (angleBetween (bearings[i], bearings[previous])));
    previous = i;
  }
  if (steps.empty ())
    return 0.0;
  const auto middle = steps.begin () + static_cast<std::ptrdiff_t> (steps.size () / 2);
  std::nth_element (steps.begin (), middle, steps.end ());
  return *middle;
}

ThinnedScan
keepAll (const Eigen::Matrix2Xd& points)
{
  ThinnedScan thinned;
  thinned.kept.resize (static_cast<std::size_t> (points.cols ()));
  for (Eigen::Index i = 0; i < points.cols (); ++i)
    thinned.kept[static_cast<std::size_t> (i)] = static_cast<int> (i);
  thinned.points = points;
  return thinned;
}

/** thinScan with the bearings computed. */
ThinnedScan
thinAlong (const Eigen::Matrix2Xd& points, const std::vector<double>& bearings, int factor, double scan_spacing)
{
  const Eigen::Index n = points.cols ();
  if (factor <= 1 || n == 0)
    return keepAll (points);
  ThinnedScan thinned;
  thinned.factor = factor;
  // The beam of every point, counted from the first along the unwrapped bearings.
  double swept = 0.0;
  thinned.kept.push_back (0);
  for (Eigen::Index i = 1; i < n; ++i) {
    swept += angleBetween (bearings[i], bearings[i - 1]);
    if (std::llround (swept / scan_spacing) % factor == 0)
      thinned.kept.push_back (static_cast<int> (i));
  }
  thinned.points.resize (2, static_cast<Eigen::Index> (thinned.kept.size ()));
  for (std::size_t k = 0; k < thinned.kept.size (); ++k)
    thinned.points.col (static_cast<Eigen::Index> (k)) = points.col (thinned.kept[k]);
  return thinned;
}

}  // namespace

double
medianBeamSpacing (const Eigen::Matrix2Xd& points)
{
  return medianSpacing (points, bearingsOf (points));
}

int
thinningFactor (double scan_spacing, double model_spacing)
{
  if (!(scan_spacing >= 0.0) || !(model_spacing >= 0.0) || !std::isfinite (scan_spacing) ||
      !std::isfinite (model_spacing))
    throw std::invalid_argument ("[pcl_crf::thinningFactor] beam spacings must be finite and >= 0");
  if (scan_spacing == 0.0 || model_spacing == 0.0)
    return 1;
  const double ratio = model_spacing / scan_spacing;
  return std::max (1, static_cast<int> (std::floor (std::min (ratio + 0.1, 1e6))));
}

ThinnedScan
thinScan (const Eigen::Matrix2Xd& points, int factor, double scan_spacing)
{
  if (factor <= 1)
    return keepAll (points);
  if (!(scan_spacing > 0.0) || !std::isfinite (scan_spacing))
    throw std::invalid_argument ("[pcl_crf::thinScan] thinning by " + std::to_string (factor) +
                                 " beams needs the scan's beam spacing, an angle > 0 rad, not " +
                                 std::to_string (scan_spacing));
  if (!points.allFinite ())
    throw std::invalid_argument ("[pcl_crf::thinScan] the scan holds NaN or infinite points");
  return thinAlong (points, bearingsOf (points), factor, scan_spacing);
}

ThinnedScan
thinToSpacing (const Eigen::Matrix2Xd& points, double model_spacing)
{
  if (model_spacing == 0.0)
    return keepAll (points);
  const std::vector<double> bearings = bearingsOf (points);
  const double scan_spacing = medianSpacing (points, bearings);
  return thinAlong (points, bearings, thinningFactor (scan_spacing, model_spacing), scan_spacing);
}

}  // namespace pcl_crf
