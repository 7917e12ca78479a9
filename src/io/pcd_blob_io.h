#pragma once
// Private to pcl_crf: PCD reading that turns every malformed file into a DatasetError.

#include <pcl/PCLPointCloud2.h>

#include <string>
#include <vector>

namespace pcl_crf {
namespace detail {

/** Reads a PCD file after checking its header (PCL's reader trusts the header
 *  and can crash on a corrupt one) and that it has every field in \a fields. */
pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<std::string>& fields);

}  // namespace detail
}  // namespace pcl_crf
