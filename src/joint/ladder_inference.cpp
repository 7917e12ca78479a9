#include <pcl_crf/core/rigid_fit.h>
#include <pcl_crf/joint/ladder_inference.h>
#include <pcl_crf/joint/map_history.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace joint {

namespace {

/** The most states a node may have (association candidates + 1, clusters + 1): node
 *  temporaries live on the stack, so a visit allocates nothing. */
constexpr int kMaxStates = 64;
using Small = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStates, 1>;

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::joint::inferLadder] " + what);
}

/** out(t) = max_s in(s) + P(s, t) for a column-major \a rows x \a cols P whose
 *  columns start \a stride apart: a message along P's rows to its columns (plain
 *  loops: the vectors hold a handful of states, too few for Eigen's packet reductions
 *  to pay off). */
void
maxToColumns (const double* in, const double* P, int rows, int cols, Eigen::Index stride, Small& out)
{
  out.resize (cols);
  for (int t = 0; t < cols; ++t, P += stride) {
    double best = P[0] + in[0];
    for (int s = 1; s < rows; ++s)
      best = std::max (best, P[s] + in[s]);
    out (t) = best;
  }
}

void
maxToColumns (const Small& in, const Eigen::Ref<const Eigen::MatrixXd>& P, Small& out)
{
  maxToColumns (in.data (), P.data (), static_cast<int> (P.rows ()), static_cast<int> (P.cols ()), P.outerStride (),
                out);
}

/** out(s) = max_t in(t) + P(s, t): a message along P's columns to its rows. */
void
maxToRows (const double* in, const double* P, int rows, int cols, Eigen::Index stride, Small& out)
{
  out.resize (rows);
  for (int s = 0; s < rows; ++s)
    out (s) = P[s] + in[0];
  for (int t = 1; t < cols; ++t) {
    P += stride;
    for (int s = 0; s < rows; ++s)
      out (s) = std::max (out (s), P[s] + in[t]);
  }
}

void
maxToRows (const Small& in, const Eigen::Ref<const Eigen::MatrixXd>& P, Small& out)
{
  maxToRows (in.data (), P.data (), static_cast<int> (P.rows ()), static_cast<int> (P.cols ()), P.outerStride (),
             out);
}

Eigen::Index
argmax (const Small& v)
{
  Eigen::Index best = 0;
  v.maxCoeff (&best);
  return best;
}

/** Every message of the ladder in one buffer (allocated once per inference, not once
 *  per message); index i of a chain message is the edge (i, i + 1). Node i's block
 *  holds the three messages of its S_i association states, then the three of its
 *  K + 1 cluster states. */
class Messages
{
public:
  using Message = Eigen::Map<Eigen::VectorXd>;
  using ConstMessage = Eigen::Map<const Eigen::VectorXd>;

  /** All messages 0. */
  Messages (const LadderGeometry& geometry, int clusters)
    : clusters_ (clusters), offsets_ (static_cast<std::size_t> (geometry.size ()) + 1, 0)
  {
    for (int i = 0; i < geometry.size (); ++i) {
      association_states_.push_back (geometry.associationStates (i));
      offsets_[i + 1] = offsets_[i] + 3 * static_cast<std::size_t> (association_states_[i] + clusters_ + 1);
    }
    values_.assign (offsets_.back (), 0.0);
  }

  /** x^a_i → x^a_{i+1} */
  Message
  associationForward (int i) { return association (i + 1, 0); }
  ConstMessage
  associationForward (int i) const { return association (i + 1, 0); }
  /** x^a_{i+1} → x^a_i */
  Message
  associationBackward (int i) { return association (i, 1); }
  ConstMessage
  associationBackward (int i) const { return association (i, 1); }
  /** x^c_i → x^a_i (the rung) */
  Message
  clusterToAssociation (int i) { return association (i, 2); }
  ConstMessage
  clusterToAssociation (int i) const { return association (i, 2); }
  /** x^c_i → x^c_{i+1} */
  Message
  clusterForward (int i) { return cluster (i, 0); }
  ConstMessage
  clusterForward (int i) const { return cluster (i, 0); }
  /** x^c_{i+1} → x^c_i */
  Message
  clusterBackward (int i) { return cluster (i, 1); }
  ConstMessage
  clusterBackward (int i) const { return cluster (i, 1); }
  /** x^a_i → x^c_i (the rung) */
  Message
  associationToCluster (int i) { return cluster (i, 2); }
  ConstMessage
  associationToCluster (int i) const { return cluster (i, 2); }

private:
  /** Where the \a slot-th message over node i's association states begins. */
  std::size_t
  associationAt (int i, int slot) const
  {
    return offsets_[i] + static_cast<std::size_t> (slot) * association_states_[i];
  }

