#include <pcl_crf/clustering/cluster_fits.h>
#include <pcl_crf/clustering/cluster_merging.h>
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/clustering/ego_cluster.h>
#include <pcl_crf/clustering/scan_segmentation.h>
#include <pcl_crf/crf/chain_inference.h>

#include <algorithm>
#include <cmath>
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

/** The clusters each node keeps: its \a max_states best by local log-potential (the
 *  first of equal ones), of those the ones within \a margin of the best; increasing
 *  cluster order. \a states keeps the capacity of its lists from round to round. */
void
candidateStates (const Eigen::MatrixXd& local, double margin, int max_states, CandidateStates& states)
{
  states.resize (static_cast<std::size_t> (local.cols ()));
  const int clusters = static_cast<int> (local.rows ());
  const int keep = std::min (clusters, max_states);
  std::vector<int> best (static_cast<std::size_t> (keep) + 1);  // sorted by decreasing potential
  for (Eigen::Index i = 0; i < local.cols (); ++i)
  {
    const double* column = local.data () + i * local.rows ();
    int count = 0;
    for (int l = 0; l < clusters; ++l)
    {
      const double value = column[l];
      if (count == keep && value <= column[best[count - 1]])
        continue;
      int at = count;  // after the ones it does not beat
      while (at > 0 && value > column[best[at - 1]])
        --at;
      for (int k = std::min (count, keep - 1); k > at; --k)
        best[k] = best[k - 1];
      best[at] = l;
      count = std::min (count + 1, keep);
    }
    const double floor = column[best[0]] - margin;
    while (column[best[count - 1]] < floor)
      --count;
    std::vector<int>& kept = states[i];
    kept.assign (best.begin (), best.begin () + count);
    std::sort (kept.begin (), kept.end ());
  }
}

/** Column-wise softmax of log-potentials, in place (glibc's exp: faster here than Eigen's). */
void
columnSoftmax (Eigen::MatrixXd& log_p)
{
  for (Eigen::Index i = 0; i < log_p.cols (); ++i)
  {
    double* column = log_p.data () + i * log_p.rows ();
    const double maximum = *std::max_element (column, column + log_p.rows ());
    double sum = 0.0;
    for (Eigen::Index l = 0; l < log_p.rows (); ++l)
    {
      column[l] = std::exp (column[l] - maximum);
      sum += column[l];
    }
    for (Eigen::Index l = 0; l < log_p.rows (); ++l)
      column[l] /= sum;
  }
}

/** The most pairs of an initial cluster: max_segment_points, raised so that the scan
 *  makes at most max_initial_clusters of them (about: breaks at distance make more). */
int
segmentCap (const PointPairs& pairs, const CrfClusteringParameters& parameters)
{
  const auto n = static_cast<long> (pairs.size ());
  const long spread = (n + parameters.max_initial_clusters - 1) / parameters.max_initial_clusters;
  return parameters.max_segment_points > 0 ? static_cast<int> (std::max<long> (parameters.max_segment_points, spread))
                                           : parameters.max_segment_points;
}

/** What the rounds of clusterPointPairs () reuse (kept per thread between calls). */
struct Workspace
{
  Eigen::MatrixXd scales;            // unaryScales ()
  Eigen::MatrixXd local;             // S x n local log-potentials, then the merge test's probabilities
  CandidateStates states;            // pruned clusters of every node
  crf::PackedChainPotentials chain;  // their potentials
  crf::ChainInference inference;     // sum-product and max-product
};

/** One round (Sec. IV-D) for the \a motions: local log-potentials (Eq. (2)), pruned
 *  candidate states, sum-product and max-product. Leaves the local log-potentials,
 *  the states and the inference results in \a workspace; returns the MAP cluster of
 *  every pair. */
std::vector<int>
propagate (const PointPairs& pairs, const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters,
           const std::vector<Rigid2d>& motions, Workspace& workspace)
{
  localLogPotentials (pairs, motions, workspace.scales, weights, workspace.local);  // Eq. (2)
  candidateStates (workspace.local, parameters.pruning_margin, parameters.max_states, workspace.states);
  chainPotentials (pairs, motions, workspace.states, workspace.local, weights, parameters.features, workspace.chain);
  workspace.inference.compute (workspace.chain, crf::kMapAndMarginals);
  std::vector<int> labels (pairs.size ());
  for (std::size_t i = 0; i < pairs.size (); ++i)
    labels[i] = workspace.states[i][workspace.inference.mapLabels ()[i]];
  return labels;
}

/** The sum-product marginals of the clusters in \a kept (rows in that order), |kept| x n,
 *  0 where a cluster is not a state of the node. */
Eigen::MatrixXd
keptMarginals (const Workspace& workspace, const std::vector<int>& kept, int cluster_count)
{
  std::vector<int> row (static_cast<std::size_t> (cluster_count), -1);
  for (std::size_t k = 0; k < kept.size (); ++k)
    row[kept[k]] = static_cast<int> (k);
  Eigen::MatrixXd marginals = Eigen::MatrixXd::Zero (static_cast<Eigen::Index> (kept.size ()),
                                                     static_cast<Eigen::Index> (workspace.states.size ()));
  for (std::size_t i = 0; i < workspace.states.size (); ++i)
  {
    const Eigen::Map<const Eigen::VectorXd> p = workspace.inference.nodeMarginal (i);
    for (std::size_t a = 0; a < workspace.states[i].size (); ++a)
      if (row[workspace.states[i][a]] >= 0)
        marginals (row[workspace.states[i][a]], static_cast<Eigen::Index> (i)) = p (a);
  }
  return marginals;
}

