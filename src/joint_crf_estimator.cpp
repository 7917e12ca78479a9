#include <pcl_crf/impl/joint_crf_estimator.hpp>
#include <pcl_crf/joint_crf_estimator.h>

template class pcl_crf::JointCRFEstimator<pcl::PointXYZ, pcl::PointXYZ, float>;
template class pcl_crf::JointCRFEstimator<pcl::PointXYZI, pcl::PointXYZI, float>;
template class pcl_crf::JointCRFEstimator<pcl::PointXYZL, pcl::PointXYZL, float>;
