#include <pcl_crf/metrics/motion_error.h>

#include <cmath>
#include <limits>

namespace pcl_crf {

MotionError
computeMotionError (const Rigid2d& T_estimated, const Rigid2d& T_true)
{
  const Rigid2d residual = T_estimated.inverse () * T_true;
  return {std::abs (rotationAngle (residual)), residual.translation ().norm ()};
}

MotionError
computeEgoMotionError (const ScanPair& truth, const Rigid2d& T_source_target)
{
  for (const auto& object : truth.objects)
    if (object.is_static)
      // The static world moves by the inverse of the sensor's motion.
      return computeMotionError (T_source_target, object.T_target_source.inverse ());
  const double nan = std::numeric_limits<double>::quiet_NaN ();
  return {nan, nan};
}

}  // namespace pcl_crf
