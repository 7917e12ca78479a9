#pragma once

#include <pcl_crf/joint/joint_estimation.h>
#include <pcl_crf/joint/joint_model.h>

#include <pcl/correspondence.h>
#include <pcl/point_types.h>
#include <pcl/PointIndices.h>
#include <pcl/registration/registration.h>

#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Joint scan matching, moving-object detection and motion estimation as a
 *  pcl::Registration (joint::estimateJoint behind PCL's interface).
 *
 *  align() associates the source scan with the target scan, clusters the source
 *  points by their rigid motion and estimates every cluster's motion; the final
 *  transformation is the static world's motion (it maps source points into the
 *  target frame, the inverse of the sensor's own motion), and hasConverged() is true
 *  when a static cluster associated with at least three target points was found (fewer
 *  do not determine the sensor's motion: a target that does not overlap the source, or
 *  a scan far from the guess, gave back the guess unchanged as the estimate). Points with non-finite x or y, and points at
 *  the sensor itself (x = y = 0, a driver's range of 0 for a beam without a return), are skipped (all
 *  indices refer to the input clouds). The guess given to align() is the odometry
 *  (T_target_source) unless setOdometry() was called.
 *
 *  \code
 *  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> joint;
 *  joint.loadModel ("data/models/joint.model");
 *  joint.setInputSource (source);
 *  joint.setInputTarget (target);
 *  pcl::PointCloud<pcl::PointXYZ> aligned;
 *  joint.align (aligned, odometry_guess);
 *  if (joint.hasConverged ())
 *    for (const pcl::PointIndices& cluster : joint.getClusters ()) ...
 *  \endcode
 */
template <typename PointSource, typename PointTarget, typename Scalar = float>
class JointCRFEstimator : public pcl::Registration<PointSource, PointTarget, Scalar>
{
public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using Ptr = pcl::shared_ptr<JointCRFEstimator<PointSource, PointTarget, Scalar>>;
  using ConstPtr = pcl::shared_ptr<const JointCRFEstimator<PointSource, PointTarget, Scalar>>;

  JointCRFEstimator ();

  /** Not copyable or movable, as pcl::IterativeClosestPoint: a copy would share
   *  pcl::Registration's search trees and correspondences with the original (a copy's
   *  align () on another target left the original's getFitnessScore () measured
   *  against that target). Hold one through Ptr to pass it around. */
  JointCRFEstimator (const JointCRFEstimator&) = delete;
  JointCRFEstimator (JointCRFEstimator&&) = delete;
  JointCRFEstimator&
  operator= (const JointCRFEstimator&) = delete;
  JointCRFEstimator&
  operator= (JointCRFEstimator&&) = delete;
  ~JointCRFEstimator () override = default;

  /** \brief Uses a trained model (joint::trainJointModel or pcl_crf_train --method joint). */
  void
  setModel (const joint::JointModel& model) { model_ = model; }
  const joint::JointModel&
  getModel () const { return model_; }

  /** \brief Loads a model file; false (and PCL_ERROR naming the problem) when it cannot. */
  bool
  loadModel (const std::string& path);

  /** \brief Runtime settings (inference schedule, rounds, cluster removal). */
  void
  setParameters (const joint::JointParameters& parameters) { parameters_ = parameters; }
  const joint::JointParameters&
  getParameters () const { return parameters_; }

  /** \brief The sensor's measured motion (its pose at the target time in the source
   *  frame, 4x4) and the covariance of (x [m], y [m], yaw [rad]); used for the
   *  candidates and to pick the static cluster. Without it align()'s guess is used
   *  with setGuessCovariance()'s covariance. */
  void
  setOdometry (const Matrix4& T_source_target, const Eigen::Matrix3d& covariance);

  /** \brief Forgets setOdometry (): align ()'s guess is used again (the scan interval stays). */
  void
  clearOdometry () { has_odometry_ = false; }

  /** \brief Time from the source scan to the target scan [s] (0: unknown, the default),
   *  with or without odometry: no object is searched for farther than the model's top
   *  speed (SegmentMotionParameters::max_speed, 30 m/s) travels in that time. */
  void
  setScanInterval (double seconds) { odometry_.interval = seconds; }
  double
  getScanInterval () const { return odometry_.interval; }

  /** \brief The longest run of beams without a return that one surface may have
   *  dropped (SegmentMotionParameters::max_missing_returns; the shipped model's 10):
   *  raise it for a laser that drops long runs on dark surfaces; −1: any run. A value
   *  below −1 makes align() fail with an error naming it. */
  void
  setMaxMissingReturns (int beams) { model_.matcher.parameters.candidates.segments.max_missing_returns = beams; }
  int
  getMaxMissingReturns () const { return model_.matcher.parameters.candidates.segments.max_missing_returns; }

  /** \brief Covariance of align()'s guess when no odometry is set; default diag(0.25 m², 0.25 m², 0.05 rad²). */
  void
  setGuessCovariance (const Eigen::Matrix3d& covariance) { guess_covariance_ = covariance; }

  /** \brief pcl::Registration::align with the identity guess (see the overload below). */
  void
  align (PointCloudSource& output);

  /** \brief pcl::Registration::align, after checking that every index given with
   *  setIndices () is a point of the source cloud: PCL's align copies the indexed
   *  points before any estimator runs, and would read past the cloud. An index outside
   *  it gives PCL_ERROR naming it, no result and hasConverged () == false. Only the
   *  indexed points are estimated, and \a output holds them moved by the static world's
   *  motion. The chains follow the beam order, counter-clockwise as the model learned:
   *  the points' order when it is one (a laser's), backwards when they go clockwise,
   *  else the points sorted by bearing (pcl_crf::beamOrder (): a cloud through
   *  pcl::VoxelGrid, say). */
  void
  align (PointCloudSource& output, const Matrix4& guess);

  /** \brief The associations of the last align() (see joint::JointResult::source_match):
   *  (source index, target index, squared distance after the static motion), by source
   *  index. Outliers have none. */
  const pcl::Correspondences&
  getCorrespondences () const { return correspondences_; }

  /** \brief The clusters of the last align(), largest first (outliers excluded), each
   *  one's indices increasing. */
  const std::vector<pcl::PointIndices>&
  getClusters () const { return clusters_; }

  /** \brief Each cluster's motion, mapping its source points into the target frame. */
  const std::vector<Matrix4, Eigen::aligned_allocator<Matrix4>>&
  getClusterTransformations () const { return cluster_transformations_; }

  /** \brief Index in getClusters () of the static world, or −1. */
  int
  getStaticCluster () const { return result_.static_cluster; }

  /** \brief Source points in the outlier cluster, increasing. */
  const pcl::Indices&
  getOutliers () const { return outliers_; }

  /** \brief Outliers that moved away (joint::JointResult::moved_away): the target saw
   *  through where the static motion puts them, so they are not the static world; their
   *  motion is unknown. */
  const pcl::Indices&
  getMovedAway () const { return moved_away_; }

  /** \brief Everything the last align() found, in the core's frame-explicit form: its
   *  source point k is the source cloud's point getResultSourceIndices ()[k], its
   *  target point j the target cloud's getResultTargetIndices ()[j] (the finite points
   *  off the sensor, in beam order). */
  const joint::JointResult&
  getResult () const { return result_; }

  /** \brief The source cloud index of every source point of getResult (). */
  const std::vector<int>&
  getResultSourceIndices () const { return result_source_index_; }

  /** \brief The target cloud index of every target point of getResult (). */
  const std::vector<int>&
  getResultTargetIndices () const { return result_target_index_; }

protected:
  void
  computeTransformation (PointCloudSource& output, const Matrix4& guess) override;

  using Base::converged_;
  using Base::fake_indices_;
  using Base::final_transformation_;
  using Base::indices_;
  using Base::input_;
  using Base::reg_name_;
  using Base::target_;
  using Base::transformation_;

private:
  void
  clearResults ();
  /** The indexed source points (every point without setIndices ()) moved by \a T. */
  void
  moveSource (const Matrix4& T, PointCloudSource& output) const;
  /** The getters' results from result_ (of \a source and \a target, the scans it was estimated from). */
  void
  storeResults (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target);
  /** Distinct target points the static cluster's points are associated with in the last result. */
  int
  staticMatches () const;

  joint::JointModel model_;
  joint::JointParameters parameters_;
  bool has_odometry_ = false;
  Odometry odometry_;
  Eigen::Matrix3d guess_covariance_ = Eigen::Vector3d (0.25, 0.25, 0.05).asDiagonal ();
  joint::JointResult result_;
  std::vector<int> result_source_index_;
  std::vector<int> result_target_index_;
  pcl::Correspondences correspondences_;
  std::vector<pcl::PointIndices> clusters_;
  std::vector<Matrix4, Eigen::aligned_allocator<Matrix4>> cluster_transformations_;
  pcl::Indices outliers_;
  pcl::Indices moved_away_;
};

}  // namespace pcl_crf

#if !defined(PCL_NO_PRECOMPILE)
extern template class pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ, float>;
extern template class pcl_crf::JointCRFEstimator<pcl::PointXYZI, pcl::PointXYZI, float>;
extern template class pcl_crf::JointCRFEstimator<pcl::PointXYZL, pcl::PointXYZL, float>;
#else
#include <pcl_crf/impl/joint_crf_estimator.hpp>
#endif
