#include <pcl_crf/clustering/motion_kmeans.h>
#include <pcl_crf/core/rigid_fit.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

/** k contiguous runs of (nearly) equal length in scan order. */
std::vector<int>
contiguousRuns (std::size_t n, int k)
{
  std::vector<int> labels (n);
  for (std::size_t i = 0; i < n; ++i)
    labels[i] = static_cast<int> (i * static_cast<std::size_t> (k) / n);
  return labels;
}

/** Motions of the clusters with pairs, the previous motion for empty ones. */
void
refit (const PointPairs& pairs, const std::vector<int>& labels, std::vector<Rigid2d>& motions)
{
  std::vector<RigidFitAccumulator> fits (motions.size ());
  for (std::size_t i = 0; i < labels.size (); ++i)
    fits[labels[i]].add (pairs.source.col (i), pairs.target.col (i));  // Eq. (3)
  for (std::size_t l = 0; l < motions.size (); ++l)
    if (fits[l].weight () > 0.0)
      motions[l] = fits[l].solve ();
}

/** Assigns every pair to its nearest motion (Eq. (10)); returns whether anything changed. */
bool
assign (const PointPairs& pairs, const std::vector<Rigid2d>& motions, std::vector<int>& labels)
{
  const Eigen::MatrixXd residuals = squaredResiduals (pairs, motions);  // Eq. (10)
  bool changed = false;
  for (Eigen::Index i = 0; i < residuals.cols (); ++i)
  {
    Eigen::Index best = 0;
    residuals.col (i).minCoeff (&best);
    changed = changed || labels[i] != static_cast<int> (best);
    labels[i] = static_cast<int> (best);
  }
  return changed;
}

/** Drops empty clusters and numbers the others by decreasing size. */
void
sortBySize (MotionKMeansResult& result)
{
  const int k = static_cast<int> (result.motions.size ());
  const std::vector<int> sizes = clusterSizes (result.labels, k);
  std::vector<int> order (static_cast<std::size_t> (k));
  std::iota (order.begin (), order.end (), 0);
  std::stable_sort (order.begin (), order.end (), [&sizes] (int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank (order.size (), -1);
  std::vector<Rigid2d> motions;
  result.sizes.clear ();
  for (const int l : order)
    if (sizes[l] > 0)
    {
      rank[l] = static_cast<int> (motions.size ());
      motions.push_back (result.motions[l]);
      result.sizes.push_back (sizes[l]);
    }
  for (int& l : result.labels)
    l = rank[l];
  result.motions.swap (motions);
}

}  // namespace

MotionKMeansResult
clusterKMeans (const PointPairs& pairs, const MotionKMeansParameters& parameters)
{
  if (parameters.cluster_count < 1 || parameters.max_iterations < 1)
    throw std::invalid_argument ("[pcl_crf::clustering::clusterKMeans] cluster_count and max_iterations must be >= 1");
  const std::string problem = pointPairsProblem (pairs);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::clustering::clusterKMeans] " + problem);
  MotionKMeansResult result;
  if (pairs.size () == 0)
    return result;
  const int k =
      static_cast<int> (std::min<std::size_t> (pairs.size (), static_cast<std::size_t> (parameters.cluster_count)));
  result.labels = contiguousRuns (pairs.size (), k);
  result.motions.assign (static_cast<std::size_t> (k), Rigid2d::Identity ());
  while (result.iterations < parameters.max_iterations && !result.converged)
  {
    ++result.iterations;
    refit (pairs, result.labels, result.motions);
    result.converged = !assign (pairs, result.motions, result.labels);
  }
  refit (pairs, result.labels, result.motions);
  sortBySize (result);
  return result;
}

}  // namespace clustering
}  // namespace pcl_crf
