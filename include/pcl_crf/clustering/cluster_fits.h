#pragma once

#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/core/rigid_fit.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace clustering {

/** \brief S x n weights with a single 1 per column: column i is the indicator of
 *  labels[i] (labels outside [0, cluster_count) give an all-zero column). */
Eigen::MatrixXd
oneHot (const std::vector<int>& labels, int cluster_count);

/** \brief S x n weights of MotionFit::OwnPoints: column i holds marginals(labels[i], i)
 *  in row labels[i] and zeros elsewhere (labels outside [0, S) give an all-zero column).
 *  \throws std::invalid_argument when labels and marginals differ in size. */
Eigen::MatrixXd
ownPointWeights (const Eigen::MatrixXd& marginals, const std::vector<int>& labels);

/** \brief Running sums of every cluster's weighted least-squares fit (Eq. (3)):
 *  cluster l holds pair i with weight weights(l, i).
 *  \param[in] weights S x n non-negative weights (hard: oneHot (); soft: marginals or
 *  ownPointWeights ())
 */
std::vector<RigidFitAccumulator>
accumulateFits (const PointPairs& pairs, const Eigen::MatrixXd& weights);

/** \brief The motion T_target_source of every accumulated cluster. */
std::vector<Rigid2d>
solveFits (const std::vector<RigidFitAccumulator>& fits);

}  // namespace clustering
}  // namespace pcl_crf
