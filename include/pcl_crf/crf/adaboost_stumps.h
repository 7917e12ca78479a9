#pragma once

#include <Eigen/Core>

#include <iosfwd>
#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Discrete AdaBoost over decision stumps (Freund & Schapire, 1997), the
 *  binary classifier CRF-Matching turns into unary features (Ramos et al., RSS 2007).
 *
 *  The strong classifier is H(x) = Σ_t α_t h_t(x) with h_t(x) ∈ {−1, +1};
 *  probability(x) = 1 / (1 + exp(−2 H(x))) (Friedman, Hastie & Tibshirani, 2000).
 *  Training sorts every feature column once; each round then scans all thresholds
 *  in O(n·d).
 *
 *  \code
 *  pcl_crf::crf::AdaBoostStumps booster;
 *  booster.train (X, y, 50);                          // X: n x d, y: 0/1
 *  const double p = booster.probability (X.row (0).transpose ());
 *  std::ofstream file ("booster.txt");               // #include <fstream>
 *  booster.write (file);
 *  \endcode
 */
class AdaBoostStumps
{
public:
  /** \brief One weak learner h(x) = polarity if x[feature] > threshold else −polarity. */
  struct Stump
  {
    /** feature index; −1 marks a constant stump (h(x) = polarity), used when y has one class. */
    int feature = -1;
    double threshold = 0.0;
    /** +1 or −1. */
    int polarity = 1;
    /** vote weight α = ½ ln((1 − ε) / ε), ε clamped to ≥ kMinimumError. */
    double alpha = 0.0;

    int
    predict (const Eigen::Ref<const Eigen::VectorXd>& x) const
    {
      if (feature < 0)
        return polarity;
      return x (feature) > threshold ? polarity : -polarity;
    }
  };

  /** \brief Weighted error below which a stump counts as perfect: it caps α at
   *  ½ ln((1 − 1e-10) / 1e-10) ≈ 11.5 and ends training. */
  static constexpr double kMinimumError = 1e-10;

  /** \brief Trains from scratch (replaces any previous model).
   *  Stops early when a stump is perfect or no stump beats chance (ε ≥ ½).
   *  \param[in] X n x d samples (one per row), finite
   *  \param[in] y n labels, 0 or 1
   *  \param[in] rounds maximum number of stumps (≥ 1); default 50
   *  \throws std::invalid_argument for empty X, size mismatch, labels not 0/1,
   *  NaN or infinite features, rounds < 1.
   */
  void
  train (const Eigen::MatrixXd& X, const std::vector<int>& y, int rounds = 50);

  /** \brief Σ_t α_t h_t(x); 0 for an untrained model. x needs at least getDimension () entries.
   *  \throws std::invalid_argument when x is too short. */
  double
  margin (const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /** \brief p(y = 1 | x) = 1 / (1 + exp(−2 · margin(x))). */
  double
  probability (const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /** \brief Writes the model as text (exact round trip of every number). */
  void
  write (std::ostream& os) const;

  /** \brief Reads a model written by write (); the model is unchanged on error.
   *  \throws std::runtime_error naming the line and what is malformed. */
  void
  read (std::istream& is);

  const std::vector<Stump>&
  getStumps () const { return stumps_; }

  /** \brief Number of features d the model was trained on. */
  int
  getDimension () const { return dimension_; }

private:
  std::vector<Stump> stumps_;
  int dimension_ = 0;
};

}  // namespace crf
}  // namespace pcl_crf
