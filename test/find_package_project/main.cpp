// A program written by a pcl_crf user: it only sees the installed package.
#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/joint_crf_estimator.h>
#include <pcl_crf/metrics/pair_scores.h>

#include <pcl/point_types.h>

#include <cmath>
#include <string>
#include <iostream>

int
main ()
{
  // A square room seen from two poses 0.3 m apart.
  pcl::PointCloud<pcl::PointXYZ> room;
  for (int k = 0; k < 200; ++k) {
    const double t = k / 50.0;
    const int side = k / 50;
    const double u = t - side;
    const double x = side == 0 ? 4 * u - 2 : side == 1 ? 2 : side == 2 ? 2 - 4 * u : -2;
    const double y = side == 0 ? -2 : side == 1 ? 4 * u - 2 : side == 2 ? 2 : 2 - 4 * u;
    room.push_back (pcl::PointXYZ (static_cast<float> (x), static_cast<float> (y), 0.0f));
  }
  pcl_crf::ScanPair pair;
  pair.source = pcl_crf::toMatrix2X (room);
  const pcl_crf::Rigid2d truth = pcl_crf::makeRigid2d (0.3, 0.0, 0.02);
  pair.target = truth * pair.source;
  pair.odometry.T_source_target = truth.inverse ();
  const pcl_crf::Prediction prediction = pcl_crf::runIcpBaseline (pair);
  const double error = (prediction.cluster_motions[0].inverse () * truth).translation ().norm ();
  if (!(error < 1e-3)) {
    std::cout << "ICP error too large: " << error << std::endl;
    return 1;
  }
  // The joint estimator links from the package too (its explicit instantiations);
  // without a model it reports the problem and does not converge.
  pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ> joint;
  joint.setInputSource (room.makeShared ());
  joint.setInputTarget (room.makeShared ());
  pcl::PointCloud<pcl::PointXYZ> aligned;
  joint.align (aligned);
  if (joint.hasConverged ()) {
    std::cout << "an untrained JointCRFEstimator must not converge" << std::endl;
    return 1;
  }
  // With the installed joint model (pcl_crf_MODELS_DIR) and the true motion as the
  // guess it finds the motion: the final transformation maps the source into the target.
  joint.loadModel (std::string (PCL_CRF_MODELS_DIR) + "/joint.model");
  pcl::PointCloud<pcl::PointXYZ> moved;
  for (const auto& p : pair.target.colwise ())
    moved.push_back (pcl::PointXYZ (static_cast<float> (p.x ()), static_cast<float> (p.y ()), 0.0f));
  joint.setInputTarget (moved.makeShared ());
  Eigen::Matrix4f guess = Eigen::Matrix4f::Identity ();
  guess.topLeftCorner<2, 2> () = truth.linear ().cast<float> ();
  guess.block<2, 1> (0, 3) = truth.translation ().cast<float> ();
  joint.align (aligned, guess);
  const Eigen::Matrix4f found = joint.getFinalTransformation ();
  const double motion_error = std::hypot (found (0, 3) - 0.3, found (1, 3));
  if (!joint.hasConverged () || !(motion_error < 0.01)) {
    std::cout << "the installed joint model: converged " << joint.hasConverged () << ", motion error "
              << motion_error << std::endl;
    return 1;
  }
  std::cout << "outside project OK" << std::endl;
  return 0;
}
