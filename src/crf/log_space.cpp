#include <pcl_crf/crf/log_space.h>

namespace pcl_crf {
namespace crf {

Eigen::VectorXd
logVectorMatrix (const Eigen::VectorXd& v, const Eigen::MatrixXd& m)
{
  Eigen::VectorXd r (m.cols ());
  Eigen::VectorXd column (m.rows ());
  for (Eigen::Index t = 0; t < m.cols (); ++t)
  {
    column = v + m.col (t);
    r (t) = logSumExp (column);
  }
  return r;
}

Eigen::VectorXd
logMatrixVector (const Eigen::MatrixXd& m, const Eigen::VectorXd& v)
{
  // Pass 1: the row maxima; pass 2: Σ_t exp(m(s, t) + v(t) − max_s), both over contiguous columns.
  const Eigen::VectorXd maxima = maxMatrixVector (m, v);
  const Eigen::ArrayXd shift = (maxima.array () == kLogZero).select (0.0, maxima.array ());
  Eigen::ArrayXd sums = Eigen::ArrayXd::Zero (m.rows ());
  Eigen::ArrayXd term (m.rows ());
  for (Eigen::Index t = 0; t < m.cols (); ++t)
  {
    term = (m.col (t).array () + (v (t) - shift)).exp ();
    flushDenormals (term.data (), term.size ());
    sums += term;
  }
  return (shift + sums.log ()).matrix ();  // rows with no allowed t: 0 + log 0 = −∞
}

Eigen::VectorXd
maxVectorMatrix (const Eigen::VectorXd& v, const Eigen::MatrixXd& m, std::vector<int>* argmax)
{
  Eigen::VectorXd r (m.cols ());
  if (argmax)
    argmax->resize (m.cols ());
  for (Eigen::Index t = 0; t < m.cols (); ++t)
  {
    Eigen::Index best = 0;
    r (t) = (v + m.col (t)).maxCoeff (&best);
    if (argmax)
      (*argmax)[t] = static_cast<int> (best);
  }
  return r;
}

Eigen::VectorXd
maxMatrixVector (const Eigen::MatrixXd& m, const Eigen::VectorXd& v)
{
  Eigen::VectorXd r = Eigen::VectorXd::Constant (m.rows (), kLogZero);
  for (Eigen::Index t = 0; t < m.cols (); ++t)
    r = r.cwiseMax (m.col (t) + Eigen::VectorXd::Constant (m.rows (), v (t)));
  return r;
}

}  // namespace crf
}  // namespace pcl_crf
