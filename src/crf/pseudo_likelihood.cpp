#include <pcl_crf/crf/pseudo_likelihood.h>
#include <pcl_crf/crf/log_space.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::PseudoLikelihood] " + what);
}

using StridedRows = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

/** Rows f_p(i−1, y_left, s) for every state s of node i (stride S_{i−1} in the edge matrix). */
StridedRows
rowsGivenLeft (const Eigen::MatrixXd& edge, int states_left, int y_left)
{
  const Eigen::Index states_right = edge.rows () / states_left;
  return StridedRows (edge.data () + y_left, states_right, edge.cols (),
                      Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic> (edge.rows (), states_left));
}

/** Rows f_p(i, s, y_right) for every state s of node i (a contiguous block). */
Eigen::Block<const Eigen::MatrixXd>
rowsGivenRight (const Eigen::MatrixXd& edge, int states_here, int y_right)
{
  return edge.middleRows (ChainFeatures::pairRow (0, y_right, states_here), states_here);
}

/** grad += F^T p − F.row(y)^T: expected minus observed features of one factor. */
template <typename Features, typename Gradient> void
addExpectedMinusObserved (const Features& f, const Eigen::VectorXd& p, int y, Gradient grad)
{
  grad.noalias () += f.transpose () * p;
  grad -= f.row (y).transpose ();
}

void
checkLabels (const LabelledChain& chain, std::size_t c)
{
  const std::string name = "chain " + std::to_string (c);
  if (chain.labels.size () != chain.features.size ())
    fail (name + " has " + std::to_string (chain.labels.size ()) + " labels for " +
          std::to_string (chain.features.size ()) + " nodes");
  for (std::size_t i = 0; i < chain.labels.size (); ++i)
    if (chain.labels[i] < 0 || chain.labels[i] >= chain.features.states (i))
      fail (name + ": label " + std::to_string (chain.labels[i]) + " of node " + std::to_string (i) +
            " is out of range");
}

}  // namespace

bool
hasAnEdge (const std::vector<LabelledChain>& chains)
{
  return std::any_of (chains.begin (), chains.end (), [] (const LabelledChain& c) { return !c.features.pairwise.empty (); });
}

PseudoLikelihood::PseudoLikelihood (std::vector<LabelledChain> chains, double prior_sigma)
  : chains_ (std::move (chains))
{
  setPriorSigma (prior_sigma);
  bool have_nodes = false, have_edges = false;
  for (std::size_t c = 0; c < chains_.size (); ++c)
  {
    const ChainFeatures& f = chains_[c].features;
    f.validate ();
    checkLabels (chains_[c], c);
    if (f.size () > 0 && have_nodes && f.unaryDimension () != unary_dimension_)
      fail ("chain " + std::to_string (c) + " has D_u = " + std::to_string (f.unaryDimension ()) +
            ", an earlier chain " + std::to_string (unary_dimension_));
    if (!f.pairwise.empty () && have_edges && f.pairwiseDimension () != pairwise_dimension_)
      fail ("chain " + std::to_string (c) + " has D_p = " + std::to_string (f.pairwiseDimension ()) +
            ", an earlier chain " + std::to_string (pairwise_dimension_));
    if (f.size () > 0 && !have_nodes)
      unary_dimension_ = f.unaryDimension ();
    if (!f.pairwise.empty () && !have_edges)
      pairwise_dimension_ = f.pairwiseDimension ();
    have_nodes = have_nodes || f.size () > 0;
    have_edges = have_edges || !f.pairwise.empty ();
  }
}

void
PseudoLikelihood::setPriorSigma (double prior_sigma)
{
  if (!(prior_sigma > 0.0))
    fail ("prior_sigma must be > 0 (+inf disables the prior)");
  prior_sigma_ = prior_sigma;
}

double
PseudoLikelihood::chainTerm (const LabelledChain& chain, const Eigen::VectorXd& w, Eigen::VectorXd& grad) const
{
  const ChainFeatures& f = chain.features;
  const std::vector<int>& y = chain.labels;
  const auto w_u = w.head (unary_dimension_);
  const auto w_p = w.tail (pairwise_dimension_);
  double value = 0.0;
  for (std::size_t i = 0; i < f.size (); ++i)
  {
    // s_i(s) = w_u·f_u(i,s) + w_p·f_p(i−1, y_{i−1}, s) + w_p·f_p(i, s, y_{i+1})
    Eigen::VectorXd score = f.unary[i] * w_u;
    if (i > 0)
      score.noalias () += rowsGivenLeft (f.pairwise[i - 1], f.states (i - 1), y[i - 1]) * w_p;
    if (i + 1 < f.size ())
      score.noalias () += rowsGivenRight (f.pairwise[i], f.states (i), y[i + 1]) * w_p;

    value += logSumExp (score) - score (y[i]);  // −log p(y_i | y_{i−1}, y_{i+1})
    const Eigen::VectorXd p = normalizedExp (score);
    addExpectedMinusObserved (f.unary[i], p, y[i], grad.head (unary_dimension_));
    if (i > 0)
      addExpectedMinusObserved (rowsGivenLeft (f.pairwise[i - 1], f.states (i - 1), y[i - 1]), p, y[i],
                                grad.tail (pairwise_dimension_));
    if (i + 1 < f.size ())
      addExpectedMinusObserved (rowsGivenRight (f.pairwise[i], f.states (i), y[i + 1]), p, y[i],
                                grad.tail (pairwise_dimension_));
  }
  return value;
}

double
PseudoLikelihood::objectiveAndGradient (const Eigen::VectorXd& w, Eigen::VectorXd& grad) const
{
  if (w.size () != getDimension ())
    fail ("objectiveAndGradient: " + std::to_string (w.size ()) + " weights, expected " +
          std::to_string (getDimension ()));
  grad = Eigen::VectorXd::Zero (w.size ());
  double value = 0.0;
  for (const LabelledChain& chain : chains_)
    value += chainTerm (chain, w, grad);
  if (std::isfinite (prior_sigma_))
  {
    // Gaussian prior: + ||w||² / (2σ²), gradient + w / σ²
    const double precision = 1.0 / (prior_sigma_ * prior_sigma_);
    value += 0.5 * precision * w.squaredNorm ();
    grad += precision * w;
  }
  return value;
}

LbfgsResult
PseudoLikelihood::train (const LbfgsOptions& options) const
{
  return train (Eigen::VectorXd::Zero (getDimension ()), options);
}

LbfgsResult
PseudoLikelihood::train (const Eigen::VectorXd& w0, const LbfgsOptions& options) const
{
  const Objective hook = [this] (const Eigen::VectorXd& w, Eigen::VectorXd& grad) {
    return objectiveAndGradient (w, grad);
  };
  return minimizeLbfgs (hook, w0, options);
}

}  // namespace crf
}  // namespace pcl_crf
