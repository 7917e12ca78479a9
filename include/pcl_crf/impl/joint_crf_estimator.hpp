#pragma once

#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/core/planar_transform.h>
#include <pcl_crf/joint_crf_estimator.h>

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>

namespace pcl_crf {

template <typename PointSource, typename PointTarget, typename Scalar>
JointCRFEstimator<PointSource, PointTarget, Scalar>::JointCRFEstimator ()
{
  reg_name_ = "JointCRFEstimator";
}

template <typename PointSource, typename PointTarget, typename Scalar> bool
JointCRFEstimator<PointSource, PointTarget, Scalar>::loadModel (const std::string& path)
{
  try {
    model_ = joint::loadJointModel (path);
    return true;
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::loadModel] %s\n", reg_name_.c_str (), error.what ());
    return false;
  }
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::setOdometry (const Matrix4& T_source_target,
                                                                 const Eigen::Matrix3d& covariance)
{
  Odometry odometry;
  odometry.T_source_target = toRigid2dWarning (T_source_target, reg_name_ + "::setOdometry");
  odometry.covariance = covariance;
  const std::string problem = odometryProblem (odometry);
  if (!problem.empty ()) {
    PCL_ERROR ("[pcl_crf::%s::setOdometry] %s; odometry unchanged\n", reg_name_.c_str (), problem.c_str ());
    return;
  }
  odometry.interval = odometry_.interval;  // setScanInterval ()'s
  odometry_ = odometry;
  has_odometry_ = true;
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::clearResults ()
{
  result_ = joint::JointResult ();
  result_source_index_.clear ();
  result_target_index_.clear ();
  correspondences_.clear ();
  clusters_.clear ();
  cluster_transformations_.clear ();
  outliers_.clear ();
  moved_away_.clear ();
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::storeResults (const Eigen::Matrix2Xd& source,
                                                                  const Eigen::Matrix2Xd& target)
{
  const std::vector<int>& source_index = result_source_index_;
  const std::vector<int>& target_index = result_target_index_;
  const Rigid2d& T_static = result_.cluster_motions[result_.static_cluster];
  clusters_.resize (result_.cluster_motions.size ());
  for (std::size_t i = 0; i < result_.source_cluster.size (); ++i) {
    const int original = source_index[i];
    if (result_.source_cluster[i] == kOutlierCluster)
      outliers_.push_back (original);
    else
      clusters_[result_.source_cluster[i]].indices.push_back (original);
    const int j = result_.source_match[i];
    if (j != kNoMatch) {
      const double d2 = (T_static * source.col (i) - target.col (j)).squaredNorm ();
      correspondences_.emplace_back (original, target_index[j], static_cast<float> (d2));
    }
  }
  for (const Rigid2d& T : result_.cluster_motions)
    cluster_transformations_.push_back (toMatrix4<Scalar> (T));
  for (const int i : result_.moved_away)
    moved_away_.push_back (source_index[i]);
  // In cloud order, whatever order the chains read the cloud in (a clockwise or shuffled one).
  for (pcl::PointIndices& cluster : clusters_)
    std::sort (cluster.indices.begin (), cluster.indices.end ());
  std::sort (outliers_.begin (), outliers_.end ());
  std::sort (moved_away_.begin (), moved_away_.end ());
  detail::sortByQuery (correspondences_);
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::moveSource (const Matrix4& T, PointCloudSource& output) const
{
  // Normals turn with the points, as pcl::IterativeClosestPoint turns them.
  if constexpr (pcl::traits::has_normal_v<PointSource>) {
    if (fake_indices_)  // every point: keeps an organised cloud's width and height
      pcl::transformPointCloudWithNormals (*input_, output, T);
    else
      pcl::transformPointCloudWithNormals (*input_, *indices_, output, T);
  }
  else if (fake_indices_)
    pcl::transformPointCloud (*input_, output, T);
  else
    pcl::transformPointCloud (*input_, *indices_, output, T);
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::align (PointCloudSource& output)
{
  align (output, Matrix4::Identity ());
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::align (PointCloudSource& output, const Matrix4& guess)
{
  // Indices given with setIndices () (not PCL's own "every point") are checked here:
  // Base::align copies the points they name before computeTransformation runs, and
  // builds PCL's kd-tree of the target, which aborts on coordinates near 1e37.
  const std::string problem =
      inputProblem (fake_indices_ ? nullptr : indices_.get (), input_.get (), target_.get ());
  if (!problem.empty ()) {
    PCL_ERROR ("[pcl_crf::%s::align] %s.\n", reg_name_.c_str (), problem.c_str ());
    clearResults ();
    converged_ = false;
    return;
  }
  Base::align (output, guess);
}

template <typename PointSource, typename PointTarget, typename Scalar> void
JointCRFEstimator<PointSource, PointTarget, Scalar>::computeTransformation (PointCloudSource& output,
                                                                           const Matrix4& guess)
{
  clearResults ();
  converged_ = false;
  const Eigen::Matrix2Xd source = scanToMatrix2X (*input_, *indices_, result_source_index_);  // the indexed points
  const Eigen::Matrix2Xd target = scanToMatrix2X (*target_, result_target_index_);
  Odometry odometry = odometry_;
  if (!has_odometry_) {
    odometry.T_source_target = toRigid2dWarning (guess, reg_name_ + "::align").inverse ();
    odometry.covariance = guess_covariance_;
  }
  try {
    if (source.cols () == 0 || target.cols () == 0)
      throw std::invalid_argument (std::string ("The ") + (source.cols () == 0 ? "source" : "target") +
                                   " cloud has no finite point off the sensor (x = y = 0 is no return).");
    result_ = joint::estimateJoint (source, target, odometry, model_, parameters_);
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::computeTransformation] %s\n", reg_name_.c_str (), error.what ());
    clearResults ();
    // No estimate: the motion it would have started from, the odometry's when it was given.
    final_transformation_ = transformation_ =
        has_odometry_ ? toMatrix4<Scalar> (odometry.T_source_target.inverse ()) : guess;
    moveSource (final_transformation_, output);
    return;
  }
  if (result_.static_cluster >= 0)
    storeResults (source, target);
  final_transformation_ = transformation_ = toMatrix4<Scalar> (result_.T_source_target.inverse ());
  moveSource (final_transformation_, output);
  // Fewer than three target points associated with the static world do not over-determine
  // its motion: with none, the guess comes back unchanged, not estimated.
  constexpr int kLeastStaticMatches = 3;
  const int static_matches = staticMatches ();
  converged_ = result_.static_cluster >= 0 && static_matches >= kLeastStaticMatches;
  if (result_.static_cluster >= 0 && !converged_)
    PCL_WARN ("[pcl_crf::%s::computeTransformation] the static world is associated with %d target points: its "
              "motion is not estimated (hasConverged () is false)\n",
              reg_name_.c_str (), static_matches);
}

template <typename PointSource, typename PointTarget, typename Scalar> int
JointCRFEstimator<PointSource, PointTarget, Scalar>::staticMatches () const
{
  std::vector<int> targets;
  for (std::size_t i = 0; i < result_.source_cluster.size (); ++i)
    if (result_.source_cluster[i] == result_.static_cluster && result_.source_match[i] != kNoMatch)
      targets.push_back (result_.source_match[i]);
  std::sort (targets.begin (), targets.end ());
  return static_cast<int> (std::unique (targets.begin (), targets.end ()) - targets.begin ());
}

}  // namespace pcl_crf
