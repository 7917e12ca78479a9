#include <pcl_crf/metrics/validate_prediction.h>

#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::validatePrediction] " + what);
}

void
checkLength (std::size_t length, std::size_t points, const std::string& what)
{
  if (length != points)
    fail (what + " has " + std::to_string (length) + " entries for " + std::to_string (points) +
          " source points");
}

void
checkTargetIndices (const std::vector<int>& matches, Eigen::Index target_points,
                    const std::string& what)
{
  for (std::size_t i = 0; i < matches.size (); ++i)
    if (matches[i] != kNoMatch && (matches[i] < 0 || matches[i] >= target_points))
      fail (what + " of source point " + std::to_string (i) + " is target index " +
            std::to_string (matches[i]) + ", out of range [0, " + std::to_string (target_points) +
            ") and not kNoMatch");
}

void
checkAssociation (const ScanPair& truth, const Prediction& prediction)
{
  const auto points = static_cast<std::size_t> (truth.source.cols ());
  checkLength (prediction.source_match.size (), points, "prediction.source_match");
  checkLength (truth.source_match.size (), points, "truth.source_match");
  checkTargetIndices (prediction.source_match, truth.target.cols (), "prediction.source_match");
  checkTargetIndices (truth.source_match, truth.target.cols (), "truth.source_match");
}

void
checkClustering (const ScanPair& truth, const Prediction& prediction)
{
  const auto points = static_cast<std::size_t> (truth.source.cols ());
  checkLength (prediction.source_cluster.size (), points, "prediction.source_cluster");
  checkLength (truth.source_object.size (), points, "truth.source_object");
  const auto clusters = prediction.cluster_motions.size ();
  for (std::size_t i = 0; i < points; ++i) {
    const int label = prediction.source_cluster[i];
    if (label != kOutlierCluster && (label < 0 || static_cast<std::size_t> (label) >= clusters))
      fail ("prediction.source_cluster of source point " + std::to_string (i) + " is " +
            std::to_string (label) + ", but cluster_motions holds " + std::to_string (clusters) +
            " clusters (labels must lie in [0, " + std::to_string (clusters) +
            ") or be kOutlierCluster)");
    if (truth.objectIndex (truth.source_object[i]) < 0)
      fail ("truth.source_object of source point " + std::to_string (i) + " is " +
            std::to_string (truth.source_object[i]) + ", an id not among truth.objects");
  }
}

/** The motions a prediction states: finite rigid motions, and a static cluster among its clusters. */
void
checkMotions (const Prediction& prediction)
{
  const auto rigid = [] (const Rigid2d& T) { return T.matrix ().allFinite () && isRotation (T); };
  if (!rigid (prediction.T_source_target))
    fail ("prediction.T_source_target is not a finite rigid motion (NaN, infinite, or no rotation)");
  for (std::size_t c = 0; c < prediction.cluster_motions.size (); ++c)
    if (!rigid (prediction.cluster_motions[c]))
      fail ("prediction.cluster_motions[" + std::to_string (c) +
            "] is not a finite rigid motion (NaN, infinite, or no rotation)");
  if (prediction.static_cluster < -1 ||
      prediction.static_cluster >= static_cast<int> (prediction.cluster_motions.size ()))
    fail ("prediction.static_cluster is " + std::to_string (prediction.static_cluster) + ", not -1 or one of the " +
          std::to_string (prediction.cluster_motions.size ()) + " clusters");
}

}  // namespace

void
validatePrediction (const ScanPair& truth, const Prediction& prediction)
{
  checkMotions (prediction);
  if (!prediction.source_match.empty ())
    checkAssociation (truth, prediction);
  if (!prediction.source_cluster.empty ())
    checkClustering (truth, prediction);
}

}  // namespace pcl_crf
