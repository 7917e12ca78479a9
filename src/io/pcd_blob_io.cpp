#include "pcd_blob_io.h"

#include <pcl_crf/io/dataset_io.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>

namespace pcl_crf {
namespace detail {

pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<std::string>& fields)
{
  if (!std::filesystem::is_regular_file (path))
    throw DatasetError (path + ": file not found");
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_index = 0;
  if (reader.readHeader (path, blob, origin, orientation, version, data_type, data_index) != 0 ||
      blob.fields.empty () || blob.point_step == 0)
    throw DatasetError (path + ": not a PCD file (unreadable header, or no FIELDS/SIZE/TYPE)");
  if (static_cast<std::size_t> (blob.width) * blob.height == 0)
    throw DatasetError (path + ": PCD header declares no points");
  if (reader.read (path, blob) != 0)
    throw DatasetError (path + ": not a readable PCD file (truncated or corrupt data)");
  for (const auto& field : fields)
    if (pcl::getFieldIndex (blob, field) < 0)
      throw DatasetError (path + ": missing field '" + field + "'");
  return blob;
}

}  // namespace detail
}  // namespace pcl_crf
