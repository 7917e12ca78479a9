#include <pcl_crf/clustering/ego_cluster.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace pcl_crf {
namespace clustering {

namespace {

double
wrapAngle (double angle)
{
  return std::atan2 (std::sin (angle), std::cos (angle));
}

}  // namespace

double
odometryMahalanobis (const Rigid2d& T_target_source, const Odometry& odometry)
{
  const Eigen::Vector3d cluster = toXYTheta (T_target_source.inverse ());
  const Eigen::Vector3d measured = toXYTheta (odometry.T_source_target);
  Eigen::Vector3d e = cluster - measured;
  e (2) = wrapAngle (e (2));
  const Eigen::Vector3d solved = odometry.covariance.completeOrthogonalDecomposition ().solve (e);
  return e.dot (solved);
}

int
selectStaticCluster (const std::vector<Rigid2d>& motions, const Odometry& odometry)
{
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity ();
  for (std::size_t l = 0; l < motions.size (); ++l)
  {
    const double d = odometryMahalanobis (motions[l], odometry);
    if (best < 0 || d < best_distance)
    {
      best = static_cast<int> (l);
      best_distance = d;
    }
  }
  return best;
}

}  // namespace clustering
}  // namespace pcl_crf
