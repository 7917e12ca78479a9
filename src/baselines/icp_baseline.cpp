#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/core/planar_transform.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

void
checkOptions (const ScanPair& pair, const IcpBaselineOptions& options)
{
  if (pair.source.cols () == 0 || pair.target.cols () == 0)
    throw std::invalid_argument ("[pcl_crf::runIcpBaseline] the source or target scan is empty");
  if (!pair.source.allFinite () || !pair.target.allFinite ())
    throw std::invalid_argument ("[pcl_crf::runIcpBaseline] the scans hold NaN or infinite points");
  const std::string problem = odometryProblem (pair.odometry);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::runIcpBaseline] " + problem);
  // PCL's points are single precision: a squared distance must stay finite in float.
  const auto within = [] (const auto& values) { return values.cwiseAbs ().maxCoeff () <= kMaxCoordinate; };
  if (!within (pair.source) || !within (pair.target) || !within (pair.odometry.T_source_target.translation ()))
    throw std::invalid_argument ("[pcl_crf::runIcpBaseline] coordinates and odometry beyond 1e18 m do not fit "
                                 "PCL's single-precision points");
  if (options.max_iterations <= 0 || !(options.max_correspondence_distance > 0.0) ||
      !(options.outlier_distance > 0.0) || !(options.transformation_epsilon >= 0.0))
    throw std::invalid_argument ("[pcl_crf::runIcpBaseline] iterations and distances must be positive");
}

std::vector<int>
nearestNeighbourMatches (const Eigen::Matrix2Xd& source, const Rigid2d& T, const Cloud::Ptr& target,
                         double outlier_distance)
{
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud (target);
  std::vector<int> matches (source.cols (), kNoMatch);
  pcl::Indices index (1);
  std::vector<float> squared_distance (1);
  const double max_squared = outlier_distance * outlier_distance;
  for (Eigen::Index i = 0; i < source.cols (); ++i) {
    const Eigen::Vector2d q = T * source.col (i);
    pcl::PointXYZ query (static_cast<float> (q.x ()), static_cast<float> (q.y ()), 0.0f);
    if (tree.nearestKSearch (query, 1, index, squared_distance) == 1 && squared_distance[0] <= max_squared)
      matches[i] = index[0];
  }
  return matches;
}

}  // namespace

Prediction
runIcpBaseline (const ScanPair& pair, const IcpBaselineOptions& options)
{
  checkOptions (pair, options);
  Cloud::Ptr source (new Cloud), target (new Cloud), aligned (new Cloud);
  fromMatrix2X (pair.source, *source);
  fromMatrix2X (pair.target, *target);

  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setTransformationEstimation (
      pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>> ());
  icp.setInputSource (source);
  icp.setInputTarget (target);
  icp.setMaximumIterations (options.max_iterations);
  icp.setMaxCorrespondenceDistance (options.max_correspondence_distance);
  icp.setTransformationEpsilon (options.transformation_epsilon);
  const Rigid2d guess = pair.odometry.T_source_target.inverse ();
  icp.align (*aligned, toMatrix4<float> (guess));
  const Rigid2d T_target_source = icp.hasConverged () ? toRigid2d (icp.getFinalTransformation ()) : guess;

  Prediction prediction;
  prediction.source_match = nearestNeighbourMatches (pair.source, T_target_source, target, options.outlier_distance);
  prediction.source_cluster.assign (pair.source.cols (), 0);
  prediction.cluster_motions = {T_target_source};
  prediction.static_cluster = 0;
  prediction.T_source_target = T_target_source.inverse ();
  return prediction;
}

}  // namespace pcl_crf
