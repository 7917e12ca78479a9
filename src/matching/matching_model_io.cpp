#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/io/readable_file.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/raw_features.h>

#include "model_reader.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace matching {

namespace {

using detail::ModelReader;

const char* const kMagic = "pcl_crf_crf_matching_model";
const char* const kWeightNames =
    "data_margin outlier_margin outlier_bias sequence sequence_repeat sequence_skip outlier_switch outlier_run "
    "pairwise_distance pairwise_translation";


MatchingParameters
readParameters (ModelReader& reader)
{
  MatchingParameters p;
  p.candidates.guess_neighbours = reader.integer ("guess_neighbours", 0, 64);
  p.candidates.shape_neighbours = reader.integer ("shape_neighbours", 0, 64);
  p.candidates.shape_position_scale = reader.real ("shape_position_scale", 0.0);
  SegmentMotionParameters& segments = p.candidates.segments;
  segments.neighbours = reader.integer ("segment_neighbours", 0, 64);
  segments.breakpoint_angle = reader.real ("segment_breakpoint_angle", 0.0, M_PI / 2);
  segments.range_noise = reader.real ("segment_range_noise", 0.0);
  segments.min_segment_points = reader.integer ("segment_min_points", 1, 100000);
  segments.max_displacement = reader.real ("segment_max_displacement", 0.0);
  // absent from models written before it: no speed bound, as they were trained
  segments.max_speed = reader.optionalReal ("segment_max_speed", 0.0, 0.0, 1e6);
  // absent from models written before it: no bound, as they were trained
  segments.max_missing_returns = reader.optionalInteger ("segment_max_missing_returns", -1, -1, 100000);
  segments.overlap_radius = reader.real ("segment_overlap_radius", 0.0);
  // absent from models written before it: the metric radius everywhere, as they were trained
  segments.overlap_spacings = reader.optionalReal ("segment_overlap_spacings", 0.0, 0.0, 1e6);
  p.boosting_rounds = reader.integer ("boosting_rounds", 1, 100000);
  p.prior_sigma = reader.real ("prior_sigma", std::numeric_limits<double>::min ());
  p.residual_scale = reader.real ("residual_scale", std::numeric_limits<double>::min ());
  p.passes = reader.integer ("passes", 1, 2);
  p.fit.iterations = reader.integer ("fit_iterations", 1, 1000);
  p.fit.initial_scale = reader.real ("fit_initial_scale", std::numeric_limits<double>::min ());
  p.fit.final_scale = reader.real ("fit_final_scale", std::numeric_limits<double>::min ());
  p.fit.reassociate = reader.integer ("fit_reassociate", 0, 1) == 1;
  const std::string metric = reader.keyLine ("fit_metric").front ();
  if (metric != "point_to_point" && metric != "point_to_line")
    reader.fail ("'fit_metric' must be point_to_point or point_to_line, not '" + metric + "'");
  p.fit.metric = metric == "point_to_line" ? FitMetric::PointToLine : FitMetric::PointToPoint;
  p.training_beam_spacing = reader.optionalReal ("training_beam_spacing", 0.0, 0.0, M_PI);
  try {
    validateParameters (p);
  }
  catch (const std::invalid_argument& error) {
    reader.fail (error.what ());
  }
  return p;
}

StageModel
readStage (ModelReader& reader, int index)
{
  reader.integer ("stage", index, index);  // stages in order 0, 1, ...
  StageModel stage;
  const std::vector<std::string> weights = reader.keyLine ("crf_weights", kCrfWeightCount);
  stage.crf_weights.resize (kCrfWeightCount);
  for (int k = 0; k < kCrfWeightCount; ++k)
    stage.crf_weights (k) = reader.number ("crf_weights", weights[k]);
  reader.booster ("data_boosting", kDataFeatureCount, stage.data_boosting);
  reader.booster ("outlier_boosting", kOutlierFeatureCount, stage.outlier_boosting);
  return stage;
}

}  // namespace

