#include <pcl_crf/crf/adaboost_stumps.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

[[noreturn]] void
fail (const std::string& what)
{
  throw std::invalid_argument ("[pcl_crf::crf::AdaBoostStumps::train] " + what);
}

/** Every feature column sorted once: order[j] = sample indices by increasing X(:, j). */
struct SortedColumns
{
  std::vector<std::vector<int>> order;
  std::vector<std::vector<double>> values;
};

SortedColumns
sortColumns (const Eigen::MatrixXd& X)
{
  SortedColumns sorted;
  sorted.order.resize (X.cols ());
  sorted.values.resize (X.cols ());
  for (Eigen::Index j = 0; j < X.cols (); ++j)
  {
    std::vector<int>& order = sorted.order[j];
    order.resize (X.rows ());
    std::iota (order.begin (), order.end (), 0);
    const auto column = X.col (j);
    std::stable_sort (order.begin (), order.end (), [&] (int a, int b) { return column (a) < column (b); });
    sorted.values[j].resize (X.rows ());
    for (Eigen::Index k = 0; k < X.rows (); ++k)
      sorted.values[j][k] = column (order[k]);
  }
  return sorted;
}

/** Best stump with its weighted error. */
struct Candidate
{
  AdaBoostStumps::Stump stump;
  double error = 1.0;
};

/** Keeps the better of polarity +1 (error e_plus) and −1 (error total − e_plus). */
void
consider (Candidate& best, int feature, double threshold, double e_plus, double total)
{
  if (e_plus < best.error)
    best = {{feature, threshold, +1, 0.0}, e_plus};
  if (total - e_plus < best.error)
    best = {{feature, threshold, -1, 0.0}, total - e_plus};
}

/** Scans all thresholds of feature j in O(n). signed_weight_i = w_i y_i with y ∈ {−1, +1}.
 *  e_plus(θ) = Σ_{x ≤ θ, y = +1} w + Σ_{x > θ, y = −1} w starts at W_neg (θ = −∞). */
void
scanFeature (const SortedColumns& sorted, int j, const std::vector<double>& signed_weight, double w_neg,
             double total, Candidate& best)
{
  const std::vector<int>& order = sorted.order[j];
  const std::vector<double>& values = sorted.values[j];
  double e_plus = w_neg;
  for (std::size_t k = 0; k + 1 < order.size (); ++k)
  {
    e_plus += signed_weight[order[k]];  // sample k moves to the "x ≤ θ" side
    if (values[k] < values[k + 1])
      consider (best, j, values[k] + 0.5 * (values[k + 1] - values[k]), e_plus, total);
  }
}

Candidate
bestStump (const SortedColumns& sorted, const std::vector<int>& y, const std::vector<double>& w)
{
  std::vector<double> signed_weight (w.size ());
  double w_neg = 0.0, total = 0.0;
  for (std::size_t i = 0; i < w.size (); ++i)
  {
    signed_weight[i] = y[i] == 1 ? w[i] : -w[i];
    w_neg += y[i] == 1 ? 0.0 : w[i];
    total += w[i];
  }
  Candidate best;
  consider (best, -1, 0.0, w_neg, total);  // constant stump: always +1 errs on W_neg
  for (std::size_t j = 0; j < sorted.order.size (); ++j)
    scanFeature (sorted, static_cast<int> (j), signed_weight, w_neg, total, best);
  best.error = std::clamp (best.error / total, 0.0, 1.0);
  return best;
}

/** w_i ← w_i exp(−α y_i h(x_i)), then normalised to sum 1. */
void
reweight (const Eigen::MatrixXd& X, const std::vector<int>& y, const AdaBoostStumps::Stump& stump,
          std::vector<double>& w)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < w.size (); ++i)
  {
    const int h = stump.feature < 0 ? stump.polarity
                                    : (X (i, stump.feature) > stump.threshold ? stump.polarity : -stump.polarity);
    const int label = y[i] == 1 ? 1 : -1;
    w[i] *= std::exp (-stump.alpha * label * h);
    sum += w[i];
  }
  for (double& wi : w)
    wi /= sum;
}

void
validateTrainingSet (const Eigen::MatrixXd& X, const std::vector<int>& y, int rounds)
{
  if (X.rows () == 0 || X.cols () == 0)
    fail ("X is empty (" + std::to_string (X.rows ()) + "x" + std::to_string (X.cols ()) + ")");
  if (static_cast<Eigen::Index> (y.size ()) != X.rows ())
    fail (std::to_string (y.size ()) + " labels for " + std::to_string (X.rows ()) + " samples");
  if (rounds < 1)
    fail ("rounds must be >= 1");
  for (std::size_t i = 0; i < y.size (); ++i)
    if (y[i] != 0 && y[i] != 1)
      fail ("label of sample " + std::to_string (i) + " is " + std::to_string (y[i]) + ", expected 0 or 1");
  for (Eigen::Index j = 0; j < X.cols (); ++j)
    if (!X.col (j).allFinite ())
      fail ("feature " + std::to_string (j) + " has a NaN or infinite value");
}

}  // namespace

void
AdaBoostStumps::train (const Eigen::MatrixXd& X, const std::vector<int>& y, int rounds)
{
  validateTrainingSet (X, y, rounds);
  const SortedColumns sorted = sortColumns (X);
  std::vector<double> w (y.size (), 1.0 / static_cast<double> (y.size ()));
  std::vector<Stump> stumps;
  for (int t = 0; t < rounds; ++t)
  {
    Candidate best = bestStump (sorted, y, w);
    if (best.error >= 0.5)
      break;  // no weak learner beats chance
    const double error = std::max (best.error, kMinimumError);
    best.stump.alpha = 0.5 * std::log ((1.0 - error) / error);  // α_t = ½ ln((1 − ε_t) / ε_t)
    stumps.push_back (best.stump);
    if (best.error <= kMinimumError)
      break;  // perfect on the weighted set: more rounds would repeat this stump
    reweight (X, y, best.stump, w);
  }
  stumps_ = std::move (stumps);
  dimension_ = static_cast<int> (X.cols ());
}

double
AdaBoostStumps::margin (const Eigen::Ref<const Eigen::VectorXd>& x) const
{
  if (x.size () < dimension_)
    throw std::invalid_argument ("[pcl_crf::crf::AdaBoostStumps::margin] x has " + std::to_string (x.size ()) +
                                 " features, the model needs " + std::to_string (dimension_));
  double sum = 0.0;
  for (const Stump& stump : stumps_)
    sum += stump.alpha * stump.predict (x);
  return sum;
}

double
AdaBoostStumps::probability (const Eigen::Ref<const Eigen::VectorXd>& x) const
{
  return 1.0 / (1.0 + std::exp (-2.0 * margin (x)));
}

}  // namespace crf
}  // namespace pcl_crf
