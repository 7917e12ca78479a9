#include <pcl_crf/clustering/clustering_features.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

/** T_l s_i of every cluster l: one 2 x n matrix per cluster. */
std::vector<Eigen::Matrix2Xd>
movedSources (const PointPairs& pairs, const std::vector<Rigid2d>& motions)
{
  std::vector<Eigen::Matrix2Xd> moved;
  moved.reserve (motions.size ());
  for (const Rigid2d& T : motions)
    moved.push_back ((T.linear () * pairs.source).colwise () + T.translation ());
  return moved;
}

/** Beams between chain neighbours e and e + 1 (consecutive pairs) that hold no pair:
 *  round(Δφ / Δθ) − 1, Δφ their bearing difference, Δθ the scan's angular resolution
 *  (the count matching::segmentScan () bounds in a run of missing returns). */
long
beamsBetween (const PointPairs& pairs, Eigen::Index e)
{
  const Eigen::Vector2d a = pairs.source.col (e), b = pairs.source.col (e + 1);
  const double dphi = std::abs (std::atan2 (a.x () * b.y () - a.y () * b.x (), a.dot (b)));
  return std::lround (dphi / pairs.angular_resolution) - 1;
}

/** The weighted neighbour feature of edge (e, e + 1) when both points share a cluster
 *  (Eq. (5)): 1 / max(d, d_min), or 0 across more than options.weighted_neighbour_max_gap
 *  beams without a pair. */
double
weightedNeighbour (const PointPairs& pairs, Eigen::Index e, double d, const FeatureOptions& options)
{
  const bool bounded = options.weighted_neighbour_max_gap >= 0 && pairs.angular_resolution > 0.0;
  if (bounded && beamsBetween (pairs, e) > options.weighted_neighbour_max_gap)
    return 0.0;
  return 1.0 / std::max (d, options.min_neighbour_distance);
}

/** What the pairwise features of edge (i, i + 1) need: d = ||s_i − s_{i+1}|| and the moved points. */
struct Edge
{
  const std::vector<Eigen::Matrix2Xd>& moved;
  Eigen::Index i;
  double distance;
  double inverse_distance;  // weightedNeighbour (): 1 / max(d, d_min), or 0 across a gap

  /** Eq. (6): how much the pair's distance changes when s_i moves with k and s_{i+1} with l. */
  double
  stiffness (int k, int l) const
  {
    return k == l ? 0.0 : std::abs ((moved[k].col (i) - moved[l].col (i + 1)).norm () - distance);
  }
};

Edge
makeEdge (const PointPairs& pairs, const std::vector<Eigen::Matrix2Xd>& moved, std::size_t i,
          const FeatureOptions& options)
{
  const auto e = static_cast<Eigen::Index> (i);
  const double d = (pairs.source.col (e) - pairs.source.col (e + 1)).norm ();
  return {moved, e, d, weightedNeighbour (pairs, e, d, options)};
}

/** Pairwise feature rows of an edge, row a + S_i b for states (states_i[a], states_j[b]). */
Eigen::MatrixXd
edgeRows (const Edge& edge, const std::vector<int>& states_i, const std::vector<int>& states_j)
{
  const auto s_i = static_cast<Eigen::Index> (states_i.size ());
  Eigen::MatrixXd rows (s_i * static_cast<Eigen::Index> (states_j.size ()), kPairwiseFeatureCount);
  for (std::size_t b = 0; b < states_j.size (); ++b)
    for (std::size_t a = 0; a < states_i.size (); ++a)
    {
      const int k = states_i[a], l = states_j[b];
      const double same = k == l ? 1.0 : 0.0;
      const Eigen::Index row = static_cast<Eigen::Index> (a) + s_i * static_cast<Eigen::Index> (b);
      rows (row, 0) = same;                          // Eq. (4)
      rows (row, 1) = same * edge.inverse_distance;  // Eq. (5)
      rows (row, 2) = edge.stiffness (k, l);         // Eq. (6)
    }
  return rows;
}

/** Pairwise log-potentials of an edge: w_p · (rows of edgeRows ()). */
Eigen::MatrixXd
edgeTable (const Edge& edge, const std::vector<int>& states_i, const std::vector<int>& states_j,
           const Eigen::VectorXd& weights)
{
  const double w_same = weights (kUnaryFeatureCount), w_inverse = weights (kUnaryFeatureCount + 1);
  const double w_stiffness = weights (kUnaryFeatureCount + 2);
  Eigen::MatrixXd table (static_cast<Eigen::Index> (states_i.size ()), static_cast<Eigen::Index> (states_j.size ()));
  for (Eigen::Index b = 0; b < table.cols (); ++b)
    for (Eigen::Index a = 0; a < table.rows (); ++a)
    {
      const int k = states_i[a], l = states_j[b];
      table (a, b) = k == l ? w_same + w_inverse * edge.inverse_distance : w_stiffness * edge.stiffness (k, l);
    }
  return table;
}

