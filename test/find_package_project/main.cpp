// A program written by a pcl_crf user: it only sees the installed package.
#include <pcl_crf/baselines/icp_baseline.h>
#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/joint_crf_estimator.h>
#include <pcl_crf/metrics/pair_scores.h>

#include <pcl/point_types.h>

#include <cmath>
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
  std::cout << "outside project OK" << std::endl;
  return 0;
}