  /** Where the \a slot-th message over node i's cluster states begins. */
  std::size_t
  clusterAt (int i, int slot) const
  {
    return associationAt (i, 3) + static_cast<std::size_t> (slot) * (clusters_ + 1);
  }

  Message
  association (int i, int slot) { return {values_.data () + associationAt (i, slot), association_states_[i]}; }
  ConstMessage
  association (int i, int slot) const { return {values_.data () + associationAt (i, slot), association_states_[i]}; }
  Message
  cluster (int i, int slot) { return {values_.data () + clusterAt (i, slot), clusters_ + 1}; }
  ConstMessage
  cluster (int i, int slot) const { return {values_.data () + clusterAt (i, slot), clusters_ + 1}; }

  int clusters_;
  std::vector<int> association_states_;
  std::vector<std::size_t> offsets_;  // node i's block begins at offsets_[i]
  std::vector<double> values_;
};

class Ladder
{
public:
  Ladder (const LadderGeometry& geometry, const crf::ChainPotentials& association, const Eigen::VectorXd& weights,
          const std::vector<Rigid2d>& motions, const LadderOptions& options)
    : g_ (geometry), association_ (association), w_ (weights), options_ (options), motions_ (motions),
      n_ (geometry.size ()), clusters_ (static_cast<int> (motions.size ())), messages_ (geometry, clusters_)
  {
  }

  LadderResult
  run (const std::vector<int>& initial_association, const std::vector<int>& initial_cluster)
  {
    seedFits (initial_association, initial_cluster);
    LadderResult result;
    MapHistory history;
    while (result.iterations < options_.max_iterations && !result.converged && !result.oscillating) {
      ++result.iterations;
      changes_ = 0;
      change_ = 0.0;
      computeMotionPotentials ();
      if (options_.schedule == MessageSchedule::Sweep)
        sweep ();
      else
        flood ();
      for (int l = 0; l < clusters_; ++l)  // eq. 6 from the running sums of the MAP pairs
        refit (l);
      result.converged = changes_ == 0 && change_ <= options_.tolerance;
      result.oscillating = !result.converged && history.repeats (map_association_, map_cluster_);
    }
    result.association = map_association_;
    result.cluster = map_cluster_;
    result.motions = motions_;
    result.cluster_beliefs.resize (clusters_ + 1, n_);
    for (int i = 0; i < n_; ++i) {
      const Small b = clusterIncoming (messages_, i) + messages_.associationToCluster (i);  // once per run
      const Small p = (b.array () - b.maxCoeff ()).exp ().matrix ();
      result.cluster_beliefs.col (i) = p / p.sum ();
    }
    result.cluster_evidence = localEvidence ();
    return result;
  }

private:
  Eigen::MatrixXd
  localEvidence ()
  {
    computeMotionPotentials ();  // under the final refit
    Eigen::MatrixXd evidence (clusters_ + 1, n_);
    for (int i = 0; i < n_; ++i) {
      const Small r = evidenceOf (i);
      const Small p = (r.array () - r.maxCoeff ()).exp ().matrix ();
      evidence.col (i) = p / p.sum ();
    }
    return evidence;
  }

  /** The local evidence of every cluster at point i from its rung potential. */
  Small
  evidenceOf (int i) const
  {
    const auto rung = rungs_[i];
    if (options_.evidence == ClusterEvidence::MapAssociation)
      return rung.row (map_association_[i]).transpose ();
    return (rung.colwise () + association_.unary[i]).colwise ().maxCoeff ().transpose ();
  }

