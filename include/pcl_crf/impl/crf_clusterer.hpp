#pragma once

#include <pcl_crf/clustering/clustering_model.h>
#include <pcl_crf/clustering/scan_clustering.h>
#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/core/planar_transform.h>
#include <pcl_crf/crf_clusterer.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <limits>

template <typename PointT> void
pcl_crf::CRFClusterer<PointT>::setOdometry (const Eigen::Matrix4f& T_source_target, const Eigen::Matrix3d& covariance)
{
  odometry_.T_source_target = toRigid2dWarning (T_source_target, std::string (getClassName ()) + "::setOdometry");
  odometry_.covariance = covariance;
  has_odometry_ = true;
}

template <typename PointT> void
pcl_crf::CRFClusterer<PointT>::setWeights (const Eigen::VectorXd& weights)
{
  if (weights.size () != clustering::kWeightCount || !weights.allFinite ())
  {
    PCL_ERROR ("[pcl_crf::%s::setWeights] expected %d finite weights, got %d%s; weights unchanged\n",
               getClassName ().c_str (), clustering::kWeightCount, static_cast<int> (weights.size ()),
               weights.allFinite () ? "" : " holding NaN or infinite values");
    return;
  }
  weights_ = weights;
}

template <typename PointT> bool
pcl_crf::CRFClusterer<PointT>::loadModel (const std::string& path)
{
  try
  {
    const clustering::CrfClusteringModel model = clustering::loadModel (path);
    weights_ = model.weights;
    parameters_.features = model.features;
    return true;
  }
  catch (const std::exception& error)
  {
    PCL_ERROR ("[pcl_crf::%s::loadModel] %s\n", getClassName ().c_str (), error.what ());
    return false;
  }
}

template <typename PointT> void
pcl_crf::CRFClusterer<PointT>::resetResults ()
{
  transformations_.clear ();
  sizes_.clear ();
  static_cluster_ = -1;
  marginals_.clear ();
  iterations_ = 0;
  converged_ = false;
}

template <typename PointT> bool
pcl_crf::CRFClusterer<PointT>::prepare (Eigen::Matrix2Xd& source, Eigen::Matrix2Xd& target, std::vector<int>& matches)
{
  if (!target_ || target_->empty () || input_->empty () || !correspondences_ || correspondences_->empty ())
  {
    PCL_ERROR ("[pcl_crf::%s::extract] set non-empty source and target clouds and correspondences\n",
               getClassName ().c_str ());
    return false;
  }
  if (weights_.size () != clustering::kWeightCount)
  {
    PCL_ERROR ("[pcl_crf::%s::extract] no weights: call setWeights () or loadModel ()\n", getClassName ().c_str ());
    return false;
  }
  const std::string problem = inputProblem (indices_.get (), input_.get (), target_.get ());
  if (!problem.empty ())
  {
    PCL_ERROR ("[pcl_crf::%s::extract] %s\n", getClassName ().c_str (), problem.c_str ());
    return false;
  }
  // Source: the finite points of indices_, in beam order; target: every point.
  source = scanToMatrix2X (*input_, *indices_, source_index_);
  std::vector<int> column (input_->size (), -1);
  for (std::size_t k = 0; k < source_index_.size (); ++k)
    column[source_index_[k]] = static_cast<int> (k);
  target.resize (2, static_cast<Eigen::Index> (target_->size ()));
  for (std::size_t j = 0; j < target_->size (); ++j)
    target.col (j) << (*target_)[j].x, (*target_)[j].y;
  return readCorrespondences (column, target, matches);
}

