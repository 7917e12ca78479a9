#pragma once

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

namespace pcl_crf {

/** \brief Parameters of the PCL ICP baseline (pcl::IterativeClosestPoint with
 *  pcl::registration::TransformationEstimation2D).
 */
struct IcpBaselineOptions
{
  /** ICP iterations at most (PCL: setMaximumIterations). */
  int max_iterations = 100;
  /** pairs farther apart are ignored while aligning [m] (PCL: setMaxCorrespondenceDistance). */
  double max_correspondence_distance = 0.5;
  /** stop when the transform changes less than this (PCL: setTransformationEpsilon). */
  double transformation_epsilon = 1e-12;
  /** after alignment, a source point whose nearest target point is farther than
   *  this is reported as an outlier (no match) [m]. */
  double outlier_distance = 0.3;
};

/** \brief Aligns the pair's source scan to its target with PCL ICP from the
 *  odometry guess and reports the result in the common Prediction form: the
 *  nearest-neighbour association after alignment (kNoMatch beyond
 *  \c outlier_distance), a single cluster holding every point with the ICP
 *  motion, and that motion's inverse as the ego motion.
 *  \throws std::invalid_argument for empty scans or nonsense options.
 */
Prediction
runIcpBaseline (const ScanPair& pair, const IcpBaselineOptions& options = {});

}  // namespace pcl_crf
