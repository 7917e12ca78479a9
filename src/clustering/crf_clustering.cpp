#include <pcl_crf/clustering/cluster_fits.h>
#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/clustering/ego_cluster.h>
#include <pcl_crf/clustering/scan_segmentation.h>
#include <pcl_crf/crf/chain_inference.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::clustering::clusterPointPairs] " + what);
}

/** The clusters each node keeps: its \a max_states best by local log-potential,
 *  of those the ones within \a margin of the best; increasing cluster order. */
CandidateStates
candidateStates (const Eigen::MatrixXd& local, double margin, int max_states)
{
  CandidateStates states (static_cast<std::size_t> (local.cols ()));
  const auto keep = static_cast<std::size_t> (std::min<Eigen::Index> (local.rows (), max_states));
  for (Eigen::Index i = 0; i < local.cols (); ++i)
  {
    std::vector<int>& best = states[i];  // kept sorted by decreasing potential while scanning
    best.reserve (keep + 1);
    for (int l = 0; l < static_cast<int> (local.rows ()); ++l)
    {
      if (best.size () == keep && local (l, i) <= local (best.back (), i))
        continue;
      auto at = std::find_if (best.begin (), best.end (), [&] (int b) { return local (l, i) > local (b, i); });
      best.insert (at, l);
      if (best.size () > keep)
        best.pop_back ();
    }
    const double floor = local (best.front (), i) - margin;
    const auto below = [&] (int l) { return local (l, i) < floor; };
    best.erase (std::remove_if (best.begin (), best.end (), below), best.end ());
    std::sort (best.begin (), best.end ());
  }
  return states;
}

/** Column-wise softmax of log-potentials. The column maxima and sums are evaluated
 *  once: inside a rowwise () expression Eigen would recompute them for every entry. */
Eigen::MatrixXd
columnSoftmax (const Eigen::MatrixXd& log_p)
{
  const Eigen::RowVectorXd maxima = log_p.colwise ().maxCoeff ();
  Eigen::MatrixXd p = (log_p.rowwise () - maxima).array ().exp ().matrix ();
  const Eigen::RowVectorXd sums = p.colwise ().sum ();
  p.array ().rowwise () /= sums.array ();
  return p;
}

/** What one round of belief propagation gives, in the numbering of its clusters. */
struct Beliefs
{
  std::vector<int> labels;    // MAP
  Eigen::MatrixXd marginals;  // S x n
  Eigen::MatrixXd local;      // S x n local log-potentials
};

/** One round (Sec. IV-D) from the fit weights (S x n): motions (Eq. (3)), residuals
 *  (Eq. (2)), pruned candidate states, sum-product and max-product. */
Beliefs
propagate (const PointPairs& pairs, const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters,
           const Eigen::MatrixXd& fit_weights)
{
  const std::vector<Rigid2d> motions = solveFits (accumulateFits (pairs, fit_weights));  // Eq. (3)
  const Eigen::MatrixXd residuals = squaredResiduals (pairs, motions);                    // Eq. (2)
  Beliefs beliefs;
  beliefs.local = localLogPotentials (pairs, residuals, weights, parameters.features);
  const CandidateStates states = candidateStates (beliefs.local, parameters.pruning_margin, parameters.max_states);
  const crf::ChainPotentials chain =
      chainPotentials (pairs, motions, states, beliefs.local, weights, parameters.features);
  const crf::MarginalResult sum_product = crf::sumProduct (chain);
  const crf::MapResult map = crf::maxProduct (chain);
  beliefs.marginals = Eigen::MatrixXd::Zero (static_cast<Eigen::Index> (motions.size ()), pairs.source.cols ());
  beliefs.labels.resize (pairs.size ());
  for (std::size_t i = 0; i < pairs.size (); ++i)
  {
    for (std::size_t a = 0; a < states[i].size (); ++a)
      beliefs.marginals (states[i][a], static_cast<Eigen::Index> (i)) = sum_product.node_marginals[i] (a);
    beliefs.labels[i] = states[i][map.labels[i]];
  }
  return beliefs;
}

