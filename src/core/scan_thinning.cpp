#include <pcl_crf/core/scan_thinning.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pcl_crf {

namespace {

/** a − b wrapped to (−π, π] [rad]. */
double
angleBetween (double a, double b)
{
  return std::remainder (a - b, 2.0 * M_PI);
}

double
bearing (const Eigen::Matrix2Xd& points, Eigen::Index i)
{
  return std::atan2 (points (1, i), points (0, i));
}

}  // namespace

double
medianBeamSpacing (const Eigen::Matrix2Xd& points)
{
  std::vector<double> steps;
  steps.reserve (static_cast<std::size_t> (std::max<Eigen::Index> (points.cols () - 1, 0)));
  Eigen::Index previous = -1;
  for (Eigen::Index i = 0; i < points.cols (); ++i) {
    if (points.col (i).squaredNorm () == 0.0)
      continue;  // no bearing at the sensor
    if (previous >= 0)
      steps.push_back (std::abs (angleBetween (bearing (points, i), bearing (points, previous))));
    previous = i;
  }
  if (steps.empty ())
    return 0.0;
  const auto middle = steps.begin () + static_cast<std::ptrdiff_t> (steps.size () / 2);
  std::nth_element (steps.begin (), middle, steps.end ());
  return *middle;
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
  ThinnedScan thinned;
  const Eigen::Index n = points.cols ();
  if (factor <= 1 || n == 0) {
    thinned.kept.resize (static_cast<std::size_t> (n));
    for (Eigen::Index i = 0; i < n; ++i)
      thinned.kept[static_cast<std::size_t> (i)] = static_cast<int> (i);
    thinned.points = points;
    return thinned;
  }
  // The beam of every point, counted from the first along the unwrapped bearings.
  double swept = 0.0;
  double previous = bearing (points, 0);
  thinned.kept.push_back (0);
  for (Eigen::Index i = 1; i < n; ++i) {
    const double here = bearing (points, i);
    swept += angleBetween (here, previous);
    previous = here;
    if (std::llround (swept / scan_spacing) % factor == 0)
      thinned.kept.push_back (static_cast<int> (i));
  }
  thinned.points.resize (2, static_cast<Eigen::Index> (thinned.kept.size ()));
  for (std::size_t k = 0; k < thinned.kept.size (); ++k)
    thinned.points.col (static_cast<Eigen::Index> (k)) = points.col (thinned.kept[k]);
  return thinned;
}

ThinnedScan
thinToSpacing (const Eigen::Matrix2Xd& points, double model_spacing)
{
  const double scan_spacing = medianBeamSpacing (points);
  return thinScan (points, thinningFactor (scan_spacing, model_spacing), scan_spacing);
}

}  // namespace pcl_crf
