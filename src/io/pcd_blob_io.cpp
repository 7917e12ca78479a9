#include "pcd_blob_io.h"

#include <pcl_crf/io/dataset_io.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>

namespace pcl_crf {
namespace detail {
namespace {

/** \brief A field's layout as the PCD header spells it, e.g. "TYPE F SIZE 4 COUNT 1". */
std::string
describeLayout (int datatype, std::uint32_t count)
{
  const int size = pcl::getFieldSize (datatype);
  if (size == 0)
    return "a TYPE/SIZE pair PCL does not know";
  return "TYPE " + std::string (1, pcl::getFieldType (datatype)) + " SIZE " + std::to_string (size) + " COUNT " +
         std::to_string (count);
}

/** \brief Checks that \a blob's header declares \a field with its datatype and COUNT 1. */
void
checkField (const pcl::PCLPointCloud2& blob, const PcdField& field, const std::string& path)
{
  const int index = pcl::getFieldIndex (blob, field.name);
  if (index < 0)
    throw DatasetError (path + ": missing field '" + field.name + "'");
  const pcl::PCLPointField& found = blob.fields[index];
  if (found.datatype != field.datatype || found.count != 1)
    throw DatasetError (path + ": field '" + field.name + "' must be " +
                        describeLayout (field.datatype, 1) + ", found " +
                        describeLayout (found.datatype, found.count));
}

}  // namespace

pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<PcdField>& fields)
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
  for (const auto& field : fields)
    checkField (blob, field, path);
  if (reader.read (path, blob) != 0)
    throw DatasetError (path + ": not a readable PCD file (truncated or corrupt data)");
  return blob;
}

}  // namespace detail
}  // namespace pcl_crf
