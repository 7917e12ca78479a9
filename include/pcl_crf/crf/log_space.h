#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <vector>

namespace pcl_crf {
namespace crf {

/** \brief Negative infinity: the log-potential of a forbidden state or transition. */
constexpr double kLogZero = -std::numeric_limits<double>::infinity ();

/** \brief True when any entry is NaN or +∞ (−∞, a forbidden state, is allowed). */
template <typename Derived> bool
hasNanOrPositiveInfinity (const Eigen::MatrixBase<Derived>& values)
{
  const auto a = values.array ();
  return (a.isNaN () || a == std::numeric_limits<typename Derived::Scalar>::infinity ()).any ();
}

/** \brief Sets every entry below the smallest normal double to exactly 0.
 *
 *  Eigen 3.4's vectorised exp clamps its argument and returns ~5.6e-309 for −∞,
 *  which would give forbidden states a non-zero probability and turn an
 *  all-forbidden log-sum-exp (−∞) into ≈ −708; denormals are also slow. Flushing
 *  costs at most 2.2e-308 absolute per entry. (A plain loop: Eigen's select() is
 *  ten times slower here.)
 */
inline void
flushDenormals (double* data, Eigen::Index size)
{
  for (Eigen::Index k = 0; k < size; ++k)
    data[k] = data[k] < std::numeric_limits<double>::min () ? 0.0 : data[k];
}

/** \brief Element-wise exp with results below the smallest normal double (x < −708.4,
 *  in particular x = −∞) set to exactly 0. See flushDenormals.
 */
template <typename Derived> typename Derived::PlainObject
safeExp (const Eigen::ArrayBase<Derived>& a)
{
  typename Derived::PlainObject e = a.exp ();
  flushDenormals (e.data (), e.size ());
  return e;
}

/** \brief log Σ_k exp(v_k), stable for large |v_k|; −∞ for an empty vector or
 *  when every entry is −∞ (all states forbidden).
 */
inline double
logSumExp (const Eigen::Ref<const Eigen::VectorXd>& v)
{
  if (v.size () == 0)
    return kLogZero;
  const double m = v.maxCoeff ();
  if (!std::isfinite (m))
    return m;
  return m + std::log (safeExp (v.array () - m).sum ());
}

/** \brief exp(v − logSumExp(v)): the probabilities of log-weights v (softmax).
 *  \note v must hold at least one finite entry.
 */
inline Eigen::VectorXd
normalizedExp (const Eigen::Ref<const Eigen::VectorXd>& v)
{
  Eigen::VectorXd p = safeExp (v.array () - logSumExp (v)).matrix ();
  return p / p.sum ();
}

/** \brief Log-space vector-matrix product (sum-product message through m):
 *  r(t) = log Σ_s exp(v(s) + m(s, t)). Column by column, no temporary matrix.
 */
Eigen::VectorXd
logVectorMatrix (const Eigen::VectorXd& v, const Eigen::MatrixXd& m);

/** \brief Log-space matrix-vector product: r(s) = log Σ_t exp(m(s, t) + v(t)).
 *  Column by column (contiguous in Eigen's storage), no temporary matrix.
 */
Eigen::VectorXd
logMatrixVector (const Eigen::MatrixXd& m, const Eigen::VectorXd& v);

/** \brief Max-sum vector-matrix product r(t) = max_s v(s) + m(s, t); when argmax is
 *  given it receives the maximising s of every t (lowest index on ties).
 */
Eigen::VectorXd
maxVectorMatrix (const Eigen::VectorXd& v, const Eigen::MatrixXd& m, std::vector<int>* argmax = nullptr);

/** \brief Max-sum matrix-vector product r(s) = max_t m(s, t) + v(t). */
Eigen::VectorXd
maxMatrixVector (const Eigen::MatrixXd& m, const Eigen::VectorXd& v);

}  // namespace crf
}  // namespace pcl_crf
