#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/raw_features.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

Eigen::VectorXd
boostedMargins (const crf::AdaBoostStumps& classifier, const Eigen::MatrixXd& features)
{
  if (classifier.getDimension () > features.rows ())
    throw std::invalid_argument ("[pcl_crf::matching::boostedMargins] the classifier reads " +
                                 std::to_string (classifier.getDimension ()) + " features, got " +
                                 std::to_string (features.rows ()));
  Eigen::VectorXd margins = Eigen::VectorXd::Zero (features.cols ());
  for (const crf::AdaBoostStumps::Stump& stump : classifier.getStumps ()) {
    const double vote = stump.alpha * stump.polarity;
    if (stump.feature < 0)
      margins.array () += vote;
    else  // h(x) = polarity if x[feature] > threshold else −polarity
      for (Eigen::Index c = 0; c < features.cols (); ++c)
        margins (c) += features (stump.feature, c) > stump.threshold ? vote : -vote;
  }
  return margins;
}

BoostedScores
scorePass (const StageModel& stage, const ScanShape& source, const ScanShape& target, const PassGeometry& pass)
{
  const Eigen::MatrixXd data = dataFeatures (source, target, pass);
  BoostedScores scores;
  scores.data_margins = boostedMargins (stage.data_boosting, data);
  scores.outlier_margins =
      boostedMargins (stage.outlier_boosting, outlierFeatures (source, pass, data, scores.data_margins));
  return scores;
}

}  // namespace matching
}  // namespace pcl_crf
