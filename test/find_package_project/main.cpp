// A program written by a pcl_crf user: it only sees the installed package.
#include <pcl_crf/core/scan_pair.h>

#include <cmath>
#include <iostream>

int
main ()
{
  const pcl_crf::Rigid2d T = pcl_crf::makeRigid2d (1.0, 2.0, 0.5);
  const Eigen::Vector3d xyt = pcl_crf::toXYTheta (T);
  if (std::abs (xyt.z () - 0.5) > 1e-12)
    return 1;
  std::cout << "outside project OK" << std::endl;
  return 0;
}