void
checkSizes (const PointPairs& pairs, const CandidateStates& states, Eigen::Index residual_rows,
            Eigen::Index residual_cols, std::size_t motions)
{
  if (states.size () != pairs.size () || residual_cols != pairs.source.cols () ||
      residual_rows != static_cast<Eigen::Index> (motions))
    throw std::invalid_argument ("[pcl_crf::clustering::chainFeatures] " + std::to_string (pairs.size ()) +
                                 " pairs, " + std::to_string (states.size ()) + " state lists, " +
                                 std::to_string (motions) + " motions and a " + std::to_string (residual_rows) +
                                 " x " + std::to_string (residual_cols) + " residual matrix do not fit");
}

}  // namespace

const std::vector<const char*>&
weightNames ()
{
  static const std::vector<const char*> names = {"spacing_residual", "beam_residual", "neighbour",
                                                 "weighted_neighbour", "stiffness"};
  return names;
}

Eigen::MatrixXd
unaryScales (const PointPairs& pairs, const FeatureOptions& options)
{
  const Eigen::ArrayXd h = pairs.spacing.array ().max (options.min_spacing);
  const Eigen::ArrayXd beam =
      (pairs.source.colwise ().norm ().transpose ().array () * pairs.angular_resolution).max (options.min_spacing);
  Eigen::MatrixXd scales (kUnaryFeatureCount, pairs.source.cols ());
  scales.row (0) = (1.0 / h.square ()).matrix ().transpose ();
  scales.row (1) = (1.0 / beam.square ()).matrix ().transpose ();
  return scales;
}

Eigen::VectorXd
unaryFeatures (double f_dist, const Eigen::Ref<const Eigen::VectorXd>& inverse_scales)
{
  return (f_dist * inverse_scales.array ()).log1p ().matrix ();  // robust Eq. (2)
}

Eigen::MatrixXd
localLogPotentials (const PointPairs& pairs, const Eigen::MatrixXd& residuals, const Eigen::VectorXd& weights,
                    const FeatureOptions& options)
{
  const Eigen::MatrixXd scales = unaryScales (pairs, options);
  Eigen::MatrixXd local = Eigen::MatrixXd::Zero (residuals.rows (), residuals.cols ());
  for (int k = 0; k < kUnaryFeatureCount; ++k)  // w_k log(1 + f_dist c_k), as unaryFeatures ()
    local.array () += weights (k) * (residuals.array ().rowwise () * scales.row (k).array ()).log1p ();
  return local;
}

void
localLogPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const Eigen::MatrixXd& scales,
                    const Eigen::VectorXd& weights, Eigen::MatrixXd& local)
{
  const Eigen::Index n = pairs.source.cols ();
  const auto s_count = static_cast<Eigen::Index> (motions.size ());
  local.resize (s_count, n);
  Eigen::Matrix<double, 6, Eigen::Dynamic> coefficients (6, s_count);  // R row-major, then T
  for (Eigen::Index l = 0; l < s_count; ++l)
  {
    const Eigen::Matrix2d R = motions[l].linear ();
    coefficients.col (l) << R (0, 0), R (0, 1), R (1, 0), R (1, 1), motions[l].translation ();
  }
  double w[kUnaryFeatureCount], c[kUnaryFeatureCount];
  for (int k = 0; k < kUnaryFeatureCount; ++k)
    w[k] = weights (k);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    const double x = pairs.source (0, i), y = pairs.source (1, i);
    const double gx = pairs.target (0, i), gy = pairs.target (1, i);
    for (int k = 0; k < kUnaryFeatureCount; ++k)
      c[k] = scales (k, i);
    double* column = local.data () + i * s_count;
    for (Eigen::Index l = 0; l < s_count; ++l)
    {
      const double* m = coefficients.data () + 6 * l;
      const double dx = (m[0] * x + m[1] * y) + m[4] - gx, dy = (m[2] * x + m[3] * y) + m[5] - gy;
      const double f = dx * dx + dy * dy;  // Eq. (2): ||T_l s_i − g_i||², as squaredResiduals ()
      double value = 0.0;
      for (int k = 0; k < kUnaryFeatureCount; ++k)  // w_k log(1 + f_dist c_k), see the declaration
        value += w[k] * std::log (1.0 + f * c[k]);
      column[l] = value;
    }
  }
}

CandidateStates
allStates (std::size_t node_count, int cluster_count)
{
  std::vector<int> every (static_cast<std::size_t> (std::max (cluster_count, 0)));
  for (int l = 0; l < cluster_count; ++l)
    every[l] = l;
  return CandidateStates (node_count, every);
}

