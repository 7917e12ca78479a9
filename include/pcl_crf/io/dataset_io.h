#pragma once

#include <pcl_crf/core/scan_pair.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Thrown by the dataset reader and writer; the message names the file
 *  and what is wrong with it.
 */
class DatasetError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/** \brief Checks a scan pair against every rule of the dataset format
 *  (see data/README.md). \throws DatasetError naming the first violation.
 *  \param[in] pair the pair to check
 *  \param[in] where a prefix for the message (a file or folder name)
 */
void
validateScanPair (const ScanPair& pair, const std::string& where);

/** \brief Reads one pair folder (source.pcd, target.pcd, pair.txt).
 *  The pair's name is the folder's name. \throws DatasetError
 */
ScanPair
loadScanPair (const std::string& pair_dir);

/** \brief Writes one pair folder, creating it if needed. The pair is validated
 *  first. Output is byte-identical for identical input. \throws DatasetError
 */
void
saveScanPair (const ScanPair& pair, const std::string& pair_dir);

/** \brief Names of the pair folders of a dataset (sub-folders holding a
 *  pair.txt), sorted. \throws DatasetError when the folder is missing or has no pair.
 */
std::vector<std::string>
listScanPairs (const std::string& dataset_dir);

/** \brief Reads every pair of a dataset folder, in sorted order. \throws DatasetError */
std::vector<ScanPair>
loadDataset (const std::string& dataset_dir);

/** \brief Writes every pair into dataset_dir/<pair.name>/. \throws DatasetError */
void
saveDataset (const std::vector<ScanPair>& pairs, const std::string& dataset_dir);

}  // namespace pcl_crf
