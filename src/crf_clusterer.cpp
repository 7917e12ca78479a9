#include <pcl_crf/crf_clusterer.h>
#include <pcl_crf/impl/crf_clusterer.hpp>

template class pcl_crf::CRFClusterer<pcl::PointXYZ>;
template class pcl_crf::CRFClusterer<pcl::PointXYZI>;
template class pcl_crf::CRFClusterer<pcl::PointXYZL>;
