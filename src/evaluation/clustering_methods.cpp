#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/clustering/clustering_learning.h>
#include <pcl_crf/clustering/clustering_model.h>
#include <pcl_crf/clustering/ego_cluster.h>
#include <pcl_crf/clustering/motion_kmeans.h>
#include <pcl_crf/clustering/prior_selection.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/clustering/scan_pair_clustering.h>
#include <pcl_crf/evaluation/clustering_methods.h>

#include <algorithm>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <utility>

namespace pcl_crf {

namespace {

using clustering::UnpairedLabelling;

/** The pair's true associations (the "-t" methods cluster the truth). */
std::vector<int>
trueAssociations (const ScanPair& pair)
{
  return pair.source_match;
}

/** CRF-Clustering on the associations of a provider. */
class CrfClusteringMethod : public EvaluationMethod
{
public:
  CrfClusteringMethod (std::string name, AssociationProvider associations, bool report,
                       const clustering::CrfClusteringParameters& parameters)
    : name_ (std::move (name)), associations_ (std::move (associations)), report_ (report), parameters_ (parameters)
  {}

  std::string
  name () const override { return name_; }

  bool
  isLearned () const override { return true; }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    std::vector<std::vector<int>> associations;
    for (const ScanPair& pair : training_pairs)
      associations.push_back (associations_ (pair));  // learn from the associations it will see
    const clustering::PriorSelection selection =
        clustering::learnWithCrossValidation (training_pairs, associations, parameters_);
    model_.weights = selection.weights;
    model_.prior_sigma = selection.prior_sigma;
    model_.features = parameters_.features;
    trained_ = true;
  }

  void
  writeModel (std::ostream& os) const override
  {
    if (!trained_)
      throw std::runtime_error (name_ + ": no model to save, train first");
    clustering::writeModel (os, model_);
  }

  void
  readModel (std::istream& is, const std::string& where) override
  {
    model_ = clustering::readModel (is, where);
    parameters_.features = model_.features;
    trained_ = true;
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    if (!trained_)
      throw std::runtime_error (name_ + ": no model, train or load one first");
    const std::vector<int> matches = associations_ (pair);
    Prediction prediction = clustering::toPrediction (
        clustering::clusterScan (pair.source, pair.target, matches, model_.weights, parameters_, &pair.odometry,
                                 UnpairedLabelling::NearestSegmentNeighbour),
        pair.odometry.T_source_target);
    if (report_)
      prediction.source_match = matches;
    return prediction;
  }

private:
  std::string name_;
  AssociationProvider associations_;
  bool report_ = false;
  clustering::CrfClusteringParameters parameters_;
  clustering::CrfClusteringModel model_;
  bool trained_ = false;
};

/** The modified K-Means on the associations of a provider. */
class KMeansMethod : public EvaluationMethod
{
public:
  KMeansMethod (std::string name, AssociationProvider associations, bool report, int cluster_count)
    : name_ (std::move (name)), associations_ (std::move (associations)), report_ (report),
      learned_ (cluster_count <= 0)
  {
    parameters_.cluster_count = cluster_count;
  }

  std::string
  name () const override { return name_; }

  bool
  isLearned () const override { return learned_; }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    if (!learned_)
      return;
    int most = 0;
    for (const ScanPair& pair : training_pairs)
      most = std::max (most, clustering::associatedObjectCount (pair));
    if (most < 1)
      throw std::runtime_error (name_ + ": the training pairs have no associated point");
    parameters_.cluster_count = most;
  }

  void
  writeModel (std::ostream& os) const override
  {
    if (parameters_.cluster_count < 1)
      throw std::runtime_error (name_ + ": no cluster count to save, train first");
    os << kKMeansMagic << " 1\ncluster_count " << parameters_.cluster_count << '\n';
  }

