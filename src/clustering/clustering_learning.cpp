#include <pcl_crf/clustering/cluster_fits.h>
#include <pcl_crf/clustering/clustering_learning.h>
#include <pcl_crf/crf/pseudo_likelihood.h>

#include <map>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

/** Labels renumbered 0, 1, ... in order of first appearance; \a count receives how many. */
std::vector<int>
compactLabels (const std::vector<int>& labels, int& count)
{
  std::map<int, int> index;
  std::vector<int> compact;
  compact.reserve (labels.size ());
  for (const int label : labels)
  {
    const auto inserted = index.emplace (label, static_cast<int> (index.size ()));
    compact.push_back (inserted.first->second);
  }
  count = static_cast<int> (index.size ());
  return compact;
}

}  // namespace

crf::LabelledChain
makeTrainingChain (const PointPairs& pairs, const std::vector<int>& labels, const FeatureOptions& options)
{
  if (labels.size () != pairs.size ())
    throw std::invalid_argument ("[pcl_crf::clustering::makeTrainingChain] " + std::to_string (labels.size ()) +
                                 " labels for " + std::to_string (pairs.size ()) + " pairs");
  const std::string problem = pointPairsProblem (pairs);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::clustering::makeTrainingChain] " + problem);
  int cluster_count = 0;
  crf::LabelledChain chain;
  chain.labels = compactLabels (labels, cluster_count);
  const Eigen::MatrixXd fit_weights = oneHot (chain.labels, cluster_count);
  const std::vector<Rigid2d> motions = solveFits (accumulateFits (pairs, fit_weights));  // true motions, Eq. (3)
  const Eigen::MatrixXd residuals = squaredResiduals (pairs, motions);                    // Eq. (2)
  chain.features = chainFeatures (pairs, motions, allStates (pairs.size (), cluster_count), options, &residuals);
  return chain;
}

crf::LbfgsResult
learnWeights (const std::vector<crf::LabelledChain>& chains, const LearningOptions& options)
{
  bool any_node = false;
  for (const crf::LabelledChain& chain : chains)
    any_node = any_node || chain.features.size () > 0;
  if (!any_node)
    throw std::invalid_argument ("[pcl_crf::clustering::learnWeights] no training chain has a node");
  if (!crf::hasAnEdge (chains))
    throw std::invalid_argument ("[pcl_crf::clustering::learnWeights] no training chain has an edge: the pairwise "
                                 "weights need pairs with two or more associated points");
  for (const crf::LabelledChain& chain : chains)
    if ((chain.features.size () > 0 && chain.features.unaryDimension () != kUnaryFeatureCount) ||
        (!chain.features.pairwise.empty () && chain.features.pairwiseDimension () != kPairwiseFeatureCount))
      throw std::invalid_argument ("[pcl_crf::clustering::learnWeights] a chain does not hold the " +
                                   std::to_string (kWeightCount) + " CRF-Clustering features");
  const crf::PseudoLikelihood learner (chains, options.prior_sigma);
  return learner.train (options.lbfgs);
}

}  // namespace clustering
}  // namespace pcl_crf
