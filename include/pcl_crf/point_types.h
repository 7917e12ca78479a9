#pragma once

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <cstdint>

namespace pcl_crf {

/** \brief A labelled source-scan point as stored in a dataset's source.pcd:
 *  position, ground-truth object id (\c label) and the index of the
 *  corresponding target point (\c match, -1 for none).
 */
struct EIGEN_ALIGN16 PointXYZLMatch
{
  PCL_ADD_POINT4D;
  std::uint32_t label;
  std::int32_t match;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/** \brief A source point as a method predicted it (prediction.pcd):
 *  position, predicted cluster (-1 = outlier cluster) and predicted match
 *  (-1 = none).
 */
struct EIGEN_ALIGN16 PointXYZClusterMatch
{
  PCL_ADD_POINT4D;
  std::int32_t cluster;
  std::int32_t match;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace pcl_crf

POINT_CLOUD_REGISTER_POINT_STRUCT (pcl_crf::PointXYZLMatch,
                                   (float, x, x)
                                   (float, y, y)
                                   (float, z, z)
                                   (std::uint32_t, label, label)
                                   (std::int32_t, match, match))

POINT_CLOUD_REGISTER_POINT_STRUCT (pcl_crf::PointXYZClusterMatch,
                                   (float, x, x)
                                   (float, y, y)
                                   (float, z, z)
                                   (std::int32_t, cluster, cluster)
                                   (std::int32_t, match, match))
