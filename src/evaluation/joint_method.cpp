#include <pcl_crf/evaluation/joint_methods.h>

#include <istream>
#include <ostream>
#include <stdexcept>

namespace pcl_crf {

namespace {

class JointMethod : public EvaluationMethod
{
public:
  JointMethod (const joint::JointParameters& parameters, const joint::JointLearningOptions& learning)
    : parameters_ (parameters), learning_ (learning)
  {}

  std::string
  name () const override { return "joint"; }

  bool
  isLearned () const override { return true; }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    model_ = joint::trainJointModel (training_pairs, learning_);
  }

  void
  writeModel (std::ostream& os) const override
  {
    requireModel ();
    joint::writeJointModel (model_, os);
  }

  void
  readModel (std::istream& is, const std::string& where) override
  {
    model_ = joint::readJointModel (is, where);
  }

  Prediction
  predict (const ScanPair& pair) override
  {
    requireModel ();
    joint::JointParameters parameters = parameters_;
    parameters.sensor = pair.sensor;  // the field of view of the free-space steps
    return joint::toPrediction (pair.source,
                                joint::estimateJoint (pair.source, pair.target, pair.odometry, model_, parameters));
  }

private:
  void
  requireModel () const
  {
    if (!model_.isTrained ())
      throw std::runtime_error ("joint: no model, train or load one first");
  }

  joint::JointParameters parameters_;
  joint::JointLearningOptions learning_;
  joint::JointModel model_;
};

}  // namespace

std::unique_ptr<EvaluationMethod>
makeJointMethod (const joint::JointParameters& parameters, const joint::JointLearningOptions& learning)
{
  joint::validateParameters (parameters);
  return std::make_unique<JointMethod> (parameters, learning);
}

}  // namespace pcl_crf
