#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/readable_file.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/point_types.h>

#include "../io/pcd_blob_io.h"

#include <pcl/conversions.h>

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <optional>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pcl_crf {
namespace {

constexpr const char* kMagic = "pcl_crf_prediction";

std::string
xyTheta (const Rigid2d& T)
{
  const Eigen::Vector3d v = toXYTheta (T);
  return formatGeneral (v.x (), 17) + " " + formatGeneral (v.y (), 17) + " " + formatGeneral (v.z (), 17);
}

void
writePredictionCloud (const ScanPair& pair, const Prediction& prediction, const std::string& path)
{
  pcl::PointCloud<PointXYZClusterMatch> cloud;
  cloud.resize (pair.source.cols ());
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    cloud[i].x = static_cast<float> (pair.source (0, i));
    cloud[i].y = static_cast<float> (pair.source (1, i));
    cloud[i].z = 0.0f;
    cloud[i].cluster = prediction.source_cluster.empty () ? kOutlierCluster : prediction.source_cluster[i];
    cloud[i].match = prediction.source_match.empty () ? kNoMatch : prediction.source_match[i];
  }
  if (pcl::io::savePCDFileASCII (path, cloud) != 0)
    throw DatasetError (path + ": cannot write");
}

[[noreturn]] void
fail (const std::string& where, const std::string& what)
{
  throw DatasetError (where + ": " + what);
}

/** \brief Fails unless \a in has nothing left on its line. */
void
expectEnd (std::istringstream& in, const std::string& where)
{
  std::string extra;
  if (in >> extra)
    fail (where, "unexpected trailing value '" + extra + "'");
}

/** \brief The next word as a finite decimal number (parseDecimal ()), or nothing. */
std::optional<double>
readNumber (std::istringstream& in)
{
  std::string word;
  if (!(in >> word))
    return std::nullopt;
  return parseDecimal (word);
}

Rigid2d
readXYTheta (std::istringstream& in, const std::string& where)
{
  const std::optional<double> x = readNumber (in), y = readNumber (in), theta = readNumber (in);
  if (!x || !y || !theta)
    fail (where, "expected three finite decimal numbers x y theta");
  if (std::max (std::abs (*x), std::abs (*y)) > kMaxCoordinate)
    fail (where, "a translation beyond 1e18 m");
  expectEnd (in, where);
  return makeRigid2d (*x, *y, *theta);
}

/** \brief A "0" or "1" token (has_match, has_cluster). */
bool
readFlag (std::istringstream& in, const std::string& key, const std::string& where)
{
  std::string token;
  in >> token;
  if (token != "0" && token != "1")
    fail (where, "'" + key + "' must be 0 or 1, got '" + token + "'");
  expectEnd (in, where);
  return token == "1";
}

/** \brief One "cluster K static|moving x y theta" line; clusters come in order 0, 1, 2, ... */
void
readCluster (std::istringstream& in, const std::string& where, Prediction& prediction)
{
  std::string index, kind;
  in >> index >> kind;
  if (index != std::to_string (prediction.cluster_motions.size ()))
    fail (where, "clusters must be listed in order 0, 1, 2, ... (expected cluster " +
                     std::to_string (prediction.cluster_motions.size ()) + ", got '" + index + "')");
  if (kind != "static" && kind != "moving")
    fail (where, "cluster kind must be 'static' or 'moving', got '" + kind + "'");
  if (kind == "static" && prediction.static_cluster >= 0)
    fail (where, "a second static cluster (cluster " + std::to_string (prediction.static_cluster) +
                     " is already static)");
  if (kind == "static")
    prediction.static_cluster = static_cast<int> (prediction.cluster_motions.size ());
  prediction.cluster_motions.push_back (readXYTheta (in, where));
}

/** \brief What prediction.txt says besides the per-point labels. */
struct PredictionText
{
  Prediction prediction;
  bool has_match = false;
  bool has_cluster = false;
};

/** \brief Reads prediction.txt strictly: the header first, every key savePrediction
 *  writes exactly once (clusters any number of times), nothing else. */
PredictionText
readPredictionText (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw DatasetError (path + ": cannot read (" + problem + ")");
  std::ifstream file (path);
  PredictionText text;
  std::set<std::string> seen;
  std::string line;
  int line_number = 0;
  while (std::getline (file, line)) {
    ++line_number;
    std::istringstream in (line);
    std::string key, word;
    in >> key;
    const std::string where = path + ":" + std::to_string (line_number);
    if (line_number == 1) {
      in >> word;
      if (key != kMagic || word != "1")
        fail (where, "expected the header '" + std::string (kMagic) + " 1', got '" + line + "'");
      expectEnd (in, where);
      continue;
    }
    if (key != "cluster" && !seen.insert (key).second)
      fail (where, "'" + key + "' appears twice");
    if (key == "ego")
      text.prediction.T_source_target = readXYTheta (in, where);
    else if (key == "cluster")
      readCluster (in, where, text.prediction);
    else if (key == "has_match")
      text.has_match = readFlag (in, key, where);
    else if (key == "has_cluster")
      text.has_cluster = readFlag (in, key, where);
    else if (key == "seconds") {
      const std::optional<double> seconds = readNumber (in);
      if (!seconds || *seconds < 0.0)
        fail (where, "'seconds' needs a finite time >= 0");
      text.prediction.seconds = *seconds;
      expectEnd (in, where);
    }
    else if (key == "method" || key == "pair") {  // the rest of the line: a folder name may hold spaces
      if (!(in >> word))
        fail (where, "'" + key + "' needs a name");
    }
    else
      fail (where, "unknown key '" + key + "'");
  }
  if (line_number == 0)
    fail (path, "empty file (expected the header '" + std::string (kMagic) + " 1')");
  for (const char* key : {"method", "pair", "has_match", "has_cluster", "ego", "seconds"})
    if (!seen.count (key))
      fail (path, std::string ("missing '") + key + "' line");
  return text;
}

}  // namespace

