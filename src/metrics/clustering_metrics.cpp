#include <pcl_crf/metrics/clustering_metrics.h>
#include <pcl_crf/metrics/motion_error.h>

#include <limits>
#include <set>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN ();

/** Running mean of the rotation and translation errors of a group of objects. */
struct ErrorMean
{
  double rotation_sum = 0.0;
  double translation_sum = 0.0;
  int count = 0;

  void
  add (const MotionError& error)
  {
    rotation_sum += error.rotation;
    translation_sum += error.translation;
    ++count;
  }

  double
  rotation () const { return count == 0 ? kNaN : rotation_sum / count; }

  double
  translation () const { return count == 0 ? kNaN : translation_sum / count; }
};

const Rigid2d&
clusterMotion (const Prediction& prediction, int cluster)
{
  if (cluster < 0 || static_cast<std::size_t> (cluster) >= prediction.cluster_motions.size ())
    throw std::invalid_argument ("[pcl_crf::computeObjectMotionErrors] cluster " +
                                 std::to_string (cluster) +
                                 " has no motion: cluster_motions holds " +
                                 std::to_string (prediction.cluster_motions.size ()));
  return prediction.cluster_motions[cluster];
}

const ObjectTruth&
objectTruth (const ScanPair& truth, int id)
{
  const int index = truth.objectIndex (id);
  if (index < 0)
    throw std::invalid_argument ("[pcl_crf::computeObjectMotionErrors] object id " +
                                 std::to_string (id) + " is not among the pair's objects");
  return truth.objects[index];
}

}  // namespace

double
clusterAccuracy (const std::vector<int>& mapped_objects, const std::vector<int>& true_objects)
{
  if (mapped_objects.size () != true_objects.size ())
    throw std::invalid_argument ("[pcl_crf::clusterAccuracy] " +
                                 std::to_string (mapped_objects.size ()) + " mapped labels but " +
                                 std::to_string (true_objects.size ()) + " true object ids");
  if (true_objects.empty ())
    return kNaN;
  std::size_t correct = 0;
  for (std::size_t i = 0; i < true_objects.size (); ++i)
    correct += mapped_objects[i] == true_objects[i] ? 1 : 0;
  return static_cast<double> (correct) / static_cast<double> (true_objects.size ());
}

int
countClusters (const std::vector<int>& clusters)
{
  std::set<int> used (clusters.begin (), clusters.end ());
  used.erase (kOutlierCluster);
  return static_cast<int> (used.size ());
}

int
countObjects (const std::vector<int>& objects)
{
  return static_cast<int> (std::set<int> (objects.begin (), objects.end ()).size ());
}

ObjectMotionErrors
computeObjectMotionErrors (const ScanPair& truth, const Prediction& prediction,
                           const ClusterObjectMatching& matching)
{
  ErrorMean static_world, moving;
  for (const auto& pair : matching.pairs) {
    if (!pair.isMutualMajority ())
      continue;
    const ObjectTruth& object = objectTruth (truth, pair.object);
    const MotionError error =
        computeMotionError (clusterMotion (prediction, pair.cluster), object.T_target_source);
    (object.is_static ? static_world : moving).add (error);
  }
  return {static_world.rotation (), static_world.translation (), moving.rotation (),
          moving.translation ()};
}

}  // namespace pcl_crf
