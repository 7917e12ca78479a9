#include <pcl_crf/simulation/rigid_math.h>

namespace pcl_crf {
namespace simulation {

Rigid2d
composeRigid (const Rigid2d& A, const Rigid2d& B)
{
  const double a00 = A.linear () (0, 0), a01 = A.linear () (0, 1), a10 = A.linear () (1, 0), a11 = A.linear () (1, 1);
  const double b00 = B.linear () (0, 0), b01 = B.linear () (0, 1), b10 = B.linear () (1, 0), b11 = B.linear () (1, 1);
  const double bx = B.translation ().x (), by = B.translation ().y ();
  Rigid2d C = Rigid2d::Identity ();
  C.linear () (0, 0) = a00 * b00 + a01 * b10;
  C.linear () (0, 1) = a00 * b01 + a01 * b11;
  C.linear () (1, 0) = a10 * b00 + a11 * b10;
  C.linear () (1, 1) = a10 * b01 + a11 * b11;
  C.translation ().x () = (a00 * bx + a01 * by) + A.translation ().x ();
  C.translation ().y () = (a10 * bx + a11 * by) + A.translation ().y ();
  return C;
}

Rigid2d
invertRigid (const Rigid2d& T)
{
  const double r00 = T.linear () (0, 0), r01 = T.linear () (0, 1), r10 = T.linear () (1, 0), r11 = T.linear () (1, 1);
  const double tx = T.translation ().x (), ty = T.translation ().y ();
  Rigid2d I = Rigid2d::Identity ();
  I.linear () (0, 0) = r00;
  I.linear () (0, 1) = r10;
  I.linear () (1, 0) = r01;
  I.linear () (1, 1) = r11;
  I.translation ().x () = -(r00 * tx + r10 * ty);
  I.translation ().y () = -(r01 * tx + r11 * ty);
  return I;
}

Eigen::Vector2d
transformPoint (const Rigid2d& T, const Eigen::Vector2d& p)
{
  const double x = (T.linear () (0, 0) * p.x () + T.linear () (0, 1) * p.y ()) + T.translation ().x ();
  const double y = (T.linear () (1, 0) * p.x () + T.linear () (1, 1) * p.y ()) + T.translation ().y ();
  return {x, y};
}

double
dot2 (const Eigen::Vector2d& u, const Eigen::Vector2d& v)
{
  return u.x () * v.x () + u.y () * v.y ();
}

double
squaredDistance2 (const Eigen::Vector2d& p, const Eigen::Vector2d& q)
{
  const double dx = p.x () - q.x (), dy = p.y () - q.y ();
  return dx * dx + dy * dy;
}

}  // namespace simulation
}  // namespace pcl_crf
