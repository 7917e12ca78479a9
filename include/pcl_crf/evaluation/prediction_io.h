#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

#include <string>

namespace pcl_crf {

/** \brief Writes a method's prediction for \a pair into \a dir (created if
 *  needed): prediction.pcd (the source points with fields x y z cluster match,
 *  -1 meaning outlier cluster / no match) and prediction.txt (the clusters'
 *  motions, the static cluster, the ego motion and the time), as documented in
 *  data/README.md. \throws DatasetError
 */
void
savePrediction (const ScanPair& pair, const Prediction& prediction, const std::string& method,
                const std::string& dir);

/** \brief Reads what savePrediction wrote. \throws DatasetError naming the
 *  file and the problem. */
Prediction
loadPrediction (const std::string& dir);

}  // namespace pcl_crf