crf::ChainFeatures
chainFeatures (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
               const FeatureOptions& options, const Eigen::MatrixXd* residuals)
{
  const Eigen::MatrixXd f = residuals ? *residuals : squaredResiduals (pairs, motions);
  checkSizes (pairs, states, f.rows (), f.cols (), motions.size ());
  const Eigen::MatrixXd scales = unaryScales (pairs, options);
  const std::vector<Eigen::Matrix2Xd> moved = movedSources (pairs, motions);
  crf::ChainFeatures features;
  features.unary.reserve (pairs.size ());
  for (std::size_t i = 0; i < pairs.size (); ++i)
  {
    Eigen::MatrixXd rows (static_cast<Eigen::Index> (states[i].size ()), kUnaryFeatureCount);
    for (std::size_t a = 0; a < states[i].size (); ++a)
      rows.row (a) = unaryFeatures (f (states[i][a], static_cast<Eigen::Index> (i)), scales.col (i)).transpose ();
    features.unary.push_back (std::move (rows));
  }
  for (std::size_t i = 0; i + 1 < pairs.size (); ++i)
    features.pairwise.push_back (edgeRows (makeEdge (pairs, moved, i, options), states[i], states[i + 1]));
  return features;
}

crf::ChainPotentials
chainPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
                 const Eigen::MatrixXd& local, const Eigen::VectorXd& weights, const FeatureOptions& options)
{
  checkSizes (pairs, states, local.rows (), local.cols (), motions.size ());
  if (weights.size () != kWeightCount)
    throw std::invalid_argument ("[pcl_crf::clustering::chainPotentials] expected " + std::to_string (kWeightCount) +
                                 " weights");
  const std::vector<Eigen::Matrix2Xd> moved = movedSources (pairs, motions);
  crf::ChainPotentials chain;
  chain.unary.reserve (pairs.size ());
  for (std::size_t i = 0; i < pairs.size (); ++i)
  {
    Eigen::VectorXd unary (static_cast<Eigen::Index> (states[i].size ()));
    for (std::size_t a = 0; a < states[i].size (); ++a)
      unary (a) = local (states[i][a], static_cast<Eigen::Index> (i));
    chain.unary.push_back (std::move (unary));
  }
  for (std::size_t i = 0; i + 1 < pairs.size (); ++i)
    chain.pairwise.push_back (edgeTable (makeEdge (pairs, moved, i, options), states[i], states[i + 1], weights));
  return chain;
}

void
chainPotentials (const PointPairs& pairs, const std::vector<Rigid2d>& motions, const CandidateStates& states,
                 const Eigen::MatrixXd& local, const Eigen::VectorXd& weights, const FeatureOptions& options,
                 crf::PackedChainPotentials& chain)
{
  checkSizes (pairs, states, local.rows (), local.cols (), motions.size ());
  if (weights.size () != kWeightCount)
    throw std::invalid_argument ("[pcl_crf::clustering::chainPotentials] expected " + std::to_string (kWeightCount) +
                                 " weights");
  const double w_same = weights (kUnaryFeatureCount), w_inverse = weights (kUnaryFeatureCount + 1);
  const double w_stiffness = weights (kUnaryFeatureCount + 2);
  chain.clear ();
  std::size_t unary_entries = 0, pairwise_entries = 0;
  for (std::size_t i = 0; i < pairs.size (); ++i)
  {
    unary_entries += states[i].size ();
    if (i + 1 < pairs.size ())
      pairwise_entries += states[i].size () * states[i + 1].size ();
  }
  chain.reserve (pairs.size (), unary_entries, pairwise_entries);
  for (std::size_t i = 0; i < pairs.size (); ++i)
  {
    chain.addNode (static_cast<int> (states[i].size ()));
    Eigen::Map<Eigen::VectorXd> unary = chain.unary (i);
    for (std::size_t a = 0; a < states[i].size (); ++a)
      unary (a) = local (states[i][a], static_cast<Eigen::Index> (i));
  }
  // T_l s_i for the candidate clusters l of node i: the moved points the stiffness (Eq. (6)) compares.
  const auto moveNode = [&] (std::size_t i, std::vector<Eigen::Vector2d>& moved) {
    moved.clear ();
    const Eigen::Vector2d s = pairs.source.col (static_cast<Eigen::Index> (i));
    for (const int l : states[i])
      moved.push_back (motions[l].linear () * s + motions[l].translation ());
  };
  std::vector<Eigen::Vector2d> moved_i, moved_j;
  if (pairs.size () > 0)
    moveNode (0, moved_j);
  for (std::size_t i = 0; i + 1 < pairs.size (); ++i)
  {
    moved_i.swap (moved_j);
    moveNode (i + 1, moved_j);
    const auto e = static_cast<Eigen::Index> (i);
    const double d = (pairs.source.col (e) - pairs.source.col (e + 1)).norm ();
    const double inverse_distance = weightedNeighbour (pairs, e, d, options);
    Eigen::Map<Eigen::MatrixXd> table = chain.pairwise (i);
    for (Eigen::Index b = 0; b < table.cols (); ++b)
      for (Eigen::Index a = 0; a < table.rows (); ++a)
      {
        const int k = states[i][a], l = states[i + 1][b];
        table (a, b) = k == l ? w_same + w_inverse * inverse_distance  // Eqs. (4), (5)
                              : w_stiffness * std::abs ((moved_i[a] - moved_j[b]).norm () - d);  // Eq. (6)
      }
  }
}

}  // namespace clustering
}  // namespace pcl_crf
