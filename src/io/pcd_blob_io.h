#pragma once
// Private to pcl_crf: PCD reading that turns every malformed file into a DatasetError.

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_crf {
namespace detail {

/** \brief A field a PCD file must hold: its name and the one datatype pcl_crf
 *  writes it with (pcl::PCLPointField::FLOAT32, INT32, UINT32, ...), COUNT 1. */
struct PcdField
{
  std::string name;
  std::uint8_t datatype;
};

/** \brief Reads a PCD file after checking its header (PCL's reader trusts the header
 *  and can crash on a corrupt one) and that it has every field in \a fields with
 *  exactly the declared datatype and a COUNT of 1: PCL's conversion would otherwise
 *  leave a field of another TYPE or SIZE at 0 without a word.
 *  \throws DatasetError naming the file, the field, and the expected and found layout */
pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<PcdField>& fields);

}  // namespace detail
}  // namespace pcl_crf
