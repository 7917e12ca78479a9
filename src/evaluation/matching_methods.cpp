#include <pcl_crf/baselines/icp_baseline.h>
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

/** PCL ICP from the odometry guess (pcl_crf/baselines/icp_baseline.h). */
class IcpMethod : public EvaluationMethod
{
public:
  std::string
  name () const override
  {
    return "icp";
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    return runIcpBaseline (pair);
  }
};

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
  writeModel (std::ostream& os) const override
  {
    if (!model_.isTrained ())
      throw std::runtime_error ("crf-matching: no model to save, train first");
    matching::writeModel (model_, os);
  }

  void
  readModel (std::istream& is, const std::string& where) override
  {
    model_ = matching::readModel (is, where);
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
makeIcpMethod ()
{
  return std::make_unique<IcpMethod> ();
}

std::unique_ptr<EvaluationMethod>
makeCrfMatchingMethod (const matching::MatchingParameters& parameters)
{
  matching::validateParameters (parameters);
  return std::make_unique<CrfMatchingMethod> (parameters);
}

}  // namespace pcl_crf
