#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Anything pcl_crf_eval can score: a baseline or an estimator, seen
 *  through the common ScanPair -> Prediction form.
 */
class EvaluationMethod
{
public:
  virtual ~EvaluationMethod () = default;

  /** \brief Name as given to pcl_crf_eval --method. */
  virtual std::string
  name () const = 0;

  /** \brief true when the method learns from labelled pairs (then train() or a
   *  loaded model must come before predict()). */
  virtual bool
  isLearned () const
  {
    return false;
  }

  /** \brief Learns the method's parameters from labelled pairs (no-op for
   *  methods that learn nothing). */
  virtual void
  train (const std::vector<ScanPair>& /*training_pairs*/)
  {}

  /** \brief Writes the learned parameters as versioned text (the body of a model
   *  file; composite methods embed their parts' text in theirs).
   *  \throws std::runtime_error when the method learns nothing or is not trained. */
  virtual void
  writeModel (std::ostream& /*os*/) const
  {
    throw std::runtime_error ("method '" + name () + "' has no learned model to save");
  }

  /** \brief Reads text written by writeModel, checking its version and every field.
   *  \param[in] is the text
   *  \param[in] where what the text is called in error messages (the file name)
   *  \throws std::runtime_error naming \a where and the problem. */
  virtual void
  readModel (std::istream& /*is*/, const std::string& /*where*/)
  {
    throw std::runtime_error ("method '" + name () + "' has no learned model to load");
  }

  /** \brief Writes the learned parameters as a versioned text model file (writeModel;
   *  nothing is written when that fails).
   *  \throws std::runtime_error when the method learns nothing or cannot write. */
  virtual void
  saveModel (const std::string& path) const;

  /** \brief Reads a model file written by saveModel (readModel).
   *  \throws std::runtime_error naming the file and the problem. */
  virtual void
  loadModel (const std::string& path);

  /** \brief The method's answer for one pair. Must not read the pair's ground
   *  truth except the odometry and sensor metadata. */
  virtual Prediction
  predict (const ScanPair& pair) = 0;
};

/** \brief Settings shared by the methods pcl_crf_eval can build. */
struct MethodSettings
{
  /** the number of clusters given to K-Means-like baselines (0 = method default). */
  int cluster_count = 0;
};

/** \brief Names of every method createEvaluationMethod() knows, in display order. */
std::vector<std::string>
availableEvaluationMethods ();

/** \brief Builds the named method. It sees only the returns of a pair, the points
 *  nearer than the sensor's maximum range, and predicts the others in its static
 *  world without a match (ignoringNoReturnPoints () in pcl_crf/evaluation/no_return_points.h).
 *  \throws std::invalid_argument for an unknown name, listing the known ones. */
std::unique_ptr<EvaluationMethod>
createEvaluationMethod (const std::string& name, const MethodSettings& settings = {});

}  // namespace pcl_crf
