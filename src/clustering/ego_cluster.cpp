#include <pcl_crf/clustering/ego_cluster.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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
selectStaticCluster (const std::vector<Rigid2d>& motions, const Odometry& odometry, const std::vector<int>& sizes)
{
  if (!sizes.empty () && sizes.size () != motions.size ())
    throw std::invalid_argument ("[pcl_crf::clustering::selectStaticCluster] " + std::to_string (sizes.size ()) +
                                 " cluster sizes for " + std::to_string (motions.size ()) + " motions");
  const std::string problem = odometryProblem (odometry);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::clustering::selectStaticCluster] " + problem);
  const bool with_prior = std::any_of (sizes.begin (), sizes.end (), [] (int n) { return n > 0; });
  int best = -1;
  double best_score = std::numeric_limits<double>::infinity ();
  for (std::size_t l = 0; l < motions.size (); ++l)
  {
    if (with_prior && sizes[l] <= 0)
      continue;
    const double d2 = odometryMahalanobis (motions[l], odometry);
    // −log of p(odometry | T_l) p(static = l), up to a constant
    const double score = with_prior ? 0.5 * d2 - std::log (static_cast<double> (sizes[l])) : d2;
    if (best < 0 || score < best_score)
    {
      best = static_cast<int> (l);
      best_score = score;
    }
  }
  return best;
}

}  // namespace clustering
}  // namespace pcl_crf
