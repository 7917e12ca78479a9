#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

namespace pcl_crf {

/** \brief Checks that a prediction can be scored against a pair's truth.
 *
 *  Empty \c source_match or \c source_cluster are fine (the method does not
 *  associate or cluster). A non-empty one must hold one entry per source point,
 *  and the truth must then carry the matching labels:
 *   - source_match: truth.source_match has one entry per source point, and
 *     every index (predicted or true) is kNoMatch or a target column;
 *   - source_cluster: truth.source_object has one entry per source point, each
 *     id declared in truth.objects, and every label is kOutlierCluster or lies
 *     in [0, cluster_motions.size ()).
 *  T_source_target and every cluster motion must be finite rigid motions (a NaN
 *  motion would score as no error), and static_cluster −1 or one of the clusters.
 *
 *  \throws std::invalid_argument naming the first violation and the sizes involved.
 */
void
validatePrediction (const ScanPair& truth, const Prediction& prediction);

}  // namespace pcl_crf