  /** Unary plus chain messages into x^a_i (without the rung): (unary + left) + right.
   *  Each case is a single expression, so the sum is written once (adding to a stored
   *  copy made every visit wait for the copy's stores). */
  Small
  associationIncoming (const Messages& m, int i) const
  {
    const Eigen::VectorXd& unary = association_.unary[i];
    const bool left = i > 0, right = i + 1 < n_;
    if (left && right)
      return unary + m.associationForward (i - 1) + m.associationBackward (i);
    if (left)
      return unary + m.associationForward (i - 1);
    if (right)
      return unary + m.associationBackward (i);
    return unary;
  }

  /** The chain messages into x^c_i (without the rung): (0 + left) + right, as associationIncoming (). */
  Small
  clusterIncoming (const Messages& m, int i) const
  {
    const auto zero = Small::Zero (clusters_ + 1);
    const bool left = i > 0, right = i + 1 < n_;
    if (left && right)
      return zero + m.clusterForward (i - 1) + m.clusterBackward (i);
    if (left)
      return zero + m.clusterForward (i - 1);
    if (right)
      return zero + m.clusterBackward (i);
    return zero;
  }

  /** The clustering-edge potential between points i and i + 1 (in edges_). */
  Eigen::Map<Eigen::MatrixXd>
  edge (int i)
  {
    const int states = clusters_ + 1;
    return {edges_.data () + static_cast<std::size_t> (i) * states * states, states, states};
  }

  /** T_l s_i for every cluster l into \a m (2 x K, its storage reused). */
  void
  moved (int i, Eigen::Matrix2Xd& m) const
  {
    m.resize (2, clusters_);
    for (int l = 0; l < clusters_; ++l)
      m.col (l) = motions_[l] * g_.source.col (i);
  }

  /** The rung and clustering-edge potentials under the current motions (they depend
   *  on x^RT; the motions change only between iterations, so every visit of this
   *  iteration sees the same values). */
  void
  computeMotionPotentials ()
  {
    const bool first = rungs_.empty ();
    std::vector<int> changed;  // clusters whose motion moved since the potentials were computed
    for (int l = 0; l < clusters_; ++l)
      if (first || motions_computed_[l].matrix () != motions_[l].matrix ())
        changed.push_back (l);
    if (changed.empty ())
      return;
    if (first)
      rungPotentials (g_, motions_, w_, rungs_);
    else
      for (int l : changed)
        updateRungColumn (g_, motions_[l], w_, l, rungs_);
    const int states = clusters_ + 1;
    edges_.resize (static_cast<std::size_t> (std::max (n_ - 1, 0)) * states * states);
    Eigen::Matrix2Xd here, next;
    moved (0, here);
    for (int i = 0; i + 1 < n_; ++i) {
      moved (i + 1, next);
      clusterEdgePotential (g_, i, here, next, w_, edge (i));
      here.swap (next);
    }
    motions_computed_ = motions_;
  }

  /** m ← (1 − λ) fresh + λ m (log domain), \a fresh first shifted to a maximum of 0
   *  (a message is defined up to a constant; all 0 when its maximum is not finite). */
  void
  assign (Messages::Message message, const Small& fresh)
  {
    double top = fresh (0);
    for (Eigen::Index k = 1; k < fresh.size (); ++k)
      top = std::max (top, fresh (k));
    const bool finite = std::isfinite (top);
    const double keep = options_.damping;
    double change = change_;  // a local: message (k) could alias change_, which would serialise the loop
    for (Eigen::Index k = 0; k < fresh.size (); ++k) {
      const double shifted = finite ? fresh (k) - top : 0.0;
      const double next = (1.0 - keep) * shifted + keep * message (k);
      change = std::max (change, std::abs (next - message (k)));
      message (k) = next;
    }
    change_ = change;
  }

  /** Node i's messages read from \a in and written to \a out: the rung, then the
   *  chain messages to the left and/or right neighbour. */
  void
  visit (int i, const Messages& in, Messages& out, bool to_right, bool to_left)
  {
    visit (i, in, out, to_right, to_left, associationIncoming (in, i), clusterIncoming (in, i));
  }

