#include <pcl_crf/evaluation/matching_methods.h>
#include <pcl_crf/matching/matching_learner.h>
#include <pcl_crf/matching/robust_rigid_fit.h>
#include <pcl_crf/matching/scan_matching.h>

#include <stdexcept>

namespace pcl_crf {

namespace {

/** Prediction of CRF-Matching: its association and one static cluster. */
Prediction
toPrediction (const matching::MatchResult& result)
{
  Prediction prediction;
  prediction.source_match = result.matches;
  prediction.source_cluster.resize (result.matches.size ());
  for (std::size_t i = 0; i < result.matches.size (); ++i)
    prediction.source_cluster[i] = result.matches[i] == kNoMatch ? kOutlierCluster : 0;
  prediction.cluster_motions = {result.T_target_source};
  prediction.static_cluster = 0;
  prediction.T_source_target = result.T_target_source.inverse ();
  return prediction;
}

class CrfMatchingMethod : public EvaluationMethod
{
public:
  explicit CrfMatchingMethod (const matching::MatchingParameters& parameters) { model_.parameters = parameters; }

  std::string
  name () const override
  {
    return "crf-matching";
  }

  bool
  isLearned () const override
  {
    return true;
  }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    model_ = matching::trainCrfMatching (training_pairs, model_.parameters);
  }

  void
  saveModel (const std::string& path) const override
  {
    if (!model_.isTrained ())
      throw std::runtime_error ("crf-matching: no model to save, train first");
    matching::saveModel (model_, path);
  }

  void
  loadModel (const std::string& path) override
  {
    model_ = matching::loadModel (path);
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    if (!model_.isTrained ())
      throw std::runtime_error ("crf-matching: no model, train or load one first");
    return toPrediction (
        matching::matchScans (pair.source, pair.target, matching::MotionGuess::fromOdometry (pair.odometry), model_));
  }

private:
  matching::CrfMatchingModel model_;
};

}  // namespace

std::unique_ptr<EvaluationMethod>
makeCrfMatchingMethod (const matching::MatchingParameters& parameters)
{
  matching::validateParameters (parameters);
  return std::make_unique<CrfMatchingMethod> (parameters);
}

}  // namespace pcl_crf