/** The weights of the refit after a round (Eq. (3), MotionFit): the marginals of
 *  every pair (no copy), or only of each cluster's own (MAP) pairs, written to \a own. */
const Eigen::MatrixXd&
fitWeights (const CrfClusteringResult& round, const CrfClusteringParameters& parameters, Eigen::MatrixXd& own)
{
  if (parameters.motion_fit == MotionFit::Marginals)
    return round.marginals;
  own = ownPointWeights (round.marginals, round.labels);
  return own;
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
  if (p.max_initial_clusters < 1)
    fail ("max_initial_clusters must be >= 1");
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
  if (p.features.weighted_neighbour_max_gap < -1)
    fail ("features.weighted_neighbour_max_gap must be >= 0 beams, or -1 for no bound");
  if (p.merge_evidence != MergeEvidence::Local && p.merge_evidence != MergeEvidence::Marginals)
    fail ("merge_evidence must be MergeEvidence::Local or MergeEvidence::Marginals, got " +
          std::to_string (static_cast<int> (p.merge_evidence)));
  if (!isMotionFit (p.motion_fit))
    fail ("motion_fit must be MotionFit::Marginals or MotionFit::OwnPoints, got " +
          std::to_string (static_cast<int> (p.motion_fit)));
}

bool
isMotionFit (MotionFit fit)
{
  return fit == MotionFit::Marginals || fit == MotionFit::OwnPoints;
}

CrfClusteringResult
clusterPointPairs (const PointPairs& pairs, const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters,
                   const Odometry* odometry)
{
  validateParameters (parameters);
  if (weights.size () != kWeightCount || !weights.allFinite ())
    fail ("expected " + std::to_string (kWeightCount) + " finite weights, got " + std::to_string (weights.size ()) +
          (weights.allFinite () ? "" : " holding NaN or infinite values"));
  const std::string problem = pointPairsProblem (pairs);
  if (!problem.empty ())
    fail (problem);
  CrfClusteringResult result;
  if (pairs.size () == 0)
    return result;

  // Sec. IV-D: over-segment the scan, one cluster per segment.
  result.labels = segmentByDistance (pairs.source, parameters.segment_break_distance, segmentCap (pairs, parameters));
  mergeNarrowestBreaks (pairs.source, parameters.max_initial_clusters, result.labels);  // every round costs S x n
  int cluster_count = result.labels.back () + 1;
  result.initial_clusters = cluster_count;

  // Sec. IV-D, IV-E: BP, removal of empty and ambiguous clusters (Eq. (8)), refit,
  // until the MAP labelling and the clusters stop changing.
  // The buffers are kept per thread from call to call: after the first call, a call
  // allocates only its result and a few small per-round matrices, so that the heap
  // does not grow and shrink (with page faults) on every call.
  static thread_local Workspace workspace;
  workspace.scales = unaryScales (pairs, parameters.features);
  std::vector<int> every;  // 0 … S − 1
  Eigen::MatrixXd own_weights;  // MotionFit::OwnPoints' refit weights
  while (result.iterations < parameters.max_iterations && !result.converged)
  {
    // Eq. (3): first the segments (hard), then the marginals of the previous round (MotionFit).
    const std::vector<Rigid2d> motions = result.iterations == 0
                                             ? fitMotions (pairs, result.labels, cluster_count)
                                             : solveFits (accumulateFits (pairs, fitWeights (result, parameters, own_weights)));
    ++result.iterations;
    std::vector<int> labels = propagate (pairs, weights, parameters, motions, workspace);
    const bool same_labels = labels == result.labels;
    std::vector<int> kept;
    if (parameters.merge_evidence == MergeEvidence::Local)
    {
      columnSoftmax (workspace.local);
      kept = selectClusters (workspace.local, labels, parameters.max_average_neff);
    }
    else
    {
      every.resize (motions.size ());
      std::iota (every.begin (), every.end (), 0);
      kept = selectClusters (keptMarginals (workspace, every, cluster_count), labels, parameters.max_average_neff);
    }
    result.converged = same_labels && static_cast<int> (kept.size ()) == cluster_count;
    // The kept clusters' marginals, renumbered and renormalised: the next fit's weights (Eq. (3)).
    result.marginals = keptMarginals (workspace, kept, cluster_count);
    std::vector<int> renumbered (static_cast<std::size_t> (cluster_count), -1);
    for (std::size_t k = 0; k < kept.size (); ++k)
      renumbered[kept[k]] = static_cast<int> (k);
    for (int& l : labels)
      l = renumbered[l];
    every.resize (kept.size ());
    std::iota (every.begin (), every.end (), 0);
    keepClusters (every, result.marginals, labels);
    result.labels.swap (labels);
    cluster_count = static_cast<int> (kept.size ());
  }
  // Eq. (3), weighted by the marginals whatever MotionFit the rounds refitted with.
  result.motions = solveFits (accumulateFits (pairs, result.marginals));
  sortBySize (result);
  result.static_cluster = odometry ? selectStaticCluster (result.motions, *odometry, result.sizes) : 0;
  return result;
}

}  // namespace clustering
}  // namespace pcl_crf