void
savePrediction (const ScanPair& pair, const Prediction& prediction, const std::string& method,
                const std::string& dir)
{
  std::error_code error;
  fs::create_directories (dir, error);
  if (error)
    throw DatasetError (dir + ": cannot create folder (" + error.message () + ")");
  writePredictionCloud (pair, prediction, (fs::path (dir) / "prediction.pcd").string ());
  const std::string path = (fs::path (dir) / "prediction.txt").string ();
  std::ofstream file (path);
  file.imbue (std::locale::classic ());  // indices without a host program's digit grouping
  file << kMagic << " 1\n";
  file << "method " << method << "\n";
  file << "pair " << pair.name << "\n";
  file << "has_match " << (prediction.source_match.empty () ? 0 : 1) << "\n";
  file << "has_cluster " << (prediction.source_cluster.empty () ? 0 : 1) << "\n";
  file << "ego " << xyTheta (prediction.T_source_target) << "\n";
  for (std::size_t k = 0; k < prediction.cluster_motions.size (); ++k)
    file << "cluster " << k << (static_cast<int> (k) == prediction.static_cluster ? " static " : " moving ")
         << xyTheta (prediction.cluster_motions[k]) << "\n";
  file << "seconds " << formatGeneral (prediction.seconds, 6) << "\n";
  if (!file)
    throw DatasetError (path + ": write failed");
}

Prediction
loadPrediction (const std::string& dir)
{
  PredictionText text = readPredictionText ((fs::path (dir) / "prediction.txt").string ());
  Prediction& prediction = text.prediction;
  const std::string cloud_path = (fs::path (dir) / "prediction.pcd").string ();
  pcl::PointCloud<PointXYZClusterMatch> cloud;
  pcl::fromPCLPointCloud2 (detail::readPcdBlob (
      cloud_path, {{"x", pcl::PCLPointField::FLOAT32}, {"y", pcl::PCLPointField::FLOAT32},
                   {"cluster", pcl::PCLPointField::INT32}, {"match", pcl::PCLPointField::INT32}}), cloud);
  const int clusters = static_cast<int> (prediction.cluster_motions.size ());
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    const PointXYZClusterMatch& point = cloud[i];
    if (text.has_cluster && (point.cluster < kOutlierCluster || point.cluster >= clusters))
      fail (cloud_path, "point " + std::to_string (i) + " has cluster " + std::to_string (point.cluster) +
                            ", out of range [0, " + std::to_string (clusters) + ") and not -1");
    if (text.has_match && point.match < kNoMatch)
      fail (cloud_path, "point " + std::to_string (i) + " has match " + std::to_string (point.match) +
                            ", negative and not -1");
    if (text.has_match)
      prediction.source_match.push_back (point.match);
    if (text.has_cluster)
      prediction.source_cluster.push_back (point.cluster);
  }
  return prediction;
}

}  // namespace pcl_crf
