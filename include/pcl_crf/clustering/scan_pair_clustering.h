#pragma once

#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/crf/chain_features.h>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief What a clustering reports for source points without an association (no node). */
enum class UnpairedLabelling
{
  /** kOutlierCluster: the clustering says nothing about them. */
  Outlier,
  /** the cluster of the nearest clustered point of the same distance segment, or the
   *  static cluster for segments without any (see completeLabels ()). */
  NearestSegmentNeighbour
};

/** \brief A clustering of point pairs as a Prediction of the whole scan pair.
 *
 *  \code
 *  const pcl_crf::Prediction prediction = pcl_crf::clustering::makePrediction (
 *      pair, pairs, result.labels, result.motions, result.static_cluster,
 *      pcl_crf::clustering::UnpairedLabelling::NearestSegmentNeighbour, 0.5);
 *  \endcode
 *  \param[in] pair the scan pair (its source scan and odometry are read)
 *  \param[in] pairs the clustered pairs (nodes)
 *  \param[in] labels cluster of every node, in [0, motions.size ())
 *  \param[in] motions T_target_source of every cluster
 *  \param[in] static_cluster the static world, or −1 (the odometry is then the ego motion)
 *  \param[in] unpaired how source points without a node are labelled
 *  \param[in] break_distance segment gap for NearestSegmentNeighbour [m]
 *  \return source_cluster, cluster_motions, static_cluster and T_source_target (the
 *  inverse of the static motion) filled; source_match is left empty (the caller
 *  adds the associations when its method made them).
 */
Prediction
makePrediction (const ScanPair& pair, const PointPairs& pairs, const std::vector<int>& labels,
                const std::vector<Rigid2d>& motions, int static_cluster, UnpairedLabelling unpaired,
                double break_distance);

/** \brief The training chain of a labelled pair: its true associations as nodes,
 *  labelled with their true objects (see makeTrainingChain ()).
 *  \throws std::invalid_argument when the pair has no truth.
 */
crf::LabelledChain
trainingChain (const ScanPair& pair, const FeatureOptions& options = {});

/** \brief The training chain of a labelled pair over other associations (those an
 *  association method gives, wrong ones included): every associated source point is
 *  a node labelled with its true object, so the weights learn how such associations
 *  look.
 *  \param[in] associations per source point: target index or kNoMatch
 *  \throws std::invalid_argument when the pair has no truth or the associations do not fit.
 */
crf::LabelledChain
trainingChain (const ScanPair& pair, const std::vector<int>& associations, const FeatureOptions& options = {});

/** \brief Distinct objects among the associated source points of a pair. */
int
associatedObjectCount (const ScanPair& pair);

}  // namespace clustering
}  // namespace pcl_crf
