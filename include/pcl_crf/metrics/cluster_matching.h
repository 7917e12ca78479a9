#pragma once

#include <cstddef>
#include <vector>

namespace pcl_crf {

/** \brief One predicted cluster paired with one ground-truth object. */
struct ClusterObjectPair
{
  int cluster = -1;
  int object = -1;
  /** source points labelled \c cluster that belong to \c object. */
  std::size_t overlap = 0;
  /** source points labelled \c cluster. */
  std::size_t cluster_points = 0;
  /** source points that belong to \c object (whatever their cluster). */
  std::size_t object_points = 0;

  /** \brief true when the cluster holds more than half of the object's points
   *  and more than half of the cluster's points belong to the object: the
   *  object is then "correctly clustered".
   */
  bool
  isMutualMajority () const
  {
    return 2 * overlap > object_points && 2 * overlap > cluster_points;
  }
};

/** \brief A one-to-one pairing of predicted clusters with ground-truth objects.
 *
 *  How the pairing is made (matchClustersToObjects):
 *   1. count, over the source points, the overlap of every predicted cluster
 *      with every true object; points labelled kOutlierCluster (-1) belong to
 *      no cluster and are never paired;
 *   2. take the (cluster, object) with the largest overlap, ties broken by the
 *      smaller cluster label, then the smaller object id;
 *   3. pair them, remove both from further consideration, and repeat 2-3 while
 *      some remaining cluster and object still overlap (overlap > 0).
 *  A cluster left unpaired maps to no object (-1); so does an outlier point.
 */
struct ClusterObjectMatching
{
  /** the pairs in the order the greedy pass made them (largest overlap first). */
  std::vector<ClusterObjectPair> pairs;

  /** \brief The object paired with \a cluster, or -1 when it has none. */
  int
  objectOf (int cluster) const;
};

/** \brief Greedily pairs predicted clusters with true objects, see
 *  ClusterObjectMatching for the rule.
 *  \param[in] clusters predicted cluster label of every source point (-1: outlier)
 *  \param[in] objects true object id of every source point
 *  \throws std::invalid_argument when the lengths differ.
 */
ClusterObjectMatching
matchClustersToObjects (const std::vector<int>& clusters, const std::vector<int>& objects);

/** \brief Replaces every cluster label by the object it is paired with, and
 *  outliers and unpaired clusters by -1.
 */
std::vector<int>
mapClustersToObjects (const std::vector<int>& clusters, const ClusterObjectMatching& matching);

}  // namespace pcl_crf
