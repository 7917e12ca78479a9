#include <pcl_crf/clustering/cluster_merging.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace clustering {

namespace {

/** Running N_eff bookkeeping over the active clusters: per point Σ_c p_c and
 *  Σ_c p_c², per cluster the sum of its points' N_eff (Eq. (8)); removing a cluster
 *  updates them in O(n). */
class EffectiveCounts
{
public:
  EffectiveCounts (const Eigen::MatrixXd& p, const std::vector<int>& labels)
    : p_ (p), total_ (p.colwise ().sum ().transpose ()), squares_ (p.colwise ().squaredNorm ().transpose ()),
      active_ (static_cast<std::size_t> (p.rows ()), 1), neff_sum_ (Eigen::VectorXd::Zero (p.rows ())),
      count_ (Eigen::VectorXd::Zero (p.rows ())), neff_ (p.cols ()),
      moves_ (static_cast<std::size_t> (p.cols ()), 0), ranked_count_ (static_cast<std::size_t> (p.cols ()), 0)
  {
    for (std::size_t i = 0; i < labels.size (); ++i)
    {
      neff_ (static_cast<Eigen::Index> (i)) = neff (static_cast<Eigen::Index> (i));
      neff_sum_ (labels[i]) += neff_ (static_cast<Eigen::Index> (i));
      count_ (labels[i]) += 1.0;
    }
  }

  /** The active cluster with points whose average N_eff is highest, and that average (−1: none). */
  std::pair<int, double>
  worst () const
  {
    std::pair<int, double> result (-1, -1.0);
    for (Eigen::Index l = 0; l < p_.rows (); ++l)
      if (active_[l] && count_ (l) > 0.0 && neff_sum_ (l) / count_ (l) > result.second)
        result = {static_cast<int> (l), neff_sum_ (l) / count_ (l)};
    return result;
  }

  /** Removes cluster r; its points go to their most probable active cluster. */
  void
  remove (int r, std::vector<int>& labels)
  {
    active_[r] = 0;
    for (std::size_t k = 0; k < labels.size (); ++k)
    {
      const auto i = static_cast<Eigen::Index> (k);
      neff_sum_ (labels[k]) -= neff_ (i);
      count_ (labels[k]) -= 1.0;
      total_ (i) -= p_ (r, i);
      squares_ (i) -= p_ (r, i) * p_ (r, i);
      if (labels[k] == r)
        labels[k] = bestActive (i);
      neff_ (i) = neff (i);
      neff_sum_ (labels[k]) += neff_ (i);
      count_ (labels[k]) += 1.0;
    }
  }

  bool
  isActive (int l) const { return active_[l] != 0; }

  int
  activeCount () const { return static_cast<int> (std::count (active_.begin (), active_.end (), 1)); }

private:
  double
  neff (Eigen::Index i) const
  {
    return squares_ (i) > 0.0 ? total_ (i) * total_ (i) / squares_ (i) : 0.0;  // Eq. (8) with p / Σp
  }

  /** The most probable active cluster of point i, the lowest index on ties: a scan of
   *  the clusters for its first kScans moves; after that the point keeps its kRanked
   *  most probable active clusters, ranked then and again once all have been removed,
   *  so that a point moved from cluster to cluster (thousands of copies of one point,
   *  say) costs O(L) per kRanked removals, not per removal. */
  int
  bestActive (Eigen::Index i)
  {
    if (++moves_[static_cast<std::size_t> (i)] <= kScans) {
      int best = -1;
      for (Eigen::Index l = 0; l < p_.rows (); ++l)
        if (active_[l] && (best < 0 || p_ (l, i) > p_ (best, i)))
          best = static_cast<int> (l);
      return best;
    }
    if (ranked_.empty ())
      ranked_.resize (static_cast<std::size_t> (p_.cols ()) * kRanked);
    int* ranked = ranked_.data () + i * kRanked;
    int& count = ranked_count_[static_cast<std::size_t> (i)];
    for (int k = 0; k < count; ++k)
      if (active_[ranked[k]])
        return ranked[k];
    scratch_.clear ();
    for (Eigen::Index l = 0; l < p_.rows (); ++l)
      if (active_[l])
        scratch_.push_back (static_cast<int> (l));
    count = static_cast<int> (std::min<std::size_t> (kRanked, scratch_.size ()));
    std::partial_sort (scratch_.begin (), scratch_.begin () + count, scratch_.end (), [this, i] (int a, int b) {
      return p_ (a, i) > p_ (b, i) || (p_ (a, i) == p_ (b, i) && a < b);
    });
    std::copy (scratch_.begin (), scratch_.begin () + count, ranked);
    return count > 0 ? ranked[0] : -1;
  }

