#pragma once
// Private to pcl_crf: PCD reading that turns every malformed file into a DatasetError.

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_crf {
namespace detail {

/** \brief A field a PCD file must hold: its name and the datatype pcl_crf writes it
 *  with and reads it as (pcl::PCLPointField::FLOAT32, INT32 or UINT32), COUNT 1. */
struct PcdField
{
  std::string name;
  std::uint8_t datatype;
};

/** \brief Reads a PCD file after checking its header (PCL's reader trusts the header
 *  and can crash on a corrupt one) and that it has every field in \a fields with a
 *  COUNT of 1. A field stored with another TYPE or SIZE (x as float64, a label as
 *  int32) is converted to the declared datatype: PCL's own conversion would leave it
 *  at 0 without a word. The blob then holds just \a fields (and z, when the file has it).
 *  \throws DatasetError naming the file and the field (COUNT other than 1, a type PCL
 *  does not know), or the point (an integer field whose value is not a whole number in
 *  its type's range) */
pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<PcdField>& fields);

}  // namespace detail
}  // namespace pcl_crf