template <typename PointT> bool
pcl_crf::CRFClusterer<PointT>::readCorrespondences (const std::vector<int>& column, const Eigen::Matrix2Xd& target,
                                                    std::vector<int>& matches) const
{
  const std::string name = getClassName ();
  const auto kept = std::count_if (column.begin (), column.end (), [] (int c) { return c >= 0; });
  matches.assign (static_cast<std::size_t> (kept), kNoMatch);
  std::vector<float> best (matches.size (), std::numeric_limits<float>::infinity ());
  for (const pcl::Correspondence& c : *correspondences_)
  {
    const int query = static_cast<int> (c.index_query), match = static_cast<int> (c.index_match);
    if (query < 0 || query >= static_cast<int> (column.size ()) || match < 0 || match >= target.cols ())
    {
      PCL_ERROR ("[pcl_crf::%s::extract] correspondence %d -> %d is outside the clouds (%zu, %zu points)\n",
                 name.c_str (), query, match, input_->size (), target_->size ());
      return false;
    }
    const PointT& p = (*input_)[query];
    if (!std::isfinite (p.x) || !std::isfinite (p.y) || !target.col (match).allFinite ())
    {
      PCL_ERROR ("[pcl_crf::%s::extract] correspondence %d -> %d joins a NaN or infinite point\n", name.c_str (),
                 query, match);
      return false;
    }
    if (std::isnan (c.distance))  // it ranks the correspondences of a point
    {
      PCL_ERROR ("[pcl_crf::%s::extract] correspondence %d -> %d has a NaN distance\n", name.c_str (), query, match);
      return false;
    }
    const int k = column[query];  // −1: outside indices_, ignored
    if (k >= 0 && c.distance < best[k])
    {
      best[k] = c.distance;
      matches[k] = match;
    }
  }
  if (std::count_if (matches.begin (), matches.end (), [] (int m) { return m != kNoMatch; }) < 2)
  {
    PCL_ERROR ("[pcl_crf::%s::extract] at least two correspondences are needed to fit a motion\n", name.c_str ());
    return false;
  }
  return true;
}

template <typename PointT> void
pcl_crf::CRFClusterer<PointT>::extract (std::vector<pcl::PointIndices>& clusters)
{
  clusters.clear ();
  resetResults ();
  if (!input_ || !pcl::PCLBase<PointT>::initCompute ())
  {
    PCL_ERROR ("[pcl_crf::%s::extract] no source cloud: call setInputSource ()\n", getClassName ().c_str ());
    return;
  }
  Eigen::Matrix2Xd source, target;
  std::vector<int> matches;
  clustering::ScanClustering result;
  try
  {
    if (!(unassociated_break_distance_ > 0.0))
      throw std::invalid_argument ("the unassociated break distance must be > 0 [m]");
    if (!prepare (source, target, matches))
      return (void) pcl::PCLBase<PointT>::deinitCompute ();
    const auto unpaired = label_unassociated_ ? clustering::UnpairedLabelling::NearestSegmentNeighbour
                                              : clustering::UnpairedLabelling::Outlier;
    result = clustering::clusterScan (source, target, matches, weights_, parameters_,
                                      has_odometry_ ? &odometry_ : nullptr, unpaired, unassociated_break_distance_);
  }
  catch (const std::exception& error)
  {
    PCL_ERROR ("[pcl_crf::%s::extract] %s\n", getClassName ().c_str (), error.what ());
    return (void) pcl::PCLBase<PointT>::deinitCompute ();
  }
  storeResults (result, clusters);
  pcl::PCLBase<PointT>::deinitCompute ();
}

template <typename PointT> void
pcl_crf::CRFClusterer<PointT>::storeResults (const clustering::ScanClustering& result,
                                             std::vector<pcl::PointIndices>& clusters)
{
  const std::vector<int>& cloud_index = source_index_;  // of every scan column (prepare ())
  clusters.resize (result.motions.size ());
  for (std::size_t k = 0; k < result.source_cluster.size (); ++k)
    if (result.source_cluster[k] >= 0)
      clusters[result.source_cluster[k]].indices.push_back (cloud_index[k]);
  for (pcl::PointIndices& cluster : clusters)  // in cloud order, whatever order the chain read
    std::sort (cluster.indices.begin (), cluster.indices.end ());
  marginals_.assign (input_->size (), Eigen::VectorXd ());
  for (std::size_t k = 0; k < result.pairs.size (); ++k)
    marginals_[cloud_index[result.pairs.source_index[k]]] = result.marginals.col (static_cast<Eigen::Index> (k));
  for (std::size_t c = 0; c < clusters.size (); ++c)
  {
    clusters[c].header = input_->header;
    sizes_.push_back (static_cast<int> (clusters[c].indices.size ()));
    Eigen::Matrix4f T = Eigen::Matrix4f::Identity ();
    T.topLeftCorner<2, 2> () = result.motions[c].linear ().cast<float> ();
    T.topRightCorner<2, 1> () = result.motions[c].translation ().cast<float> ();
    transformations_.push_back (T);
  }
  static_cluster_ = result.static_cluster;
  iterations_ = result.iterations;
  converged_ = result.converged;
}
