#include <pcl_crf/matching/shape_features.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl_crf {
namespace matching {

namespace {

/** Turning angle from direction a to direction b in (−π, π]; 0 when either is zero. */
double
turningAngle (const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const double cross = a.x () * b.y () - a.y () * b.x ();
  const double dot = a.dot (b);
  return (cross == 0.0 && dot == 0.0) ? 0.0 : std::atan2 (cross, dot);
}

/** Accumulated length along the scan: arc[i] = Σ_{m<i} ||p_{m+1} − p_m||. */
std::vector<double>
arcLength (const Eigen::Matrix2Xd& scan)
{
  std::vector<double> arc (static_cast<std::size_t> (scan.cols ()), 0.0);
  for (Eigen::Index m = 1; m < scan.cols (); ++m)
    arc[m] = arc[m - 1] + (scan.col (m) - scan.col (m - 1)).norm ();
  return arc;
}

}  // namespace

Eigen::MatrixXd
computeShapeFeatures (const Eigen::Matrix2Xd& scan)
{
  const Eigen::Index n = scan.cols ();
  Eigen::MatrixXd features (kShapeFeatureCount, n);
  const std::vector<double> arc = arcLength (scan);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d p = scan.col (i);
    for (int o = 0; o < 3; ++o) {
      const Eigen::Index before = std::max<Eigen::Index> (i - kShapeOffsets[o], 0);
      const Eigen::Index after = std::min<Eigen::Index> (i + kShapeOffsets[o], n - 1);
      const Eigen::Vector2d to_before = p - scan.col (before);
      const Eigen::Vector2d to_after = scan.col (after) - p;
      features (kDistanceBefore1 + 2 * o, i) = to_before.norm ();
      features (kDistanceAfter1 + 2 * o, i) = to_after.norm ();
      features (kAngle1 + o, i) = turningAngle (to_before, to_after);
      features (kGeodesicBefore1 + 2 * o, i) = arc[i] - arc[before];
      features (kGeodesicAfter1 + 2 * o, i) = arc[after] - arc[i];
    }
    features (kRadius, i) = p.norm ();
  }
  return features;
}

}  // namespace matching
}  // namespace pcl_crf
