#include <pcl_crf/clustering/clustering_model.h>
#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/readable_file.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace pcl_crf {
namespace clustering {

namespace {

constexpr const char* kMagic = "pcl_crf_crf_clustering_model";

[[noreturn]] void
fail (const std::string& where, int line, const std::string& what)
{
  throw std::runtime_error ("[pcl_crf::clustering::readModel] " + where +
                            (line > 0 ? ":" + std::to_string (line) : std::string ()) + ": " + what);
}

/** Every key of the file, in order: the weight names then the feature settings. */
std::vector<std::string>
modelKeys ()
{
  std::vector<std::string> keys (weightNames ().begin (), weightNames ().end ());
  keys.push_back ("min_neighbour_distance");
  keys.push_back ("min_spacing");
  return keys;
}

/** Parses "key value" into the map, rejecting unknown, repeated and malformed entries. */
void
parseEntry (const std::string& text, int line, const std::string& where, std::map<std::string, double>& values)
{
  std::istringstream words (text);
  std::string key, number, extra;
  words >> key >> number;
  const std::vector<std::string> keys = modelKeys ();
  if (std::find (keys.begin (), keys.end (), key) == keys.end ())
    fail (where, line, "unknown key '" + key + "'");
  if (values.count (key))
    fail (where, line, "key '" + key + "' appears twice");
  const std::optional<double> value = parseDecimal (number);
  if (number.empty () || (words >> extra))
    fail (where, line, "'" + key + "' needs exactly one number");
  if (!value)
    fail (where, line, "'" + key + "': '" + number + "' is not a finite decimal number");
  values[key] = *value;
}

void
checkHeader (const std::string& text, const std::string& where)
{
  std::istringstream words (text);
  std::string magic, version, extra;
  words >> magic;
  if (magic != kMagic)
    fail (where, 1, "not a CRF-Clustering model (expected first line '" + std::string (kMagic) + " " +
                        std::to_string (kModelVersion) + "')");
  // The version is one exact integer token: "1abc", "1.9", "1e9" are not version 1.
  if (!(words >> version))
    fail (where, 1, "missing model version after '" + std::string (kMagic) + "'");
  if (version != std::to_string (kModelVersion))
    fail (where, 1, "model version " + version + " is not supported (this build reads " +
                        std::to_string (kModelVersion) + ")");
  if (words >> extra)
    fail (where, 1, "unexpected text '" + extra + "' after the model version");
}

}  // namespace

void
writeModel (std::ostream& os, const CrfClusteringModel& model)
{
  os << kMagic << ' ' << kModelVersion << '\n'
     << "# CRF-Clustering (Tipaldi & Ramos, IROS 2009) weights, maximum pseudo-likelihood\n";
  if (model.prior_sigma > 0.0)
    os << "# learned with a Gaussian prior of sigma " << formatGeneral (model.prior_sigma, 17) << '\n';
  for (int k = 0; k < kWeightCount; ++k)
    os << weightNames ()[k] << ' ' << formatGeneral (model.weights (k), 17) << '\n';
  os << "min_neighbour_distance " << formatGeneral (model.features.min_neighbour_distance, 17) << '\n'
     << "min_spacing " << formatGeneral (model.features.min_spacing, 17) << '\n';
}

CrfClusteringModel
readModel (std::istream& is, const std::string& where)
{
  std::string text;
  int line = 0;
  bool have_header = false;
  std::map<std::string, double> values;
  while (std::getline (is, text))
  {
    ++line;
    const auto first = text.find_first_not_of (" \t\r");
    if (first == std::string::npos || text[first] == '#')
      continue;
    if (!have_header)
    {
      checkHeader (text, where);
      have_header = true;
      continue;
    }
    parseEntry (text, line, where, values);
  }
  if (!have_header)
    fail (where, 0, "empty file");
  for (const std::string& key : modelKeys ())
    if (!values.count (key))
      fail (where, 0, "missing key '" + key + "'");
  CrfClusteringModel model;
  for (int k = 0; k < kWeightCount; ++k)
    model.weights (k) = values[weightNames ()[k]];
  model.features.min_neighbour_distance = values["min_neighbour_distance"];
  model.features.min_spacing = values["min_spacing"];
  if (!(model.features.min_neighbour_distance > 0.0) || !(model.features.min_spacing > 0.0))
    fail (where, 0, "min_neighbour_distance and min_spacing must be > 0 [m]");
  return model;
}

void
saveModel (const CrfClusteringModel& model, const std::string& path)
{
  std::ofstream file (path);
  if (!file)
    throw std::runtime_error ("[pcl_crf::clustering::saveModel] cannot write '" + path + "'");
  writeModel (file, model);
  if (!file)
    throw std::runtime_error ("[pcl_crf::clustering::saveModel] writing '" + path + "' failed");
}

CrfClusteringModel
loadModel (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw std::runtime_error ("[pcl_crf::clustering::loadModel] cannot read '" + path + "': " + problem);
  std::ifstream file (path);
  return readModel (file, path);
}

}  // namespace clustering
}  // namespace pcl_crf
