#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/readable_file.h>
#include <pcl_crf/matching/range_profile.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace joint {

namespace {

constexpr const char* kMagic = "pcl_crf_joint_model";
constexpr const char* kClusteringPart = "crf_clustering_model";
constexpr const char* kMatchingPart = "crf_matching_model";

[[noreturn]] void
fail (const std::string& name, const std::string& what)
{
  throw std::runtime_error ("[pcl_crf::joint::readJointModel] " + name + ": " + what);
}

/** Reads the next line, failing with \a expected in the message at the end of the text. */
std::string
nextLine (std::istream& is, const std::string& name, const std::string& expected)
{
  std::string line;
  if (!std::getline (is, line))
    fail (name, "truncated: expected " + expected);
  return line;
}

/** "key value" with the given key and a finite number. */
double
readEntry (std::istream& is, const std::string& name, const std::string& key)
{
  std::istringstream words (nextLine (is, name, "'" + key + "'"));
  std::string word, number, extra;
  words >> word >> number;
  if (word != key)
    fail (name, "expected '" + key + "', found '" + word + "'");
  const std::optional<double> value = parseDecimal (number);
  if (!value || (words >> extra))
    fail (name, "'" + key + "' needs exactly one finite decimal number");
  return *value;
}

/** The text between "begin <part>" and "end <part>". */
std::string
readPart (std::istream& is, const std::string& name, const std::string& part)
{
  if (nextLine (is, name, "'begin " + part + "'") != "begin " + part)
    fail (name, "expected 'begin " + part + "'");
  std::string text, line;
  while (std::getline (is, line)) {
    if (line == "end " + part)
      return text;
    text += line + '\n';
  }
  fail (name, "truncated: no 'end " + part + "'");
}

}  // namespace

void
validateParameters (const JointParameters& p)
{
  const auto bad = [] (const std::string& what) {
    throw std::invalid_argument ("[pcl_crf::joint::validateParameters] " + what);
  };
  if (p.max_rounds < 1)
    bad ("max_rounds must be >= 1");
  if (p.min_cluster_points < 0)
    bad ("min_cluster_points must be >= 0 (0: the model's)");
  if (!(p.max_average_neff > 1.0))
    bad ("max_average_neff must be > 1");
  if (p.segment_min_points_seen_through < 1)
    bad ("segment_min_points_seen_through must be >= 1");
  if (!(p.part_gap > 0.0) || !std::isfinite (p.part_gap))
    bad ("part_gap must be a distance > 0 m");
  if (!(p.slight_motion.min_deviance > 0.0) || !std::isfinite (p.slight_motion.min_deviance))
    bad ("slight_motion.min_deviance must be > 0");
  if (!(p.slight_motion.min_mean_deviance >= 0.0) || !std::isfinite (p.slight_motion.min_mean_deviance))
    bad ("slight_motion.min_mean_deviance must be >= 0");
  if (!(p.slight_motion.along_beam_steps >= 0.0) || !std::isfinite (p.slight_motion.along_beam_steps))
    bad ("slight_motion.along_beam_steps must be >= 0 beam steps");
  if (!clustering::isMotionFit (p.final_motion_fit))
    bad ("final_motion_fit must be MotionFit::Marginals or MotionFit::OwnPoints, got " +
         std::to_string (static_cast<int> (p.final_motion_fit)));
  matching::describesBeams (p.sensor);  // throws for a sensor that describes no beams sensibly
  validateLadderOptions (p.inference);
  clustering::validateParameters (p.initial_clustering);
}

bool
JointModel::isTrained () const
{
  return matcher.isTrained () && min_cluster_points >= 1 && weights.size () == kJointWeightCount && weights.allFinite () &&
         initial_clustering.weights.size () == clustering::kWeightCount;
}

void
writeJointModel (const JointModel& model, std::ostream& os)
{
  os << kMagic << ' ' << kJointModelVersion << '\n';
  os << "prior_sigma " << formatGeneral (model.prior_sigma, 17) << '\n';
  os << "min_cluster_points " << model.min_cluster_points << '\n';
  for (int k = 0; k < kJointWeightCount; ++k)
    os << jointWeightNames ()[k] << ' ' << formatGeneral (model.weights (k), 17) << '\n';
  os << "begin " << kClusteringPart << '\n';
  clustering::writeModel (os, model.initial_clustering);
  os << "end " << kClusteringPart << '\n';
  os << "begin " << kMatchingPart << '\n';
  matching::writeModel (model.matcher, os);
  os << "end " << kMatchingPart << '\n';
}

JointModel
readJointModel (std::istream& is, const std::string& name)
{
  std::istringstream header (nextLine (is, name, "the header"));
  std::string magic, version, extra;
  if (!(header >> magic) || magic != kMagic)
    fail (name, std::string ("not a joint model (expected '") + kMagic + " " + std::to_string (kJointModelVersion) + "')");
  // The version is one exact integer token: "1abc", "1.9", "1e9" are not version 1.
  if (!(header >> version))
    fail (name, std::string ("missing version after '") + kMagic + "'");
  if (version != std::to_string (kJointModelVersion))
    fail (name, "version " + version + " is not supported (expected " + std::to_string (kJointModelVersion) + ")");
  if (header >> extra)
    fail (name, "unexpected text '" + extra + "' after the version in the header");
  JointModel model;
  model.prior_sigma = readEntry (is, name, "prior_sigma");
  const double min_points = readEntry (is, name, "min_cluster_points");
  if (min_points < 1 || min_points != std::floor (min_points) || min_points > 1e6)
    fail (name, "'min_cluster_points' must be a whole number >= 1");
  model.min_cluster_points = static_cast<int> (min_points);
  for (int k = 0; k < kJointWeightCount; ++k)
    model.weights (k) = readEntry (is, name, jointWeightNames ()[k]);
  std::istringstream clustering_text (readPart (is, name, kClusteringPart));
  model.initial_clustering = clustering::readModel (clustering_text, name + " (" + kClusteringPart + ")");
  std::istringstream matching_text (readPart (is, name, kMatchingPart));
  model.matcher = matching::readModel (matching_text, name + " (" + kMatchingPart + ")");
  return model;
}

void
saveJointModel (const JointModel& model, const std::string& path)
{
  std::ofstream file (path);
  if (!file)
    throw std::runtime_error ("[pcl_crf::joint::saveJointModel] cannot write '" + path + "'");
  writeJointModel (model, file);
  if (!file)
    throw std::runtime_error ("[pcl_crf::joint::saveJointModel] writing '" + path + "' failed");
}

JointModel
loadJointModel (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw std::runtime_error ("[pcl_crf::joint::loadJointModel] cannot read '" + path + "': " + problem);
  std::ifstream file (path);
  return readJointModel (file, path);
}

}  // namespace joint
}  // namespace pcl_crf