  /** visit () with the node's incoming messages \a a_in and \a c_in already summed. */
  void
  visit (int i, const Messages& in, Messages& out, bool to_right, bool to_left, const Small& a_in, const Small& c_in)
  {
    const auto rung = rungs_[i];
    Small fresh;
    maxToColumns (a_in, rung, fresh);
    assign (out.associationToCluster (i), fresh);
    maxToRows (c_in, rung, fresh);
    assign (out.clusterToAssociation (i), fresh);
    if (to_right && i + 1 < n_) {
      maxToColumns (a_in - in.associationBackward (i) + in.clusterToAssociation (i),
                    association_.pairwise[i], fresh);
      assign (out.associationForward (i), fresh);
      maxToColumns (c_in - in.clusterBackward (i) + in.associationToCluster (i), edge (i), fresh);
      assign (out.clusterForward (i), fresh);
    }
    if (to_left && i > 0) {
      maxToRows (a_in - in.associationForward (i - 1) + in.clusterToAssociation (i),
                 association_.pairwise[i - 1], fresh);
      assign (out.associationBackward (i - 1), fresh);
      maxToRows (c_in - in.clusterForward (i - 1) + in.associationToCluster (i), edge (i - 1), fresh);
      assign (out.clusterBackward (i - 1), fresh);
    }
  }

  void
  sweep ()
  {
    for (int i = 0; i < n_; ++i)
      visitAndUpdateMap (i, true);
    for (int i = n_ - 1; i >= 0; --i)
      visitAndUpdateMap (i, false);
  }

  /** A sweep's step: node i sends its messages one way, then takes its MAP states.
   *  Its incoming chain messages are not among those it sends, so both use one sum. */
  void
  visitAndUpdateMap (int i, bool to_right)
  {
    const Small a_in = associationIncoming (messages_, i), c_in = clusterIncoming (messages_, i);
    visit (i, messages_, messages_, to_right, !to_right, a_in, c_in);
    updateMap (i, a_in + messages_.clusterToAssociation (i), c_in + messages_.associationToCluster (i));
  }

  void
  flood ()
  {
    Messages next = messages_;
    for (int i = 0; i < n_; ++i)
      visit (i, messages_, next, true, true);
    messages_ = std::move (next);
    for (int i = 0; i < n_; ++i)
      updateMap (i);
  }

  /** The pair (s_i → t_j) of point i in its MAP states, added to (sign +1) or
   *  removed from (−1) its cluster's running sums. */
  void
  accumulate (int i, int state, int cluster, double sign)
  {
    if (cluster < 0 || cluster >= clusters_ || state < 0 || state >= g_.candidates.count (i))
      return;
    fits_[cluster].add (g_.source.col (i), g_.target.col (g_.candidates.target (i, state)), sign);
  }

  /** Closed-form refit (eq. 6) of a cluster that still holds enough pairs. */
  void
  refit (int cluster)
  {
    if (cluster < 0 || cluster >= clusters_)
      return;
    const RigidFitAccumulator& fit = fits_[cluster];
    if (fit.weight () >= options_.min_fit_points - 0.5 && fit.isWellPosed ())
      motions_[cluster] = fit.solve ();
  }

  void
  seedFits (const std::vector<int>& association, const std::vector<int>& cluster)
  {
    fits_.assign (static_cast<std::size_t> (clusters_), RigidFitAccumulator ());
    map_association_ = association;
    map_cluster_ = cluster;
    for (int i = 0; i < n_; ++i)  // the initial motions stand until the first refit
      accumulate (i, association[i], cluster[i], 1.0);
  }

  /** Node i's MAP states from its beliefs; on a change, its pair moves between the
   *  running sums in O(1) (the motions are solved from them after the iteration). */
  void
  updateMap (int i)
  {
    updateMap (i, associationIncoming (messages_, i) + messages_.clusterToAssociation (i),
               clusterIncoming (messages_, i) + messages_.associationToCluster (i));
  }

  /** updateMap () from node i's association and cluster beliefs. */
  void
  updateMap (int i, const Small& association_belief, const Small& cluster_belief)
  {
    const int a = static_cast<int> (argmax (association_belief));
    const int c = static_cast<int> (argmax (cluster_belief));
    if (a == map_association_[i] && c == map_cluster_[i])
      return;
    ++changes_;
    accumulate (i, map_association_[i], map_cluster_[i], -1.0);
    accumulate (i, a, c, 1.0);
    map_association_[i] = a;
    map_cluster_[i] = c;
  }