void
writeModel (const CrfMatchingModel& model, std::ostream& os)
{
  if (!model.isTrained ())
    throw std::runtime_error ("[pcl_crf::matching::writeModel] the model is not trained");
  std::ostringstream text;
  text.imbue (std::locale::classic ());
  const MatchingParameters& p = model.parameters;
  const auto number = [] (double value) { return formatShortest (value); };
  text << kMagic << ' ' << kModelFileVersion << '\n'
       << "# CRF-Matching (Ramos, Fox & Durrant-Whyte, RSS 2007; Tipaldi & Ramos, ICRA 2010, Sec. IV-C).\n"
       << "# Units: metres, radians. Written by pcl_crf::matching::writeModel.\n"
       << "guess_neighbours " << p.candidates.guess_neighbours << '\n'
       << "shape_neighbours " << p.candidates.shape_neighbours << '\n'
       << "shape_position_scale " << number (p.candidates.shape_position_scale) << '\n'
       << "segment_neighbours " << p.candidates.segments.neighbours << '\n'
       << "segment_breakpoint_angle " << number (p.candidates.segments.breakpoint_angle) << '\n'
       << "segment_range_noise " << number (p.candidates.segments.range_noise) << '\n'
       << "segment_min_points " << p.candidates.segments.min_segment_points << '\n'
       << "segment_max_displacement " << number (p.candidates.segments.max_displacement) << '\n'
       << "segment_max_speed " << number (p.candidates.segments.max_speed) << '\n'
       << "segment_max_missing_returns " << p.candidates.segments.max_missing_returns << '\n'
       << "segment_overlap_radius " << number (p.candidates.segments.overlap_radius) << '\n'
       << "segment_overlap_spacings " << number (p.candidates.segments.overlap_spacings) << '\n'
       << "boosting_rounds " << p.boosting_rounds << '\n'
       << "prior_sigma " << number (p.prior_sigma) << '\n'
       << "residual_scale " << number (p.residual_scale) << '\n'
       << "passes " << p.passes << '\n'
       << "fit_iterations " << p.fit.iterations << '\n'
       << "fit_initial_scale " << number (p.fit.initial_scale) << '\n'
       << "fit_final_scale " << number (p.fit.final_scale) << '\n'
       << "fit_reassociate " << (p.fit.reassociate ? 1 : 0) << '\n'
       << "fit_metric " << (p.fit.metric == FitMetric::PointToLine ? "point_to_line" : "point_to_point") << '\n'
       << "training_beam_spacing " << number (p.training_beam_spacing) << '\n'
       << "stages " << model.stages.size () << '\n';
  for (std::size_t k = 0; k < model.stages.size (); ++k) {
    const StageModel& stage = model.stages[k];
    text << "stage " << k << '\n' << "# weights: " << kWeightNames << '\n' << "crf_weights";
    for (Eigen::Index w = 0; w < stage.crf_weights.size (); ++w)
      text << ' ' << formatShortest (stage.crf_weights (w));
    text << '\n' << "data_boosting\n";
    stage.data_boosting.write (text);
    text << "outlier_boosting\n";
    stage.outlier_boosting.write (text);
  }
  text << "end\n";
  os << text.str ();
}

CrfMatchingModel
readModel (std::istream& is, const std::string& name)
{
  ModelReader reader (is, name);
  const std::vector<std::string> header = reader.nextLine ("the header");
  if (header.size () != 2 || header[0] != kMagic)
    reader.fail (std::string ("not a CRF-Matching model (expected the header '") + kMagic + " " +
                 std::to_string (kModelFileVersion) + "')");
  if (header[1] != std::to_string (kModelFileVersion))
    reader.fail ("unsupported model file version '" + header[1] + "', expected " + std::to_string (kModelFileVersion));
  CrfMatchingModel model;
  model.parameters = readParameters (reader);
  const int stages = reader.integer ("stages", 1, 2);
  for (int k = 0; k < stages; ++k)
    model.stages.push_back (readStage (reader, k));
  reader.keyLine ("end", 0);
  return model;
}

void
saveModel (const CrfMatchingModel& model, const std::string& path)
{
  std::ofstream file (path);
  if (!file)
    throw std::runtime_error ("[pcl_crf::matching::saveModel] cannot open '" + path + "' for writing");
  writeModel (model, file);
  if (!file)
    throw std::runtime_error ("[pcl_crf::matching::saveModel] failed writing '" + path + "'");
}

CrfMatchingModel
loadModel (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw std::runtime_error (path + ": cannot read the CRF-Matching model file: " + problem);
  std::ifstream file (path);
  return readModel (file, path);
}

}  // namespace matching
}  // namespace pcl_crf
