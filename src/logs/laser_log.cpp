#include <pcl_crf/logs/laser_log.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {

bool
samePose (const Rigid2d& a, const Rigid2d& b, double tolerance)
{
  const Rigid2d difference = a.inverse () * b;
  return difference.translation ().norm () < tolerance && std::abs (rotationAngle (difference)) < tolerance;
}

void
PoseTrack::append (double stamp, const Rigid2d& pose)
{
  if (!stamps.empty () && !(stamp > stamps.back ()))
    return;
  stamps.push_back (stamp);
  poses.push_back (pose);
}

bool
PoseTrack::interpolate (double t, Rigid2d& pose, double max_gap) const
{
  // Stamps rounded to nanoseconds (ROS) must still find the end samples.
  constexpr double kEndTolerance = 1e-6;
  if (stamps.empty () || !(t >= stamps.front () - kEndTolerance) || !(t <= stamps.back () + kEndTolerance))
    return false;
  t = std::min (std::max (t, stamps.front ()), stamps.back ());
  const auto upper = std::lower_bound (stamps.begin (), stamps.end (), t);
  const std::size_t k = static_cast<std::size_t> (upper - stamps.begin ());
  if (stamps[k] == t) {
    pose = poses[k];
    return true;
  }
  const double t0 = stamps[k - 1], t1 = stamps[k];
  if (t1 - t0 > max_gap)
    return false;
  const double s = (t - t0) / (t1 - t0);
  const Eigen::Vector3d a = toXYTheta (poses[k - 1]);
  const double turn = rotationAngle (poses[k - 1].inverse () * poses[k]);
  const Eigen::Vector2d xy = (1.0 - s) * poses[k - 1].translation () + s * poses[k].translation ();
  pose = makeRigid2d (xy.x (), xy.y (), a.z () + s * turn);
  return true;
}

std::size_t
countStampsNotAfterTheLast (const LaserLog& log)
{
  std::size_t count = 0;
  for (std::size_t k = 1; k < log.scans.size (); ++k)
    count += log.scans[k].stamp > log.scans[k - 1].stamp ? 0 : 1;
  return count;
}

}  // namespace pcl_crf
