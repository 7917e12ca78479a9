#include <pcl_crf/clustering/cluster_fits.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

Eigen::MatrixXd
oneHot (const std::vector<int>& labels, int cluster_count)
{
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero (cluster_count, static_cast<Eigen::Index> (labels.size ()));
  for (std::size_t i = 0; i < labels.size (); ++i)
    if (labels[i] >= 0 && labels[i] < cluster_count)
      weights (labels[i], static_cast<Eigen::Index> (i)) = 1.0;
  return weights;
}

Eigen::MatrixXd
ownPointWeights (const Eigen::MatrixXd& marginals, const std::vector<int>& labels)
{
  if (static_cast<Eigen::Index> (labels.size ()) != marginals.cols ())
    throw std::invalid_argument ("[pcl_crf::clustering::ownPointWeights] " + std::to_string (labels.size ()) +
                                 " labels for " + std::to_string (marginals.cols ()) + " marginal columns");
  return oneHot (labels, static_cast<int> (marginals.rows ())).cwiseProduct (marginals);
}

std::vector<RigidFitAccumulator>
accumulateFits (const PointPairs& pairs, const Eigen::MatrixXd& weights)
{
  std::vector<RigidFitAccumulator> fits (static_cast<std::size_t> (weights.rows ()));
  for (Eigen::Index i = 0; i < weights.cols (); ++i)
    for (Eigen::Index l = 0; l < weights.rows (); ++l)
      if (weights (l, i) > 0.0)
        fits[l].add (pairs.source.col (i), pairs.target.col (i), weights (l, i));  // Eq. (3)
  return fits;
}

std::vector<Rigid2d>
solveFits (const std::vector<RigidFitAccumulator>& fits)
{
  std::vector<Rigid2d> motions;
  motions.reserve (fits.size ());
  for (const RigidFitAccumulator& fit : fits)
    motions.push_back (fit.solve ());
  return motions;
}

}  // namespace clustering
}  // namespace pcl_crf