  const LadderGeometry& g_;
  const crf::ChainPotentials& association_;
  const Eigen::VectorXd& w_;
  const LadderOptions options_;
  std::vector<Rigid2d> motions_;
  const int n_;
  const int clusters_;
  Messages messages_;
  std::vector<RigidFitAccumulator> fits_;
  std::vector<int> map_association_;
  std::vector<int> map_cluster_;
  int changes_ = 0;      // MAP changes in this iteration
  double change_ = 0.0;  // largest message change in this iteration (log domain)
  RungPotentials rungs_;       // S_i x (K + 1) per point
  std::vector<double> edges_;  // (K + 1) x (K + 1) per chain edge, column-major, edge after edge
  std::vector<Rigid2d> motions_computed_;  // the motions rungs_ and edges_ hold
};

void
validate (const LadderGeometry& geometry, const crf::ChainPotentials& association, const Eigen::VectorXd& weights,
          const std::vector<Rigid2d>& motions, const std::vector<int>& initial_association,
          const std::vector<int>& initial_cluster, const LadderOptions& options)
{
  const int n = geometry.size ();
  const std::string geometry_problem = ladderGeometryProblem (geometry);
  if (!geometry_problem.empty ())
    fail (geometry_problem);
  if (weights.size () != kJointWeightCount || !weights.allFinite ())
    fail ("expected " + std::to_string (kJointWeightCount) + " finite weights, got " + std::to_string (weights.size ()) +
          (weights.allFinite () ? "" : " holding NaN or infinite values"));
  if (motions.empty ())
    fail ("at least one cluster motion is needed");
  if (static_cast<int> (motions.size ()) + 1 > kMaxStates)
    fail ("at most " + std::to_string (kMaxStates - 1) + " clusters are supported");
  if (geometry.candidates.size () != n || static_cast<int> (association.unary.size ()) != n ||
      static_cast<int> (association.pairwise.size ()) != std::max (n - 1, 0))
    fail ("the association chain does not have one node per source point");
  if (static_cast<int> (initial_association.size ()) != n || static_cast<int> (initial_cluster.size ()) != n)
    fail ("the initial labels need one entry per source point");
  for (int i = 0; i < n; ++i) {
    if (association.unary[i].size () != geometry.associationStates (i))
      fail ("node " + std::to_string (i) + " has a unary potential of the wrong size");
    if (geometry.associationStates (i) > kMaxStates)
      fail ("node " + std::to_string (i) + " has more than " + std::to_string (kMaxStates - 1) + " candidates");
    if (initial_association[i] < 0 || initial_association[i] >= geometry.associationStates (i) ||
        initial_cluster[i] < 0 || initial_cluster[i] > static_cast<int> (motions.size ()))
      fail ("the initial state of node " + std::to_string (i) + " is out of range");
  }
  validateLadderOptions (options);
}

}  // namespace

void
validateLadderOptions (const LadderOptions& options)
{
  if (options.max_iterations < 1 || !(options.damping >= 0.0 && options.damping < 1.0) ||
      options.min_fit_points < 2 || !(options.tolerance >= 0.0))
    fail ("invalid options: max_iterations >= 1, damping in [0, 1), min_fit_points >= 2, tolerance >= 0");
  if (options.schedule != MessageSchedule::Flooding && options.schedule != MessageSchedule::Sweep)
    fail ("invalid options: schedule must be MessageSchedule::Flooding or MessageSchedule::Sweep, got " +
          std::to_string (static_cast<int> (options.schedule)));
  if (options.evidence != ClusterEvidence::MapAssociation && options.evidence != ClusterEvidence::BestAssociation)
    fail ("invalid options: evidence must be ClusterEvidence::MapAssociation or ClusterEvidence::BestAssociation, "
          "got " + std::to_string (static_cast<int> (options.evidence)));
}

LadderResult
inferLadder (const LadderGeometry& geometry, const crf::ChainPotentials& association, const Eigen::VectorXd& weights,
             const std::vector<Rigid2d>& motions, const std::vector<int>& initial_association,
             const std::vector<int>& initial_cluster, const LadderOptions& options)
{
  validate (geometry, association, weights, motions, initial_association, initial_cluster, options);
  if (geometry.size () == 0) {
    LadderResult empty;
    empty.motions = motions;
    empty.converged = true;
    return empty;
  }
  Ladder ladder (geometry, association, weights, motions, options);
  return ladder.run (initial_association, initial_cluster);
}

}  // namespace joint
}  // namespace pcl_crf
