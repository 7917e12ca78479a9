#pragma once
// Private to the dataset reader/writer: the pair.txt part of a pair folder.

#include <pcl_crf/core/scan_pair.h>

#include <string>

namespace pcl_crf {
namespace detail {

/** Fills sensor, odometry and objects of \a pair from a pair.txt file. */
void
readPairText (const std::string& path, ScanPair& pair);

/** Writes sensor, odometry and objects of \a pair as a pair.txt file. */
void
writePairText (const ScanPair& pair, const std::string& path);

}  // namespace detail
}  // namespace pcl_crf
