#include <pcl_crf/core/rigid_fit.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace {
constexpr double kTinyWeight = 1e-12;
}

void
RigidFitAccumulator::add (const Eigen::Vector2d& s, const Eigen::Vector2d& g, double w)
{
  if (!s.allFinite () || !g.allFinite () || !std::isfinite (w))
    throw std::invalid_argument ("[pcl_crf::RigidFitAccumulator::add] a pair or its weight is NaN or infinite");
  w_ += w;
  sum_s_ += w * s;
  sum_g_ += w * g;
  sum_sg_ += w * s * g.transpose ();
  sum_ss_ += w * s.squaredNorm ();
  sum_gg_ += w * g.squaredNorm ();
}

bool
RigidFitAccumulator::isWellPosed (double min_spread) const
{
  if (w_ <= kTinyWeight)
    return false;
  const double spread = sum_ss_ / w_ - (sum_s_ / w_).squaredNorm ();
  return spread > min_spread;
}

Rigid2d
RigidFitAccumulator::solve () const
{
  if (w_ <= kTinyWeight)
    return Rigid2d::Identity ();
  const Eigen::Vector2d s_mean = sum_s_ / w_;
  const Eigen::Vector2d g_mean = sum_g_ / w_;
  // Cross-covariance H = Σ w (s − s̄)(g − ḡ)ᵀ from the running sums.
  const Eigen::Matrix2d H = sum_sg_ - w_ * s_mean * g_mean.transpose ();
  const double theta = std::atan2 (H (0, 1) - H (1, 0), H (0, 0) + H (1, 1));
  const Eigen::Matrix2d R = Eigen::Rotation2Dd (theta).toRotationMatrix ();
  Rigid2d T = Rigid2d::Identity ();
  T.linear () = R;
  T.translation () = g_mean - R * s_mean;
  return T;
}

double
RigidFitAccumulator::residual (const Rigid2d& T) const
{
  // Σ w |R s + t − g|² expanded over the running sums.
  const Eigen::Matrix2d& R = T.linear ();
  const Eigen::Vector2d& t = T.translation ();
  const double cross_rs_g = (R * sum_sg_).trace ();  // Σ w (R s)·g
  const double value = sum_ss_ + w_ * t.squaredNorm () + sum_gg_ + 2.0 * t.dot (R * sum_s_) -
                       2.0 * cross_rs_g - 2.0 * t.dot (sum_g_);
  return std::max (value, 0.0);
}

Rigid2d
fitRigid2d (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const Eigen::VectorXd& weights)
{
  if (source.cols () != target.cols ())
    throw std::invalid_argument ("[pcl_crf::fitRigid2d] " + std::to_string (source.cols ()) +
                                 " source points but " + std::to_string (target.cols ()) + " target points");
  if (weights.size () != 0 && weights.size () != source.cols ())
    throw std::invalid_argument ("[pcl_crf::fitRigid2d] weight count differs from the point count");
  RigidFitAccumulator accumulator;
  for (Eigen::Index i = 0; i < source.cols (); ++i) {
    const double w = weights.size () ? weights (i) : 1.0;
    if (!(w >= 0.0) || !std::isfinite (w))
      throw std::invalid_argument ("[pcl_crf::fitRigid2d] weights must be finite non-negative numbers");
    if (!source.col (i).allFinite () || !target.col (i).allFinite ())
      throw std::invalid_argument ("[pcl_crf::fitRigid2d] pair " + std::to_string (i) + " has a NaN or infinite point");
    accumulator.add (source.col (i), target.col (i), w);
  }
  return accumulator.solve ();
}

}  // namespace pcl_crf
