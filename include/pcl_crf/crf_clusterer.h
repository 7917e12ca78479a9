#pragma once

#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/core/scan_pair.h>

#include <pcl/PointIndices.h>
#include <pcl/correspondence.h>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <Eigen/StdVector>

#include <memory>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief CRF-Clustering (Tipaldi & Ramos, "Motion Clustering and Estimation with
 *  Conditional Random Fields", IROS 2009): groups associated points of two 2D laser
 *  scans by their rigid motion and estimates each group's motion, the static world
 *  among them.
 *
 *  Input: the source scan (earlier) and target scan (later), each in its own sensor
 *  frame (the CRF is a chain along the source scan: in the points' order when it is a
 *  beam order counter-clockwise, backwards when clockwise, else sorted by bearing,
 *  pcl_crf::beamOrder ()), and point correspondences (index_query = source point, index_match = target point;
 *  from any association method). Only x and y are used; a source point at the sensor
 *  itself (x = y = 0, a driver's range of 0 for a beam without a return) is left out of
 *  the chain, as a point outside setIndices () is. Output, like
 *  pcl::EuclideanClusterExtraction: clusters of source point indices, largest first,
 *  plus per cluster its rigid motion T_target_source (maps source-frame points into the
 *  target frame), its size and whether it is the static world, and per source point
 *  its cluster probabilities.
 *
 *  \code
 *  pcl_crf::CRFClusterer<pcl::PointXYZ> clusterer;
 *  clusterer.setInputSource (source);                 // a laser scan
 *  clusterer.setInputTarget (target);
 *  clusterer.setCorrespondences (correspondences);
 *  clusterer.setOdometry (T_source_target, covariance);
 *  if (!clusterer.loadModel ("data/models/crf-t.model"))
 *    return;
 *  std::vector<pcl::PointIndices> clusters;
 *  clusterer.extract (clusters);
 *  const Eigen::Matrix4f& world_motion = clusterer.getTransformations ()[clusterer.getStaticCluster ()];
 *  \endcode
 */
template <typename PointT>
class CRFClusterer : public pcl::PCLBase<PointT>
{
public:
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudPtr = typename PointCloud::Ptr;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;
  using Ptr = std::shared_ptr<CRFClusterer<PointT>>;
  using ConstPtr = std::shared_ptr<const CRFClusterer<PointT>>;
  using TransformationVector = std::vector<Eigen::Matrix4f, Eigen::aligned_allocator<Eigen::Matrix4f>>;

  CRFClusterer () = default;

  /** \brief The source scan (a laser scan; see the class comment for its order). */
  void
  setInputSource (const PointCloudConstPtr& cloud) { pcl::PCLBase<PointT>::setInputCloud (cloud); }

  PointCloudConstPtr
  getInputSource () const { return input_; }

  /** \brief The target scan. */
  void
  setInputTarget (const PointCloudConstPtr& cloud) { target_ = cloud; }

  PointCloudConstPtr
  getInputTarget () const { return target_; }

  /** \brief Source → target correspondences; a source point with several keeps the one
   *  of smallest distance. */
  void
  setCorrespondences (const pcl::CorrespondencesConstPtr& correspondences) { correspondences_ = correspondences; }

  pcl::CorrespondencesConstPtr
  getCorrespondences () const { return correspondences_; }

  /** \brief The sensor's motion: its pose at the target time in the source frame (only
   *  x, y and yaw are used) with the covariance of (x [m], y [m], yaw [rad]). Without
   *  odometry the largest cluster is taken as the static world. */
  void
  setOdometry (const Eigen::Matrix4f& T_source_target, const Eigen::Matrix3d& covariance);

  /** \brief Forgets the odometry. */
  void
  clearOdometry () { has_odometry_ = false; }

  bool
  hasOdometry () const { return has_odometry_; }

  /** \brief The CRF weights [w_spacing_residual, w_beam_residual, w_neighbour,
   *  w_weighted_neighbour, w_stiffness] (clustering::kWeightCount finite values;
   *  otherwise PCL_ERROR and the weights are unchanged). */
  void
  setWeights (const Eigen::VectorXd& weights);

  const Eigen::VectorXd&
  getWeights () const { return weights_; }

  /** \brief Reads the weights and feature settings from a model file (pcl_crf_train
   *  writes them); false after a PCL_ERROR when the file is missing or invalid. */
  bool
  loadModel (const std::string& path);

  /** \brief Gap that starts a new initial cluster [m] (> 0); default 0.5. */
  void
  setSegmentBreakDistance (double distance) { parameters_.segment_break_distance = distance; }

  double
  getSegmentBreakDistance () const { return parameters_.segment_break_distance; }

  /** \brief Longest initial cluster [points] (≤ 0: no cap); default 20. */
  void
  setMaxSegmentPoints (int points) { parameters_.max_segment_points = points; }

  int
  getMaxSegmentPoints () const { return parameters_.max_segment_points; }

  /** \brief Most rounds of belief propagation and refit (≥ 1); default 20. */
  void
  setMaximumIterations (int iterations) { parameters_.max_iterations = iterations; }

  int
  getMaximumIterations () const { return parameters_.max_iterations; }

  /** \brief Average N_eff above which a cluster is merged away [clusters] (> 1); default 1.7. */
  void
  setMaxAverageEffectiveClusters (double neff) { parameters_.max_average_neff = neff; }

  double
  getMaxAverageEffectiveClusters () const { return parameters_.max_average_neff; }

  /** \brief What the N_eff merge test reads; default clustering::MergeEvidence::Local. */
  void
  setMergeEvidence (clustering::MergeEvidence evidence) { parameters_.merge_evidence = evidence; }

  clustering::MergeEvidence
  getMergeEvidence () const { return parameters_.merge_evidence; }

  /** \brief Which pairs refit each cluster's motion; default clustering::MotionFit::Marginals. */
  void
  setMotionFit (clustering::MotionFit fit) { parameters_.motion_fit = fit; }

  clustering::MotionFit
  getMotionFit () const { return parameters_.motion_fit; }

  /** \brief Smallest neighbour distance in the weighted neighbour feature [m] (> 0);
   *  default 0.01. Part of the model: loadModel () sets it, change it only with weights
   *  learned that way. */
  void
  setMinNeighbourDistance (double distance) { parameters_.features.min_neighbour_distance = distance; }

  double
  getMinNeighbourDistance () const { return parameters_.features.min_neighbour_distance; }

  /** \brief Smallest sampling distance and range in the relative distance features [m]
   *  (> 0); default 0.01. Part of the model, like setMinNeighbourDistance (). */
  void
  setMinSpacing (double spacing) { parameters_.features.min_spacing = spacing; }

  double
  getMinSpacing () const { return parameters_.features.min_spacing; }

  /** \brief Most clusters a point considers (beam pruning) [clusters] (≥ 1); default 5. */
  void
  setMaxStates (int states) { parameters_.max_states = states; }

  int
  getMaxStates () const { return parameters_.max_states; }

  /** \brief Clusters this far below a point's best local log-potential are pruned [nats] (> 0); default 30. */
  void
  setPruningMargin (double margin) { parameters_.pruning_margin = margin; }

  double
  getPruningMargin () const { return parameters_.pruning_margin; }

  /** \brief true: points without a correspondence join the cluster of the nearest
   *  clustered point of their distance segment (else the static world); false: they
   *  are in no cluster. Default false. */
  void
  setLabelUnassociated (bool label) { label_unassociated_ = label; }

  bool
  getLabelUnassociated () const { return label_unassociated_; }

  /** \brief With setLabelUnassociated (true): the gap between consecutive source points
   *  that ends the segment within which a cluster spreads to points without a
   *  correspondence [m] (> 0); default 0.5. */
  void
  setUnassociatedBreakDistance (double distance) { unassociated_break_distance_ = distance; }

  double
  getUnassociatedBreakDistance () const { return unassociated_break_distance_; }

  /** \brief Clusters the scans. \param[out] clusters source point indices per cluster,
   *  largest first; empty after a PCL_ERROR on bad input. */
  void
  extract (std::vector<pcl::PointIndices>& clusters);

  /** \brief T_target_source of every extracted cluster (z and roll/pitch identity). */
  const TransformationVector&
  getTransformations () const { return transformations_; }

  /** \brief Number of source points of every extracted cluster. */
  const std::vector<int>&
  getClusterSizes () const { return sizes_; }

  /** \brief Index of the static-world cluster, −1 when there is none. */
  int
  getStaticCluster () const { return static_cluster_; }

  /** \brief true when extracted cluster \a cluster is the static world. */
  bool
  isStatic (int cluster) const { return cluster == static_cluster_ && cluster >= 0; }

  /** \brief Per source point, the probability of each extracted cluster (empty for
   *  points without a correspondence). */
  const std::vector<Eigen::VectorXd>&
  getMarginals () const { return marginals_; }

  /** \brief Rounds the last extract () ran, and whether it converged. */
  int
  getIterations () const { return iterations_; }

  bool
  hasConverged () const { return converged_; }

protected:
  std::string
  getClassName () const { return "CRFClusterer"; }

private:
  /** Checks the input and fills \a source, \a target, \a matches; false after a PCL_ERROR. */
  bool
  prepare (Eigen::Matrix2Xd& source, Eigen::Matrix2Xd& target, std::vector<int>& matches);

  /** The nearest valid correspondence of every kept source point (\a column: cloud
   *  index → source column or −1); false after a PCL_ERROR. */
  bool
  readCorrespondences (const std::vector<int>& column, const Eigen::Matrix2Xd& target,
                       std::vector<int>& matches) const;

  /** Copies a clustering of the scan columns into the cloud-indexed results. */
  void
  storeResults (const clustering::ScanClustering& result, std::vector<pcl::PointIndices>& clusters);

  /** Clears every result. */
  void
  resetResults ();

  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;

  PointCloudConstPtr target_;
  /** the cloud index of every source scan column (prepare ()). */
  std::vector<int> source_index_;
  pcl::CorrespondencesConstPtr correspondences_;
  Odometry odometry_;
  bool has_odometry_ = false;
  Eigen::VectorXd weights_;
  clustering::CrfClusteringParameters parameters_;
  bool label_unassociated_ = false;
  double unassociated_break_distance_ = 0.5;

  TransformationVector transformations_;
  std::vector<int> sizes_;
  int static_cluster_ = -1;
  std::vector<Eigen::VectorXd> marginals_;
  int iterations_ = 0;
  bool converged_ = false;
};

}  // namespace pcl_crf

#ifdef PCL_NO_PRECOMPILE
#include <pcl_crf/impl/crf_clusterer.hpp>
#else
extern template class pcl_crf::CRFClusterer<pcl::PointXYZ>;
extern template class pcl_crf::CRFClusterer<pcl::PointXYZI>;
extern template class pcl_crf::CRFClusterer<pcl::PointXYZL>;
#endif