  static constexpr int kScans = 4;
  static constexpr int kRanked = 16;

  const Eigen::MatrixXd& p_;
  Eigen::VectorXd total_, squares_;
  std::vector<char> active_;  // not vector<bool>: bestActive () reads it for every point of a removed cluster
  Eigen::VectorXd neff_sum_, count_;
  Eigen::VectorXd neff_;  // N_eff of every point as last added to neff_sum_
  std::vector<int> moves_;         // per point: bestActive () calls so far
  std::vector<int> ranked_;        // kRanked per point (bestActive ()), allocated when first needed
  std::vector<int> ranked_count_;  // per point: how many of its kRanked are ranked (0: none yet)
  std::vector<int> scratch_;       // the active clusters, while ranking
};

void
checkSizes (const Eigen::MatrixXd& p, const std::vector<int>& labels)
{
  if (static_cast<Eigen::Index> (labels.size ()) != p.cols ())
    throw std::invalid_argument ("[pcl_crf::clustering::selectClusters] " + std::to_string (labels.size ()) +
                                 " labels for " + std::to_string (p.cols ()) + " probability columns");
  for (const int l : labels)
    if (l < 0 || l >= p.rows ())
      throw std::invalid_argument ("[pcl_crf::clustering::selectClusters] label " + std::to_string (l) +
                                   " is outside [0, " + std::to_string (p.rows ()) + ")");
}

}  // namespace

void
keepClusters (const std::vector<int>& kept, Eigen::MatrixXd& marginals, std::vector<int>& labels)
{
  if (static_cast<Eigen::Index> (labels.size ()) != marginals.cols ())
    throw std::invalid_argument ("[pcl_crf::clustering::keepClusters] " + std::to_string (labels.size ()) +
                                 " labels for " + std::to_string (marginals.cols ()) + " nodes' marginals");
  std::vector<int> new_index (static_cast<std::size_t> (marginals.rows ()), -1);
  Eigen::MatrixXd reduced (static_cast<Eigen::Index> (kept.size ()), marginals.cols ());
  for (std::size_t k = 0; k < kept.size (); ++k)
  {
    if (kept[k] < 0 || kept[k] >= marginals.rows () || new_index[kept[k]] >= 0)
      throw std::invalid_argument ("[pcl_crf::clustering::keepClusters] kept cluster " + std::to_string (kept[k]) +
                                   " is not one of the " + std::to_string (marginals.rows ()) +
                                   " clusters, or is kept twice");
    new_index[kept[k]] = static_cast<int> (k);
    reduced.row (k) = marginals.row (kept[k]);
  }
  for (std::size_t i = 0; i < labels.size (); ++i)
  {
    if (labels[i] < 0 || labels[i] >= marginals.rows () || new_index[labels[i]] < 0)
      throw std::invalid_argument ("[pcl_crf::clustering::keepClusters] node " + std::to_string (i) +
                                   " is labelled with a cluster that is not kept");
    labels[i] = new_index[labels[i]];
    const double total = reduced.col (i).sum ();
    if (total > 0.0)
      reduced.col (i) /= total;
    else
      reduced.col (i) = Eigen::VectorXd::Unit (reduced.rows (), labels[i]);
  }
  marginals.swap (reduced);
}

double
effectiveClusterCount (const Eigen::Ref<const Eigen::VectorXd>& p)
{
  const double total = p.sum ();
  const double squares = p.squaredNorm ();
  return squares > 0.0 ? total * total / squares : 0.0;  // Eq. (8) with p / Σp
}

std::vector<int>
selectClusters (const Eigen::MatrixXd& probabilities, std::vector<int>& labels, double max_average_neff)
{
  checkSizes (probabilities, labels);
  EffectiveCounts counts (probabilities, labels);
  while (counts.activeCount () > 1)
  {
    const std::pair<int, double> worst = counts.worst ();
    if (worst.first < 0 || worst.second <= max_average_neff)
      break;
    counts.remove (worst.first, labels);  // its points go to their second-best cluster
  }
  std::vector<int> kept;
  for (Eigen::Index l = 0; l < probabilities.rows (); ++l)
    if (counts.isActive (static_cast<int> (l)) &&
        std::find (labels.begin (), labels.end (), static_cast<int> (l)) != labels.end ())
      kept.push_back (static_cast<int> (l));
  return kept;
}

std::vector<int>
mergeAmbiguousClusters (Eigen::MatrixXd& marginals, std::vector<int>& labels, double max_average_neff)
{
  const std::vector<int> kept = selectClusters (marginals, labels, max_average_neff);
  keepClusters (kept, marginals, labels);
  return kept;
}

}  // namespace clustering
}  // namespace pcl_crf