  void
  readModel (std::istream& is, const std::string& where) override
  {
    std::string magic, key, extra;
    int version = 0, count = 0;
    if (!(is >> magic >> version) || magic != kKMeansMagic || version != 1)
      throw std::runtime_error (name_ + ": '" + where + "' is not a version 1 K-Means model");
    if (!(is >> key >> count) || key != "cluster_count" || count < 1)
      throw std::runtime_error (name_ + ": '" + where + "' needs a line 'cluster_count K' with K >= 1");
    if (is >> extra)
      throw std::runtime_error (name_ + ": '" + where + "' has unexpected text '" + extra + "' after cluster_count");
    parameters_.cluster_count = count;
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    if (parameters_.cluster_count < 1)
      throw std::runtime_error (name_ + ": no cluster count, train or load a model first");
    const std::vector<int> matches = associations_ (pair);
    const clustering::PointPairs pairs = clustering::makePointPairs (pair.source, pair.target, matches);
    const clustering::MotionKMeansResult result = clustering::clusterKMeans (pairs, parameters_);
    const int world = clustering::selectStaticCluster (result.motions, pair.odometry, result.sizes);
    Prediction prediction = clustering::makePrediction (pair, pairs, result.labels, result.motions, world,
                                                        UnpairedLabelling::NearestSegmentNeighbour, kBreakDistance);
    if (report_)
      prediction.source_match = matches;
    return prediction;
  }

private:
  static constexpr const char* kKMeansMagic = "pcl_crf_kmeans_model";
  /** segment gap for labelling points without an association, as CRF-Clustering's default [m]. */
  static constexpr double kBreakDistance = 0.5;
  std::string name_;
  AssociationProvider associations_;
  bool report_ = false;
  bool learned_ = false;
  clustering::MotionKMeansParameters parameters_;
};

/** Consistency-based detection with the ego motion from odometry or ICP. */
class ConsistencyMethod : public EvaluationMethod
{
public:
  ConsistencyMethod (EgoMotionSource ego, const clustering::ConsistencyParameters& parameters)
    : ego_ (ego), parameters_ (parameters)
  {}

  std::string
  name () const override { return "cbd"; }

  Prediction
  predict (const ScanPair& pair) override
  {
    const Rigid2d T_source_target =
        ego_ == EgoMotionSource::Icp ? runIcpBaseline (pair).T_source_target : pair.odometry.T_source_target;
    const Rigid2d T_target_source = T_source_target.inverse ();
    Prediction prediction;
    const Eigen::Matrix3d* covariance = ego_ == EgoMotionSource::Odometry ? &pair.odometry.covariance : nullptr;
    prediction.source_cluster = clustering::detectDynamicSegments (pair.source, pair.target, pair.sensor,
                                                                   T_target_source, parameters_, covariance);
    const int clusters = 1 + *std::max_element (prediction.source_cluster.begin (), prediction.source_cluster.end ());
    prediction.cluster_motions.assign (static_cast<std::size_t> (clusters), Rigid2d::Identity ());
    prediction.cluster_motions[0] = T_target_source;
    prediction.static_cluster = 0;
    prediction.T_source_target = T_source_target;
    return prediction;
  }

private:
  EgoMotionSource ego_;
  clustering::ConsistencyParameters parameters_;
};

}  // namespace

std::unique_ptr<EvaluationMethod>
makeCrfClusteringMethod (const std::string& name, AssociationProvider associations, bool report_associations,
                         const clustering::CrfClusteringParameters& parameters)
{
  if (!associations)
    throw std::invalid_argument ("makeCrfClusteringMethod: the association provider is empty");
  clustering::validateParameters (parameters);
  return std::make_unique<CrfClusteringMethod> (name, std::move (associations), report_associations, parameters);
}

std::unique_ptr<EvaluationMethod>
makeCrfClusteringTrueAssociationsMethod (const clustering::CrfClusteringParameters& parameters)
{
  return makeCrfClusteringMethod ("crf-t", trueAssociations, false, parameters);
}

std::unique_ptr<EvaluationMethod>
makeKMeansMethod (int cluster_count)
{
  return makeKMeansMethod ("kmeans", trueAssociations, false, cluster_count);
}

std::unique_ptr<EvaluationMethod>
makeKMeansMethod (const std::string& name, AssociationProvider associations, bool report_associations,
                  int cluster_count)
{
  if (!associations)
    throw std::invalid_argument ("makeKMeansMethod: the association provider is empty");
  return std::make_unique<KMeansMethod> (name, std::move (associations), report_associations, cluster_count);
}

std::unique_ptr<EvaluationMethod>
makeConsistencyMethod (EgoMotionSource ego, const clustering::ConsistencyParameters& parameters)
{
  return std::make_unique<ConsistencyMethod> (ego, parameters);
}

}  // namespace pcl_crf
