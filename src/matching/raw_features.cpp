#include <pcl_crf/matching/raw_features.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_crf {
namespace matching {

namespace {

/** |a − b| for angles in (−π, π], wrapped to [0, π]. */
double
angleError (double a, double b)
{
  const double d = std::abs (a - b);
  return d > M_PI ? 2.0 * M_PI - d : d;
}

bool
isAngleRow (int row)
{
  return row >= kAngle1 && row <= kAngle5;
}

}  // namespace

Eigen::MatrixXd
dataFeatures (const ScanShape& source, const ScanShape& target, const PassGeometry& pass)
{
  const Candidates& candidates = pass.candidates;
  Eigen::MatrixXd features (kDataFeatureCount, static_cast<Eigen::Index> (candidates.targets.size ()));
  const double infinity = std::numeric_limits<double>::infinity ();
  for (int i = 0; i < candidates.size (); ++i) {
    double nearest = infinity, nearest_motion = infinity;
    const SegmentMotions& motions = pass.segment_motions;
    const bool has_motion = motions.has_hypothesis[i];
    const Eigen::Vector2d moved = pass.source_current.col (i) + motions.translation.col (i);
    for (int c = candidates.offsets[i]; c < candidates.offsets[i + 1]; ++c) {
      const int j = candidates.targets[c];
      auto f = features.col (c);
      // Shape errors between the patterns around i and j (Ramos et al., RSS 2007, Sec. IV-A).
      for (int row = 0; row < kShapeFeatureCount; ++row)
        f (row) = isAngleRow (row) ? angleError (source.shape (row, i), target.shape (row, j))
                                   : std::abs (source.shape (row, i) - target.shape (row, j));
      f (kTranslation) = (pass.source_guess.col (i) - target.points.col (j)).norm ();
      f (kRegisteredTranslation) = (pass.source_current.col (i) - target.points.col (j)).norm ();
      f (kMotionResidual) = has_motion ? std::min (f (kRegisteredTranslation), (moved - target.points.col (j)).norm ())
                                       : f (kRegisteredTranslation);
      f (kSegmentDisplacement) = motions.translation.col (i).norm ();
      f (kSegmentCurrentSupport) = motions.current_support (i);
      f (kSegmentHypothesisSupport) = motions.hypothesis_support (i);
      nearest = std::min (nearest, f (kRegisteredTranslation));
      nearest_motion = std::min (nearest_motion, f (kMotionResidual));
    }
    for (int c = candidates.offsets[i]; c < candidates.offsets[i + 1]; ++c) {
      features (kRegisteredExcess, c) = features (kRegisteredTranslation, c) - nearest;
      features (kMotionExcess, c) = features (kMotionResidual, c) - nearest_motion;
    }
  }
  return features;
}

Eigen::MatrixXd
outlierFeatures (const ScanShape& source, const PassGeometry& pass, const Eigen::MatrixXd& data_features,
                 const Eigen::VectorXd& data_margins)
{
  const Candidates& candidates = pass.candidates;
  const double infinity = std::numeric_limits<double>::infinity ();
  Eigen::MatrixXd features (kOutlierFeatureCount, candidates.size ());
  for (int i = 0; i < candidates.size (); ++i) {
    double nearest_guess = infinity, nearest_registered = infinity, nearest_motion = infinity, best_margin = -infinity;
    for (int c = candidates.offsets[i]; c < candidates.offsets[i + 1]; ++c) {
      nearest_guess = std::min (nearest_guess, data_features (kTranslation, c));
      nearest_registered = std::min (nearest_registered, data_features (kRegisteredTranslation, c));
      nearest_motion = std::min (nearest_motion, data_features (kMotionResidual, c));
      best_margin = std::max (best_margin, data_margins (c));
    }
    // A point without candidates (empty target) is as far and as poor as it gets.
    const double far = source.shape (kRadius, i) + 1.0;
    auto f = features.col (i);
    f (kNearestGuessDistance) = std::isfinite (nearest_guess) ? nearest_guess : far;
    f (kNearestRegisteredDistance) = std::isfinite (nearest_registered) ? nearest_registered : far;
    f (kSourceRadius) = source.shape (kRadius, i);
    f (kSourceDistanceBefore1) = source.shape (kDistanceBefore1, i);
    f (kSourceDistanceAfter1) = source.shape (kDistanceAfter1, i);
    f (kSourceAbsoluteAngle3) = std::abs (source.shape (kAngle3, i));
    f (kBestDataMargin) = std::isfinite (best_margin) ? best_margin : -1e3;
    f (kNearestMotionResidual) = std::isfinite (nearest_motion) ? nearest_motion : far;
    f (kOutlierSegmentDisplacement) = pass.segment_motions.translation.col (i).norm ();
    f (kOutlierCurrentSupport) = pass.segment_motions.current_support (i);
    f (kOutlierHypothesisSupport) = pass.segment_motions.hypothesis_support (i);
  }
  return features;
}

}  // namespace matching
}  // namespace pcl_crf
