#include <pcl_crf/evaluation/composite_model.h>
#include <pcl_crf/evaluation/matching_methods.h>
#include <pcl_crf/evaluation/pipeline_methods.h>

#include <stdexcept>
#include <utility>

namespace pcl_crf {
namespace {

/** An association method, then a clustering fed with its associations. */
class AssociationPipeline : public EvaluationMethod
{
public:
  AssociationPipeline (std::string name, std::shared_ptr<EvaluationMethod> associations,
                       std::unique_ptr<EvaluationMethod> clustering)
    : name_ (std::move (name)), associations_ (std::move (associations)), clustering_ (std::move (clustering))
  {}

  std::string
  name () const override { return name_; }

  bool
  isLearned () const override { return associations_->isLearned () || clustering_->isLearned (); }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    if (associations_->isLearned ())
      associations_->train (training_pairs);
    if (clustering_->isLearned ())
      clustering_->train (training_pairs);  // on the associations just learned
  }

  void
  writeModel (std::ostream& os) const override
  {
    std::vector<const EvaluationMethod*> parts;
    for (EvaluationMethod* part : learnedParts ())
      parts.push_back (part);
    writeCompositeModel (os, name_, parts);
  }

  void
  readModel (std::istream& is, const std::string& where) override
  {
    readCompositeModel (is, where, name_, learnedParts ());
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    return clustering_->predict (pair);
  }

private:
  std::vector<EvaluationMethod*>
  learnedParts () const
  {
    std::vector<EvaluationMethod*> parts;
    for (EvaluationMethod* part : {associations_.get (), clustering_.get ()})
      if (part->isLearned ())
        parts.push_back (part);
    return parts;
  }

  std::string name_;
  std::shared_ptr<EvaluationMethod> associations_;  // shared with the clustering's provider
  std::unique_ptr<EvaluationMethod> clustering_;
};

ClusteringFactory
kMeansOn (int cluster_count)
{
  return [cluster_count] (AssociationProvider associations) {
    return makeKMeansMethod ("kmeans", std::move (associations), true, cluster_count);
  };
}

}  // namespace

std::unique_ptr<EvaluationMethod>
makeAssociationPipeline (const std::string& name, std::unique_ptr<EvaluationMethod> associations,
                         const ClusteringFactory& clustering)
{
  if (!associations || !clustering)
    throw std::invalid_argument ("makeAssociationPipeline: '" + name +
                                 "' needs an association method and a clustering factory");
  std::shared_ptr<EvaluationMethod> matcher = std::move (associations);
  std::unique_ptr<EvaluationMethod> clusterer =
      clustering ([matcher] (const ScanPair& pair) { return matcher->predict (pair).source_match; });
  if (!clusterer)
    throw std::invalid_argument ("makeAssociationPipeline: '" + name + "': the clustering factory gave nothing");
  return std::make_unique<AssociationPipeline> (name, std::move (matcher), std::move (clusterer));
}

std::unique_ptr<EvaluationMethod>
makeIcpKMeansMethod (int cluster_count)
{
  return makeAssociationPipeline ("icp+kmeans", makeIcpMethod (), kMeansOn (cluster_count));
}

std::unique_ptr<EvaluationMethod>
makeCrfMatchingKMeansMethod (int cluster_count)
{
  return makeAssociationPipeline ("crf-matching+kmeans", makeCrfMatchingMethod (), kMeansOn (cluster_count));
}

std::unique_ptr<EvaluationMethod>
makeCrfMMethod ()
{
  return makeAssociationPipeline ("crf-m", makeCrfMatchingMethod (), [] (AssociationProvider associations) {
    return makeCrfClusteringMethod ("crf-clustering", std::move (associations), true);
  });
}

}  // namespace pcl_crf
