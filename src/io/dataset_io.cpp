#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/point_types.h>

#include "pair_text_io.h"
#include "pcd_blob_io.h"

#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>

namespace fs = std::filesystem;

namespace pcl_crf {
namespace {

constexpr auto kFloat32 = pcl::PCLPointField::FLOAT32;

/** \brief The fields of source.pcd as writeSource writes them (pcl_crf::PointXYZLMatch). */
const std::vector<detail::PcdField> kSourceFields = {
    {"x", kFloat32}, {"y", kFloat32}, {"label", pcl::PCLPointField::UINT32}, {"match", pcl::PCLPointField::INT32}};

/** \brief The fields of target.pcd as writeTarget writes them (pcl::PointXYZL). */
const std::vector<detail::PcdField> kTargetFields = {
    {"x", kFloat32}, {"y", kFloat32}, {"label", pcl::PCLPointField::UINT32}};

template <typename PointT> void
copyPositions (const pcl::PointCloud<PointT>& cloud, const std::string& path, Eigen::Matrix2Xd& xy,
               std::vector<int>& labels)
{
  xy.resize (2, static_cast<Eigen::Index> (cloud.size ()));
  labels.resize (cloud.size ());
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    const PointT& p = cloud[i];
    if (!std::isfinite (p.x) || !std::isfinite (p.y))
      throw DatasetError (path + ": point " + std::to_string (i) + " has a NaN or infinite coordinate");
    xy.col (i) << p.x, p.y;
    if (p.label > static_cast<std::uint32_t> (std::numeric_limits<int>::max ()))
      throw DatasetError (path + ": point " + std::to_string (i) + " has label " + std::to_string (p.label) +
                          ", beyond the largest object id " + std::to_string (std::numeric_limits<int>::max ()));
    labels[i] = static_cast<int> (p.label);
  }
}

void
readSource (const std::string& path, ScanPair& pair)
{
  const pcl::PCLPointCloud2 blob = detail::readPcdBlob (path, kSourceFields);
  pcl::PointCloud<PointXYZLMatch> cloud;
  pcl::fromPCLPointCloud2 (blob, cloud);
  copyPositions (cloud, path, pair.source, pair.source_object);
  pair.source_match.resize (cloud.size ());
  for (std::size_t i = 0; i < cloud.size (); ++i)
    pair.source_match[i] = cloud[i].match;
}

void
readTarget (const std::string& path, ScanPair& pair)
{
  pcl::PointCloud<pcl::PointXYZL> cloud;
  pcl::fromPCLPointCloud2 (detail::readPcdBlob (path, kTargetFields), cloud);
  copyPositions (cloud, path, pair.target, pair.target_object);
}

void
writeSource (const ScanPair& pair, const std::string& path)
{
  pcl::PointCloud<PointXYZLMatch> cloud;
  cloud.resize (pair.source.cols ());
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    cloud[i].x = static_cast<float> (pair.source (0, i));
    cloud[i].y = static_cast<float> (pair.source (1, i));
    cloud[i].z = 0.0f;
    cloud[i].label = static_cast<std::uint32_t> (pair.source_object[i]);
    cloud[i].match = pair.source_match[i];
  }
  if (pcl::io::savePCDFileASCII (path, cloud) != 0)
    throw DatasetError (path + ": cannot write");
}

void
writeTarget (const ScanPair& pair, const std::string& path)
{
  pcl::PointCloud<pcl::PointXYZL> cloud;
  cloud.resize (pair.target.cols ());
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    cloud[i].x = static_cast<float> (pair.target (0, i));
    cloud[i].y = static_cast<float> (pair.target (1, i));
    cloud[i].z = 0.0f;
    cloud[i].label = static_cast<std::uint32_t> (pair.target_object[i]);
  }
  if (pcl::io::savePCDFileASCII (path, cloud) != 0)
    throw DatasetError (path + ": cannot write");
}

}  // namespace

ScanPair
loadScanPair (const std::string& pair_dir)
{
  if (!fs::is_directory (pair_dir))
    throw DatasetError (pair_dir + ": pair folder not found");
  ScanPair pair;
  pair.name = fs::path (pair_dir).lexically_normal ().filename ().string ();
  if (pair.name.empty ())
    pair.name = fs::path (pair_dir).lexically_normal ().parent_path ().filename ().string ();
  detail::readPairText ((fs::path (pair_dir) / "pair.txt").string (), pair);
  readSource ((fs::path (pair_dir) / "source.pcd").string (), pair);
  readTarget ((fs::path (pair_dir) / "target.pcd").string (), pair);
  validateScanPair (pair, pair_dir);
  return pair;
}

void
saveScanPair (const ScanPair& pair, const std::string& pair_dir)
{
  validateScanPair (pair, pair_dir);
  std::error_code error;
  fs::create_directories (pair_dir, error);
  if (error)
    throw DatasetError (pair_dir + ": cannot create folder (" + error.message () + ")");
  detail::writePairText (pair, (fs::path (pair_dir) / "pair.txt").string ());
  writeSource (pair, (fs::path (pair_dir) / "source.pcd").string ());
  writeTarget (pair, (fs::path (pair_dir) / "target.pcd").string ());
}

std::vector<std::string>
listScanPairs (const std::string& dataset_dir)
{
  if (!fs::is_directory (dataset_dir))
    throw DatasetError (dataset_dir + ": dataset folder not found");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator (dataset_dir))
    if (entry.is_directory () && fs::is_regular_file (entry.path () / "pair.txt"))
      names.push_back (entry.path ().filename ().string ());
  if (names.empty ())
    throw DatasetError (dataset_dir + ": no pair folders (sub-folders with a pair.txt)");
  std::sort (names.begin (), names.end ());
  return names;
}

std::vector<ScanPair>
loadDataset (const std::string& dataset_dir)
{
  std::vector<ScanPair> pairs;
  for (const auto& name : listScanPairs (dataset_dir))
    pairs.push_back (loadScanPair ((fs::path (dataset_dir) / name).string ()));
  return pairs;
}

void
saveDataset (const std::vector<ScanPair>& pairs, const std::string& dataset_dir)
{
  for (const auto& pair : pairs) {
    if (pair.name.empty ())
      throw DatasetError (dataset_dir + ": a pair has no name (its folder name)");
    saveScanPair (pair, (fs::path (dataset_dir) / pair.name).string ());
  }
}

}  // namespace pcl_crf
