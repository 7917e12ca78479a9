#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/point_types.h>

#include "../io/pcd_blob_io.h"

#include <pcl/conversions.h>

#include <pcl/io/pcd_io.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pcl_crf {
namespace {

constexpr const char* kMagic = "pcl_crf_prediction";

std::string
xyTheta (const Rigid2d& T)
{
  const Eigen::Vector3d v = toXYTheta (T);
  char buffer[128];
  std::snprintf (buffer, sizeof (buffer), "%.17g %.17g %.17g", v.x (), v.y (), v.z ());
  return buffer;
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

Rigid2d
readXYTheta (std::istringstream& in, const std::string& where)
{
  double x, y, theta;
  if (!(in >> x >> y >> theta) || !std::isfinite (x) || !std::isfinite (y) || !std::isfinite (theta))
    throw DatasetError (where + ": expected three finite numbers x y theta");
  return makeRigid2d (x, y, theta);
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
  file << kMagic << " 1\n";
  file << "method " << method << "\n";
  file << "pair " << pair.name << "\n";
  file << "has_match " << (prediction.source_match.empty () ? 0 : 1) << "\n";
  file << "has_cluster " << (prediction.source_cluster.empty () ? 0 : 1) << "\n";
  file << "ego " << xyTheta (prediction.T_source_target) << "\n";
  for (std::size_t k = 0; k < prediction.cluster_motions.size (); ++k)
    file << "cluster " << k << (static_cast<int> (k) == prediction.static_cluster ? " static " : " moving ")
         << xyTheta (prediction.cluster_motions[k]) << "\n";
  file << "seconds " << prediction.seconds << "\n";
  if (!file)
    throw DatasetError (path + ": write failed");
}

Prediction
loadPrediction (const std::string& dir)
{
  const std::string text_path = (fs::path (dir) / "prediction.txt").string ();
  std::ifstream file (text_path);
  if (!file)
    throw DatasetError (text_path + ": cannot open");
  Prediction prediction;
  bool has_match = false, has_cluster = false;
  std::string line;
  int line_number = 0;
  while (std::getline (file, line)) {
    ++line_number;
    std::istringstream in (line);
    std::string key;
    in >> key;
    const std::string where = text_path + ":" + std::to_string (line_number);
    if (key == "ego")
      prediction.T_source_target = readXYTheta (in, where);
    else if (key == "cluster") {
      std::size_t index;
      std::string kind;
      in >> index >> kind;
      if (index != prediction.cluster_motions.size ())
        throw DatasetError (where + ": clusters must be listed in order 0, 1, 2, ...");
      if (kind == "static")
        prediction.static_cluster = static_cast<int> (index);
      prediction.cluster_motions.push_back (readXYTheta (in, where));
    }
    else if (key == "has_match")
      in >> has_match;
    else if (key == "has_cluster")
      in >> has_cluster;
    else if (key == "seconds")
      in >> prediction.seconds;
  }
  const std::string cloud_path = (fs::path (dir) / "prediction.pcd").string ();
  pcl::PointCloud<PointXYZClusterMatch> cloud;
  pcl::fromPCLPointCloud2 (detail::readPcdBlob (
      cloud_path, {{"x", pcl::PCLPointField::FLOAT32}, {"y", pcl::PCLPointField::FLOAT32},
                   {"cluster", pcl::PCLPointField::INT32}, {"match", pcl::PCLPointField::INT32}}), cloud);
  for (const auto& point : cloud) {
    if (has_match)
      prediction.source_match.push_back (point.match);
    if (has_cluster)
      prediction.source_cluster.push_back (point.cluster);
  }
  return prediction;
}

}  // namespace pcl_crf