/** Renumbers the clusters by decreasing size (ties: previous order). */
void
sortBySize (CrfClusteringResult& result)
{
  const int s = static_cast<int> (result.motions.size ());
  std::vector<int> sizes = clusterSizes (result.labels, s);
  std::vector<int> order (static_cast<std::size_t> (s));
  std::iota (order.begin (), order.end (), 0);
  std::stable_sort (order.begin (), order.end (), [&sizes] (int a, int b) { return sizes[a] > sizes[b]; });
  std::vector<int> rank (order.size ());
  Eigen::MatrixXd marginals (result.marginals.rows (), result.marginals.cols ());
  std::vector<Rigid2d> motions (order.size ());
  for (int k = 0; k < s; ++k)
  {
    rank[order[k]] = k;
    marginals.row (k) = result.marginals.row (order[k]);
    motions[k] = result.motions[order[k]];
    result.sizes.push_back (sizes[order[k]]);
  }
  for (int& l : result.labels)
    l = rank[l];
  result.marginals.swap (marginals);
  result.motions.swap (motions);
}

}  // namespace

void
validateParameters (const CrfClusteringParameters& p)
{
  if (!(p.segment_break_distance > 0.0))
    fail ("segment_break_distance must be > 0 [m]");
  if (p.max_iterations < 1)
    fail ("max_iterations must be >= 1");
  if (!(p.max_average_neff > 1.0))
    fail ("max_average_neff must be > 1");
  if (!(p.pruning_margin > 0.0))
    fail ("pruning_margin must be > 0 [nats]");
  if (p.max_states < 1)
    fail ("max_states must be >= 1");
  if (!(p.features.min_neighbour_distance > 0.0))
    fail ("features.min_neighbour_distance must be > 0 [m]");
  if (!(p.features.min_spacing > 0.0))
    fail ("features.min_spacing must be > 0 [m]");
}

CrfClusteringResult
clusterPointPairs (const PointPairs& pairs, const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters,
                   const Odometry* odometry)
{
  validateParameters (parameters);
  if (weights.size () != kWeightCount || !weights.allFinite ())
    fail ("expected " + std::to_string (kWeightCount) + " finite weights, got " + std::to_string (weights.size ()));
  CrfClusteringResult result;
  if (pairs.size () == 0)
    return result;

  // Sec. IV-D: over-segment the scan, one cluster per segment.
  result.labels = segmentByDistance (pairs.source, parameters.segment_break_distance, parameters.max_segment_points);
  int cluster_count = result.labels.back () + 1;
  result.initial_clusters = cluster_count;
  result.marginals = oneHot (result.labels, cluster_count);

  // Sec. IV-D, IV-E: BP, removal of empty and ambiguous clusters (Eq. (8)), refit,
  // until the MAP labelling and the clusters stop changing.
  while (result.iterations < parameters.max_iterations && !result.converged)
  {
    ++result.iterations;
    Beliefs beliefs = propagate (pairs, weights, parameters, result.marginals);
    const bool same_labels = beliefs.labels == result.labels;
    const std::vector<int> kept =
        selectClusters (parameters.merge_evidence == MergeEvidence::Local ? columnSoftmax (beliefs.local)
                                                                          : beliefs.marginals,
                        beliefs.labels, parameters.max_average_neff);
    result.converged = same_labels && static_cast<int> (kept.size ()) == cluster_count;
    keepClusters (kept, beliefs.marginals, beliefs.labels);
    result.labels.swap (beliefs.labels);
    result.marginals.swap (beliefs.marginals);  // the next fit weights, Eq. (3)
    cluster_count = static_cast<int> (kept.size ());
  }
  result.motions = solveFits (accumulateFits (pairs, result.marginals));  // Eq. (3), weighted by the marginals
  sortBySize (result);
  result.static_cluster = odometry ? selectStaticCluster (result.motions, *odometry) : 0;
  return result;
}

}  // namespace clustering
}  // namespace pcl_crf
