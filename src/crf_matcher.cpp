// Explicit instantiations of pcl_crf::CRFMatcher for the common point types.
#include <pcl_crf/crf_matcher.h>
#include <pcl_crf/impl/crf_matcher.hpp>

template class pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ, float>;
template class pcl_crf::CRFMatcher<pcl::PointXYZI, pcl::PointXYZI, float>;
template class pcl_crf::CRFMatcher<pcl::PointXYZL, pcl::PointXYZL, float>;
