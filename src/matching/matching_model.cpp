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
  const std::string segments_problem = segmentParametersProblem (c.segments);
  require (segments_problem.empty (), segments_problem);
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
