#include <pcl_crf/clustering/prior_selection.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/metrics/v_measure.h>

#include <cmath>
#include <stdexcept>

namespace pcl_crf {
namespace clustering {

namespace {

/** Mean V-measure of CRF-Clustering with \a weights over \a pairs (source points vs objects). */
double
meanVMeasure (const std::vector<const ScanPair*>& pairs, const std::vector<const std::vector<int>*>& associations,
              const Eigen::VectorXd& weights, const CrfClusteringParameters& parameters)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < pairs.size (); ++k)
  {
    const ScanPair* pair = pairs[k];
    const ScanClustering result = clusterScan (pair->source, pair->target, *associations[k], weights, parameters,
                                               &pair->odometry, UnpairedLabelling::NearestSegmentNeighbour);
    sum += computeVMeasure (pair->source_object, result.source_cluster).v;
  }
  return pairs.empty () ? 0.0 : sum / static_cast<double> (pairs.size ());
}

Eigen::VectorXd
learn (const std::vector<crf::LabelledChain>& chains, double sigma, LearningOptions options)
{
  options.prior_sigma = sigma;
  return learnWeights (chains, options).x;
}

}  // namespace

PriorSelection
learnWithCrossValidation (const std::vector<ScanPair>& training, const CrfClusteringParameters& parameters,
                          const std::vector<double>& grid, int folds, const LearningOptions& options)
{
  std::vector<std::vector<int>> associations;
  for (const ScanPair& pair : training)
    associations.push_back (pair.source_match);
  return learnWithCrossValidation (training, associations, parameters, grid, folds, options);
}

PriorSelection
learnWithCrossValidation (const std::vector<ScanPair>& training, const std::vector<std::vector<int>>& associations,
                          const CrfClusteringParameters& parameters, const std::vector<double>& grid, int folds,
                          const LearningOptions& options)
{
  if (associations.size () != training.size ())
    throw std::invalid_argument ("[pcl_crf::clustering::learnWithCrossValidation] one association list per pair "
                                 "needed");
  if (grid.empty () || folds < 2)
    throw std::invalid_argument ("[pcl_crf::clustering::learnWithCrossValidation] needs candidates and folds >= 2");
  for (const double sigma : grid)
    if (!(sigma > 0.0))
      throw std::invalid_argument ("[pcl_crf::clustering::learnWithCrossValidation] every sigma must be > 0");
  std::vector<crf::LabelledChain> chains;
  for (std::size_t k = 0; k < training.size (); ++k)
    chains.push_back (trainingChain (training[k], associations[k], parameters.features));

  PriorSelection selection;
  selection.grid = grid;
  selection.prior_sigma = grid[grid.size () / 2];
  if (training.size () >= static_cast<std::size_t> (folds))
  {
    selection.scores.assign (grid.size (), 0.0);
    for (int f = 0; f < folds; ++f)
    {
      std::vector<crf::LabelledChain> fit;
      std::vector<const ScanPair*> held_out;
      std::vector<const std::vector<int>*> held_out_associations;
      for (std::size_t k = 0; k < training.size (); ++k)
        if (static_cast<int> (k % folds) == f)
        {
          held_out.push_back (&training[k]);
          held_out_associations.push_back (&associations[k]);
        }
        else
          fit.push_back (chains[k]);
      for (std::size_t g = 0; g < grid.size (); ++g)
        selection.scores[g] +=
            meanVMeasure (held_out, held_out_associations, learn (fit, grid[g], options), parameters) / folds;
    }
    double best = -1.0;
    for (std::size_t g = 0; g < grid.size (); ++g)
    {
      const bool tie = std::abs (selection.scores[g] - best) <= 1e-12;
      if (selection.scores[g] > best + 1e-12 || (tie && grid[g] < selection.prior_sigma))
      {
        best = selection.scores[g];
        selection.prior_sigma = grid[g];
      }
    }
  }
  selection.weights = learn (chains, selection.prior_sigma, options);
  return selection;
}

}  // namespace clustering
}  // namespace pcl_crf
