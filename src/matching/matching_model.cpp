#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/raw_features.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

void
require (bool condition, const std::string& what)
{
  if (!condition)
    throw std::invalid_argument ("[pcl_crf::matching::validateParameters] " + what);
}

}  // namespace

bool
CrfMatchingModel::isTrained () const
{
  if (stages.empty ())
    return false;
  for (const StageModel& stage : stages)
    if (stage.data_boosting.getDimension () != kDataFeatureCount ||
        stage.outlier_boosting.getDimension () != kOutlierFeatureCount || stage.crf_weights.size () != kCrfWeightCount ||
        !stage.crf_weights.allFinite ())
      return false;
  return true;
}

void
validateParameters (const MatchingParameters& p)
{
  const CandidateParameters& c = p.candidates;
  require (c.guess_neighbours >= 0 && c.shape_neighbours >= 0, "neighbour counts must not be negative");
  require (c.guess_neighbours + c.shape_neighbours >= 1, "at least one candidate per point is needed");
  require (c.guess_neighbours <= 64 && c.shape_neighbours <= 64, "at most 64 neighbours of each kind");
  require (c.shape_position_scale >= 0.0, "shape_position_scale must be >= 0 m (0 or inf: shape only)");
  const SegmentMotionParameters& s = c.segments;
  require (s.neighbours >= 0 && s.neighbours <= 64, "segment neighbours must be in [0, 64]");
  require (s.breakpoint_angle > 0.0 && s.breakpoint_angle <= M_PI / 2, "breakpoint_angle must be in (0, pi/2] rad");
  require (s.range_noise >= 0.0 && std::isfinite (s.range_noise), "range_noise must be a distance >= 0 m");
  require (s.min_segment_points >= 1, "min_segment_points must be >= 1");
  require (s.max_displacement >= 0.0 && std::isfinite (s.max_displacement), "max_displacement must be >= 0 m");
  require (s.max_speed >= 0.0 && std::isfinite (s.max_speed), "max_speed must be >= 0 m/s (0: no bound)");
  require (s.max_missing_returns >= -1 && s.max_missing_returns <= 100000,
           "max_missing_returns must be in [0, 100000] beams, or -1 for no bound");
  require (s.overlap_radius > 0.0 && std::isfinite (s.overlap_radius), "overlap_radius must be > 0 m");
  require (s.overlap_spacings >= 0.0 && std::isfinite (s.overlap_spacings),
           "overlap_spacings must be >= 0 point spacings (0: overlap_radius everywhere)");
  require (p.boosting_rounds >= 1, "boosting_rounds must be >= 1");
  require (p.prior_sigma > 0.0, "prior_sigma must be > 0");
  require (p.residual_scale > 0.0 && std::isfinite (p.residual_scale), "residual_scale must be a positive distance [m]");
  require (p.passes == 1 || p.passes == 2, "passes must be 1 or 2");
  require (p.training_beam_spacing >= 0.0 && p.training_beam_spacing <= M_PI,
           "training_beam_spacing must be an angle in [0, pi] rad (0: never thin)");
  require (p.fit.iterations >= 1 && p.fit.iterations <= 1000, "fit iterations must be in [1, 1000]");
  require (p.fit.metric == FitMetric::PointToPoint || p.fit.metric == FitMetric::PointToLine,
           "fit metric must be FitMetric::PointToPoint or FitMetric::PointToLine, got " +
               std::to_string (static_cast<int> (p.fit.metric)));
  require (p.fit.initial_scale > 0.0 && std::isfinite (p.fit.initial_scale) && p.fit.final_scale > 0.0 &&
               std::isfinite (p.fit.final_scale),
           "fit scales must be positive distances [m]");
}

MatchingParameters
limitToInterval (MatchingParameters parameters, double interval)
{
  parameters.candidates.segments = limitToInterval (parameters.candidates.segments, interval);
  return parameters;
}

}  // namespace matching
}  // namespace pcl_crf
