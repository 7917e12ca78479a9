#pragma once

#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/core/planar_transform.h>
#include <pcl_crf/crf_matcher.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <exception>
#include <utility>

namespace pcl_crf {

namespace detail {

/** \brief true when the target preparation depends on the same settings. */
inline bool
sameTargetSettings (const matching::MatchingParameters& a, const matching::MatchingParameters& b)
{
  return a.candidates.shape_position_scale == b.candidates.shape_position_scale &&
         a.candidates.segments.breakpoint_angle == b.candidates.segments.breakpoint_angle &&
         a.candidates.segments.range_noise == b.candidates.segments.range_noise &&
         a.training_beam_spacing == b.training_beam_spacing;
}

}  // namespace detail

template <typename PointSource, typename PointTarget, typename Scalar>
CRFMatcher<PointSource, PointTarget, Scalar>::CRFMatcher ()
{
  corr_name_ = "CRFMatcher";
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::setModel (const matching::CrfMatchingModel& model)
{
  model_ = model;
}

template <typename PointSource, typename PointTarget, typename Scalar> bool
CRFMatcher<PointSource, PointTarget, Scalar>::loadModel (const std::string& path)
{
  try {
    setModel (matching::loadModel (path));
    return true;
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::loadModel] %s\n", getClassName ().c_str (), error.what ());
    return false;
  }
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::setInitialGuess (const Matrix4& T_target_source)
{
  const double interval = guess_.interval;
  guess_ = matching::MotionGuess ();
  guess_.T_target_source = toRigid2dWarning (T_target_source, std::string (getClassName ()) + "::setInitialGuess");
  guess_.interval = interval;
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::setOdometry (const Odometry& odometry)
{
  const std::string problem = odometryProblem (odometry);
  if (!problem.empty ()) {
    PCL_ERROR ("[pcl_crf::%s::setOdometry] %s; guess unchanged\n", getClassName ().c_str (), problem.c_str ());
    return;
  }
  guess_ = matching::MotionGuess::fromOdometry (odometry);
}

template <typename PointSource, typename PointTarget, typename Scalar> typename CRFMatcher<PointSource, PointTarget, Scalar>::Matrix4
CRFMatcher<PointSource, PointTarget, Scalar>::getInitialGuess () const
{
  return toMatrix4<Scalar> (guess_.T_target_source);
}

template <typename PointSource, typename PointTarget, typename Scalar> typename CRFMatcher<PointSource, PointTarget, Scalar>::Matrix4
CRFMatcher<PointSource, PointTarget, Scalar>::getTransformation () const
{
  return toMatrix4<Scalar> (result_.T_target_source);
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::clearResults ()
{
  result_ = matching::MatchResult ();
  result_.T_target_source = guess_.T_target_source;
  source_xy_.resize (2, 0);
  source_index_.clear ();
  outliers_.clear ();
  candidates_.clear ();
  marginals_.clear ();
}

template <typename PointSource, typename PointTarget, typename Scalar> bool
CRFMatcher<PointSource, PointTarget, Scalar>::initCompute ()
{
  const char* method = "determineCorrespondences";
  if (!input_ || !target_) {
    PCL_ERROR ("[pcl_crf::%s::%s] No input %s cloud given: call setInput%s first.\n", getClassName ().c_str (), method,
               input_ ? "target" : "source", input_ ? "Target" : "Source");
    return false;
  }
  if (!model_.isTrained ()) {
    PCL_ERROR ("[pcl_crf::%s::%s] No trained model: call setModel or loadModel first.\n", getClassName ().c_str (),
               method);
    return false;
  }
  try {
    matching::validateParameters (model_.parameters);
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::%s] %s\n", getClassName ().c_str (), method, error.what ());
    return false;
  }
  if (!pcl::PCLBase<PointSource>::initCompute ())
    return false;
  // The target is checked when it is prepared again (a prepared one passed the check).
  const bool prepare_target = target_cloud_updated_ || !target_prepared_ ||
                              !detail::sameTargetSettings (target_prepared_parameters_, model_.parameters);
  std::string problem = inputProblem (indices_.get (), input_.get (), prepare_target ? target_.get () : nullptr);
  if (problem.empty () && prepare_target && target_indices_)
    problem = indicesProblem (*target_indices_, target_->size (), "target");
  if (!problem.empty ()) {
    PCL_ERROR ("[pcl_crf::%s::%s] %s.\n", getClassName ().c_str (), method, problem.c_str ());
    return false;
  }
  // The valid source points (the indices, or the whole cloud) in beam order.
  source_xy_ = scanToMatrix2X (*input_, *indices_, source_index_);
  if (source_index_.empty ()) {
    PCL_ERROR ("[pcl_crf::%s::%s] The source cloud has no finite point off the sensor (x = y = 0 is no return).\n", getClassName ().c_str (), method);
    return false;
  }
  if (prepare_target) {
    target_prepared_.reset ();
    const Eigen::Matrix2Xd target_xy = target_indices_ ? scanToMatrix2X (*target_, *target_indices_, target_index_)
                                                       : scanToMatrix2X (*target_, target_index_);
    if (target_xy.cols () == 0) {
      PCL_ERROR ("[pcl_crf::%s::%s] The target cloud has no finite point off the sensor (x = y = 0 is no return).\n", getClassName ().c_str (), method);
      return false;
    }
    target_prepared_ = std::make_shared<const matching::MatchingTarget> (
        matching::prepareMatchingTarget (target_xy, model_.parameters));
    target_prepared_parameters_ = model_.parameters;
    target_cloud_updated_ = false;
  }
  return true;
}

template <typename PointSource, typename PointTarget, typename Scalar> bool
CRFMatcher<PointSource, PointTarget, Scalar>::computeMatches ()
{
  try {
    result_ = matching::matchScans (source_xy_, *target_prepared_, guess_, model_);
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::determineCorrespondences] %s\n", getClassName ().c_str (), error.what ());
    clearResults ();
    return false;
  }
  candidates_.assign (input_->size (), pcl::Indices ());
  marginals_.assign (input_->size (), Eigen::VectorXd ());
  for (std::size_t k = 0; k < source_index_.size (); ++k) {
    const int i = source_index_[k];
    if (result_.matches[k] == kNoMatch)
      outliers_.push_back (i);
    pcl::Indices& states = candidates_[i];
    for (int c = 0; c < result_.candidates.count (static_cast<int> (k)); ++c)
      states.push_back (target_index_[result_.candidates.target (static_cast<int> (k), c)]);
    marginals_[i] = result_.marginals[k];
  }
  std::sort (outliers_.begin (), outliers_.end ());  // in cloud order, whatever order the chain read
  return true;
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::determineCorrespondences (pcl::Correspondences& correspondences,
                                                                        double max_distance)
{
  correspondences.clear ();
  clearResults ();
  if (!initCompute () || !computeMatches ())
    return;
  correspondences.reserve (source_index_.size ());
  pcl::Correspondence c;
  for (std::size_t k = 0; k < source_index_.size (); ++k)
    if (correspondenceOf (k, max_distance, c))
      correspondences.push_back (c);
  detail::sortByQuery (correspondences);
}

template <typename PointSource, typename PointTarget, typename Scalar> bool
CRFMatcher<PointSource, PointTarget, Scalar>::correspondenceOf (std::size_t k, double max_distance,
                                                               pcl::Correspondence& c) const
{
  const int j = result_.matches[k];
  if (j == kNoMatch)
    return false;
  const double squared =
      (guess_.T_target_source * source_xy_.col (k) - target_prepared_->points.col (j)).squaredNorm ();
  if (!(squared <= max_distance * max_distance))  // +inf for the default
    return false;
  c = pcl::Correspondence (source_index_[k], target_index_[j], static_cast<float> (squared));
  return true;
}

template <typename PointSource, typename PointTarget, typename Scalar> void
CRFMatcher<PointSource, PointTarget, Scalar>::determineReciprocalCorrespondences (
    pcl::Correspondences& correspondences, double max_distance)
{
  pcl::Correspondences forward;
  determineCorrespondences (forward, max_distance);
  correspondences.clear ();
  if (forward.empty ())
    return;
  matching::MatchResult backward;
  std::vector<int> source_first;  // per source chain position: its first copy, which backward names
  try {  // target → source with the inverse guess (no prior)
    matching::MotionGuess inverse;
    inverse.T_target_source = guess_.T_target_source.inverse ();
    matching::MatchingTarget source_as_target = matching::prepareMatchingTarget (source_xy_, model_.parameters);
    source_first = std::move (source_as_target.first_copy);
    backward = matching::matchScans (target_prepared_->points, source_as_target, inverse, model_);
  }
  catch (const std::exception& error) {
    PCL_ERROR ("[pcl_crf::%s::determineReciprocalCorrespondences] %s\n", getClassName ().c_str (), error.what ());
    return;
  }
  // Both directions in the chains' positions (k source, j target), then named by the clouds' indices.
  pcl::Correspondence c;
  for (std::size_t k = 0; k < source_index_.size (); ++k)
    if (correspondenceOf (k, max_distance, c) && backward.matches[result_.matches[k]] == source_first[k])
      correspondences.push_back (c);
  detail::sortByQuery (correspondences);
}

}  // namespace pcl_crf
