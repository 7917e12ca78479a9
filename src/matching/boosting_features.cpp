#include <pcl_crf/matching/boosting_features.h>
#include <pcl_crf/matching/raw_features.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

/** Columns scored together, stump after stump: their features (a few KB) stay in the
 *  L1 cache for all the stumps instead of being read again from memory per stump. */
constexpr Eigen::Index kColumnBlock = 64;

}  // namespace

Eigen::VectorXd
boostedMargins (const crf::AdaBoostStumps& classifier, const Eigen::MatrixXd& features)
{
  if (classifier.getDimension () > features.rows ())
    throw std::invalid_argument ("[pcl_crf::matching::boostedMargins] the classifier reads " +
                                 std::to_string (classifier.getDimension ()) + " features, got " +
                                 std::to_string (features.rows ()));
  Eigen::VectorXd margins = Eigen::VectorXd::Zero (features.cols ());
  for (Eigen::Index begin = 0; begin < features.cols (); begin += kColumnBlock) {
    const Eigen::Index end = std::min (begin + kColumnBlock, features.cols ());
    for (const crf::AdaBoostStumps::Stump& stump : classifier.getStumps ()) {  // each margin sums them in order
      const double vote = stump.alpha * stump.polarity;
      if (stump.feature < 0)
        margins.segment (begin, end - begin).array () += vote;
      else  // h(x) = polarity if x[feature] > threshold else −polarity
        for (Eigen::Index c = begin; c < end; ++c)
          margins (c) += features (stump.feature, c) > stump.threshold ? vote : -vote;
    }
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
