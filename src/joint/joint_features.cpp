#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/clustering/point_pairs.h>
#include <pcl_crf/joint/joint_features.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace pcl_crf {
namespace joint {

namespace {

/** Index of the association state of point i that stands for target point j (kNoMatch: outlier). */
inline int
stateTarget (const matching::Candidates& candidates, int i, int s)
{
  return s < candidates.count (i) ? candidates.target (i, s) : kNoMatch;
}

[[noreturn]] void
failIn (const char* function, const std::string& what)
{
  throw std::invalid_argument (std::string ("[pcl_crf::joint::") + function + "] " + what);
}

void
requireConsistent (const char* function, const LadderGeometry& geometry)
{
  const std::string problem = ladderGeometryProblem (geometry);
  if (!problem.empty ())
    failIn (function, problem);
}

/** The problem of compressed candidate rows over \a rows source and \a targets target points, or "". */
std::string
candidatesProblem (const matching::Candidates& candidates, int rows, Eigen::Index targets)
{
  const std::vector<int>& offsets = candidates.offsets;
  if (offsets.empty () || offsets.front () != 0 || offsets.back () != static_cast<int> (candidates.targets.size ()) ||
      !std::is_sorted (offsets.begin (), offsets.end ()))
    return "the candidates' offsets must run from 0, non-decreasing, to their number of targets";
  if (candidates.size () != rows)
    return "the candidates have " + std::to_string (candidates.size ()) + " rows for " + std::to_string (rows) +
           " source points";
  for (int i = 0; i < rows; ++i)
    for (int c = 0; c < candidates.count (i); ++c)
      if (candidates.target (i, c) < 0 || candidates.target (i, c) >= targets)
        return "candidate " + std::to_string (c) + " of source point " + std::to_string (i) + " is target point " +
               std::to_string (candidates.target (i, c)) + " of " + std::to_string (targets);
  return {};
}

/** The cluster-distance features log(1 + r² c_k) (CRF-Clustering's local features). */
inline void
residualFeatures (double squared_residual, const LadderGeometry& geometry, int i, double& spacing, double& beam)
{
  spacing = std::log1p (squared_residual * geometry.inverse_scales (0, i));
  beam = std::log1p (squared_residual * geometry.inverse_scales (1, i));
}

/** | ||a − b|| − d |: how much a neighbour distance changes (Eq. (6) of the clustering paper). */
inline double
stiffness (const Eigen::Vector2d& a, const Eigen::Vector2d& b, double d)
{
  return std::abs ((a - b).norm () - d);
}

}  // namespace

const std::vector<const char*>&
jointWeightNames ()
{
  static const std::vector<const char*> names = {
      "association_data_margin", "association_outlier_margin", "association_outlier_bias",
      "association_sequence", "association_sequence_repeat", "association_sequence_skip",
      "association_outlier_switch", "association_outlier_run", "association_pairwise_distance",
      "association_pairwise_translation", "rung_spacing_residual", "rung_beam_residual",
      "rung_matched_outlier_cluster", "rung_unmatched_cluster",
      "cluster_neighbour", "cluster_weighted_neighbour", "cluster_stiffness", "cluster_outlier_switch",
      "cluster_outlier_run"};
  return names;
}

std::string
ladderGeometryProblem (const LadderGeometry& geometry)
{
  const int n = geometry.size ();
  const std::string problem = candidatesProblem (geometry.candidates, n, geometry.target.cols ());
  if (!problem.empty ())
    return problem;
  if (geometry.inverse_scales.cols () != n || geometry.neighbour_distance.size () != std::max (n - 1, 0))
    return std::to_string (geometry.inverse_scales.cols ()) + " inverse scales and " +
           std::to_string (geometry.neighbour_distance.size ()) + " neighbour distances for " + std::to_string (n) +
           " source points: give one scale per point and one distance per pair of consecutive points";
  return {};
}

LadderGeometry
makeLadderGeometry (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target,
                    const matching::Candidates& candidates, double min_spacing, double min_neighbour_distance)
{
  const std::string problem = candidatesProblem (candidates, static_cast<int> (source.cols ()), target.cols ());
  if (!problem.empty ())
    failIn ("makeLadderGeometry", problem);
  LadderGeometry geometry;
  geometry.source = source;
  geometry.target = target;
  geometry.candidates = candidates;
  geometry.min_neighbour_distance = min_neighbour_distance;
  // The scales of CRF-Clustering's local features over every source point: the
  // pairs (s_i → s_i) only serve to reuse its sampling-distance and beam-spacing code.
  std::vector<int> all (static_cast<std::size_t> (source.cols ()));
  std::iota (all.begin (), all.end (), 0);
  clustering::FeatureOptions options;
  options.min_spacing = min_spacing;
  geometry.inverse_scales = clustering::unaryScales (clustering::makePointPairs (source, source, all), options);
  const Eigen::Index n = source.cols ();
  geometry.neighbour_distance.resize (std::max<Eigen::Index> (n - 1, 0));
  for (Eigen::Index i = 0; i + 1 < n; ++i)
    geometry.neighbour_distance (i) = (source.col (i + 1) - source.col (i)).norm ();
  return geometry;
}

void
RungPotentials::resize (const LadderGeometry& geometry, int clusters)
{
  columns_ = clusters + 1;
  rows_.resize (static_cast<std::size_t> (geometry.size ()));
  offsets_.resize (rows_.size ());
  std::size_t total = 0;
  for (int i = 0; i < geometry.size (); ++i) {
    rows_[i] = geometry.associationStates (i);
    offsets_[i] = total;
    total += static_cast<std::size_t> (rows_[i]) * static_cast<std::size_t> (columns_);
  }
  values_.resize (total);
}

void
updateRungColumn (const LadderGeometry& geometry, const Rigid2d& motion, const Eigen::VectorXd& w, int l,
                  RungPotentials& rungs)
{
  if (static_cast<int> (rungs.size ()) != geometry.size () || l < 0 || l + 1 >= rungs.columns () ||
      w.size () != kJointWeightCount)
    failIn ("updateRungColumn", std::to_string (rungs.size ()) + " rungs of " + std::to_string (rungs.columns ()) +
                                    " columns for " + std::to_string (geometry.size ()) + " points, cluster " +
                                    std::to_string (l) + " and " + std::to_string (w.size ()) +
                                    " weights: give the rungs rungPotentials () sized, one of their real clusters "
                                    "and kJointWeightCount weights");
  const double w_spacing = w (kRungSpacingResidual), w_beam = w (kRungBeamResidual);
  for (int i = 0; i < geometry.size (); ++i) {  // cluster distance w_s log(1 + r² c_s) + w_b log(1 + r² c_b)
    const Eigen::Vector2d moved = motion * geometry.source.col (i);
    const double c_spacing = geometry.inverse_scales (0, i), c_beam = geometry.inverse_scales (1, i);
    double* column = rungs[i].col (l).data ();
    for (int s = 0; s < geometry.candidates.count (i); ++s) {
      const double r2 = (moved - geometry.target.col (geometry.candidates.target (i, s))).squaredNorm ();
      column[s] = w_spacing * std::log (1.0 + r2 * c_spacing) + w_beam * std::log (1.0 + r2 * c_beam);
    }
  }
}

void
rungPotentials (const LadderGeometry& geometry, const std::vector<Rigid2d>& motions, const Eigen::VectorXd& w,
                RungPotentials& rungs)
{
  requireConsistent ("rungPotentials", geometry);
  if (w.size () != kJointWeightCount)
    failIn ("rungPotentials", "expected " + std::to_string (kJointWeightCount) + " weights, got " +
                                  std::to_string (w.size ()));
  const int clusters = static_cast<int> (motions.size ());
  rungs.resize (geometry, clusters);
  for (int i = 0; i < geometry.size (); ++i) {  // the cluster-inlier features
    const int count = geometry.candidates.count (i);
    auto rung = rungs[i];
    rung.row (count).setConstant (w (kRungUnmatchedCluster));
    rung.col (clusters).head (count).setConstant (w (kRungMatchedOutlierCluster));
    rung (count, clusters) = 0.0;  // the reference
  }
  for (int l = 0; l < clusters; ++l)
    updateRungColumn (geometry, motions[l], w, l, rungs);
}

Eigen::VectorXd
rungFeatures (const LadderGeometry& geometry, int i, int s, int l, const std::vector<Rigid2d>& motions)
{
  if (i < 0 || i >= geometry.size () || i >= geometry.candidates.size () || s < 0 ||
      s >= geometry.associationStates (i) || l < 0 || l > static_cast<int> (motions.size ()))
    failIn ("rungFeatures", "point " + std::to_string (i) + ", association state " + std::to_string (s) +
                                " and cluster " + std::to_string (l) + " do not fit " + std::to_string (geometry.size ()) +
                                " points and " + std::to_string (motions.size ()) + " clusters");
  Eigen::VectorXd f = Eigen::VectorXd::Zero (kJointWeightCount);
  const int j = stateTarget (geometry.candidates, i, s);
  if (j != kNoMatch && (j >= geometry.target.cols () || i >= geometry.inverse_scales.cols ()))
    failIn ("rungFeatures", "the geometry is inconsistent: " + ladderGeometryProblem (geometry));
  const bool outlier_cluster = l == static_cast<int> (motions.size ());
  if (j == kNoMatch) {
    if (!outlier_cluster)
      f (kRungUnmatchedCluster) = 1.0;
  }
  else if (outlier_cluster)
    f (kRungMatchedOutlierCluster) = 1.0;
  else {
    const double r2 = (motions[l] * geometry.source.col (i) - geometry.target.col (j)).squaredNorm ();
    residualFeatures (r2, geometry, i, f (kRungSpacingResidual), f (kRungBeamResidual));
  }
  return f;
}

void
clusterEdgePotential (const LadderGeometry& geometry, int i, const Eigen::Matrix2Xd& moved_here,
                      const Eigen::Matrix2Xd& moved_next, const Eigen::VectorXd& w,
                      Eigen::Ref<Eigen::MatrixXd> potential)
{
  const int clusters = static_cast<int> (moved_here.cols ());
  if (potential.rows () != clusters + 1 || potential.cols () != clusters + 1)
    throw std::invalid_argument ("[pcl_crf::joint::clusterEdgePotential] the potential is not (K + 1) x (K + 1)");
  if (i < 0 || i >= geometry.neighbour_distance.size () || moved_next.cols () != clusters)
    failIn ("clusterEdgePotential", "edge " + std::to_string (i) + " of " +
                                        std::to_string (geometry.neighbour_distance.size ()) + ", " +
                                        std::to_string (clusters) + " and " + std::to_string (moved_next.cols ()) +
                                        " moved points: give an edge of the geometry and K moved points at each end");
  const double d = geometry.neighbour_distance (i);
  const double same = w (kClusterNeighbour) + w (kClusterWeightedNeighbour) / std::max (d, geometry.min_neighbour_distance);
  for (int l = 0; l < clusters; ++l) {
    for (int k = 0; k < clusters; ++k)  // a rigid pair keeps its distance: no stiffness when k = l
      potential (k, l) = k == l ? same : w (kClusterStiffness) * stiffness (moved_here.col (k), moved_next.col (l), d);
    potential (clusters, l) = w (kClusterOutlierSwitch);
    potential (l, clusters) = w (kClusterOutlierSwitch);
  }
  potential (clusters, clusters) = w (kClusterOutlierRun);
}

Eigen::VectorXd
clusterEdgeFeatures (const LadderGeometry& geometry, int i, int k, int l, const std::vector<Rigid2d>& motions)
{
  const int clusters = static_cast<int> (motions.size ());
  if (i < 0 || i >= geometry.neighbour_distance.size () || i + 1 >= geometry.source.cols () || k < 0 || k > clusters ||
      l < 0 || l > clusters)
    failIn ("clusterEdgeFeatures", "edge " + std::to_string (i) + " of " +
                                       std::to_string (geometry.neighbour_distance.size ()) + " in clusters " +
                                       std::to_string (k) + " and " + std::to_string (l) + " of " +
                                       std::to_string (clusters) + " (+ the outlier cluster)");
  Eigen::VectorXd f = Eigen::VectorXd::Zero (kJointWeightCount);
  const double d = geometry.neighbour_distance (i);
  if (k == clusters || l == clusters)
    f (k == l ? kClusterOutlierRun : kClusterOutlierSwitch) = 1.0;
  else if (k == l) {
    f (kClusterNeighbour) = 1.0;
    f (kClusterWeightedNeighbour) = 1.0 / std::max (d, geometry.min_neighbour_distance);
  }
  else
    f (kClusterStiffness) =
        stiffness (motions[k] * geometry.source.col (i), motions[l] * geometry.source.col (i + 1), d);
  return f;
}

}  // namespace joint
}  // namespace pcl_crf
