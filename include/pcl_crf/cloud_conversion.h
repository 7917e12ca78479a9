#pragma once

#include <pcl_crf/core/beam_order.h>
#include <pcl_crf/core/planar_transform.h>

#include <pcl/console/print.h>
#include <pcl/correspondence.h>
#include <pcl/point_cloud.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {

namespace detail {

/** \brief The finite (x, y) of the cloud points \a index_at (0) … \a index_at (count − 1),
 *  in that order, as the columns of a 2 x N matrix; \a kept receives their cloud indices. */
template <typename PointT, typename IndexAt> Eigen::Matrix2Xd
finiteXY (const pcl::PointCloud<PointT>& cloud, std::size_t count, IndexAt index_at, std::vector<int>* kept)
{
  Eigen::Matrix2Xd xy (2, static_cast<Eigen::Index> (count));
  Eigen::Index n = 0;
  if (kept)
    kept->clear ();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = index_at (k);
    if (!std::isfinite (cloud[i].x) || !std::isfinite (cloud[i].y))
      continue;
    xy.col (n++) << cloud[i].x, cloud[i].y;
    if (kept)
      kept->push_back (static_cast<int> (i));
  }
  xy.conservativeResize (2, n);
  return xy;
}

}  // namespace detail

/** \brief Copies the (x, y) of a PCL cloud into a 2 x N matrix, in cloud order.
 *  Points with a non-finite x or y are skipped; \a kept receives the cloud index
 *  of every column (so results can be mapped back to the user's indices).
 */
template <typename PointT> Eigen::Matrix2Xd
toMatrix2X (const pcl::PointCloud<PointT>& cloud, std::vector<int>* kept = nullptr)
{
  return detail::finiteXY (cloud, cloud.size (), [] (std::size_t k) { return k; }, kept);
}

/** \brief Copies the (x, y) of the points of \a cloud at \a indices, in that order, into a
 *  2 x N matrix. Points with a non-finite x or y are skipped; \a kept receives the cloud
 *  index of every column. Every index must be a point of the cloud (firstIndexOutside).
 */
template <typename PointT, typename Index> Eigen::Matrix2Xd
toMatrix2X (const pcl::PointCloud<PointT>& cloud, const std::vector<Index>& indices, std::vector<int>* kept = nullptr)
{
  return detail::finiteXY (
      cloud, indices.size (), [&indices] (std::size_t k) { return static_cast<std::size_t> (indices[k]); }, kept);
}

namespace detail {

/** \brief Sorts \a correspondences by source point (index_query), in cloud order
 *  whatever order the chains read the cloud in (a clockwise or shuffled one). */
inline void
sortByQuery (pcl::Correspondences& correspondences)
{
  std::sort (correspondences.begin (), correspondences.end (),
             [] (const pcl::Correspondence& a, const pcl::Correspondence& b) { return a.index_query < b.index_query; });
}

/** \brief \a xy without its points at the sensor itself, (0, 0) (−0 too), and \a kept
 *  without theirs: a range of 0 is what drivers report for a beam without a return, so
 *  such a point is no surface (as pcl_crf::isReturn () says for the datasets). */
inline Eigen::Matrix2Xd
dropSensorOrigin (Eigen::Matrix2Xd xy, std::vector<int>& kept)
{
  Eigen::Index n = 0;
  for (Eigen::Index k = 0; k < xy.cols (); ++k)
    if (xy (0, k) != 0.0 || xy (1, k) != 0.0) {
      xy.col (n) = xy.col (k);
      kept[static_cast<std::size_t> (n)] = kept[static_cast<std::size_t> (k)];
      ++n;
    }
  xy.conservativeResize (2, n);
  kept.resize (static_cast<std::size_t> (n));
  return xy;
}

/** \brief \a xy with its columns, and \a kept with them, in beam order counter-clockwise
 *  (beamOrder ()): unchanged when they are in one. */
inline Eigen::Matrix2Xd
putInBeamOrder (Eigen::Matrix2Xd xy, std::vector<int>& kept)
{
  if (inBeamOrder (xy))
    return xy;
  const std::vector<int> order = beamOrder (xy);
  Eigen::Matrix2Xd ordered (2, xy.cols ());
  std::vector<int> ordered_kept (kept.size ());
  for (std::size_t k = 0; k < order.size (); ++k) {
    ordered.col (static_cast<Eigen::Index> (k)) = xy.col (order[k]);
    ordered_kept[k] = kept[static_cast<std::size_t> (order[k])];
  }
  kept = std::move (ordered_kept);
  return ordered;
}

}  // namespace detail

/** \brief toMatrix2X () of a laser scan for the CRF chains: its returns (points at the
 *  sensor itself, x = y = 0, are left out as well: a range of 0 is what drivers report
 *  for a beam without a return) in beam order (beamOrder (): the cloud's order when
 *  that is one, counter-clockwise; backwards when it goes clockwise; a cloud through
 *  pcl::VoxelGrid, a kd-tree or a shuffle is sorted by bearing). \a kept receives the
 *  cloud index of every column, so that results map back to the user's points. */
template <typename PointT> Eigen::Matrix2Xd
scanToMatrix2X (const pcl::PointCloud<PointT>& cloud, std::vector<int>& kept)
{
  return detail::putInBeamOrder (detail::dropSensorOrigin (toMatrix2X (cloud, &kept), kept), kept);
}

/** \brief scanToMatrix2X () of the points of \a cloud at \a indices. */
template <typename PointT, typename Index> Eigen::Matrix2Xd
scanToMatrix2X (const pcl::PointCloud<PointT>& cloud, const std::vector<Index>& indices, std::vector<int>& kept)
{
  return detail::putInBeamOrder (detail::dropSensorOrigin (toMatrix2X (cloud, indices, &kept), kept), kept);
}

/** \brief The position in \a indices of the first index outside a cloud of \a size
 *  points (negative or too large), or -1 when every index is a point of the cloud. */
template <typename Index> long
firstIndexOutside (const std::vector<Index>& indices, std::size_t size)
{
  for (std::size_t k = 0; k < indices.size (); ++k)
    if (indices[k] < 0 || static_cast<std::size_t> (indices[k]) >= size)
      return static_cast<long> (k);
  return -1;
}

/** \brief The position in \a indices of the first index that repeats an earlier one, or
 *  -1 when none does. Every index must be a point of a cloud of \a size points
 *  (firstIndexOutside ()). */
template <typename Index> long
firstRepeatedIndex (const std::vector<Index>& indices, std::size_t size)
{
  std::vector<bool> seen (size, false);
  for (std::size_t k = 0; k < indices.size (); ++k) {
    const auto i = static_cast<std::size_t> (indices[k]);
    if (seen[i])
      return static_cast<long> (k);
    seen[i] = true;
  }
  return -1;
}

/** \brief Why \a indices cannot name points of the \a name cloud ("source" or
 *  "target") of \a size points, or "" when they can: an index outside the cloud
 *  (firstIndexOutside ()), or one given twice (firstRepeatedIndex (): a source point is
 *  one node of the chains, a target point one candidate). */
template <typename Index> std::string
indicesProblem (const std::vector<Index>& indices, std::size_t size, const std::string& name = "source")
{
  const long outside = firstIndexOutside (indices, size);
  if (outside >= 0)
    return name + " index " + std::to_string (indices[outside]) + " (position " + std::to_string (outside) +
           " of the indices) is not a point of the " + std::to_string (size) + "-point " + name + " cloud";
  const long repeated = firstRepeatedIndex (indices, size);
  if (repeated >= 0)
    return name + " index " + std::to_string (indices[repeated]) + " (position " + std::to_string (repeated) +
           " of the indices) is given twice: every point is one " +
           (name == "source" ? "node of the chain" : "candidate");
  return "";
}

/** \brief Why the finite points of \a cloud do not fit PCL's single precision
 *  (kMaxCoordinate, for |x|, |y| and |z|), naming the first point beyond it, or "" when all fit.
 *  \param[in] name "source" or "target", for the message */
template <typename PointT> std::string
coordinateProblem (const pcl::PointCloud<PointT>& cloud, const std::string& name)
{
  for (std::size_t i = 0; i < cloud.size (); ++i) {
    const Eigen::Vector3d xyz = cloud[i].getVector3fMap ().template cast<double> ();
    const bool beyond = (xyz.array ().isFinite () && xyz.array ().abs () > kMaxCoordinate).any ();
    if (beyond)
      return name + " point " + std::to_string (i) +
             " has a coordinate beyond 1e18 m: its squared distances do not fit PCL's single-precision points";
  }
  return "";
}

/** \brief Why the PCL classes cannot take their inputs, or "" when they can: the
 *  indicesProblem () of \a indices, then the coordinateProblem () of \a source and of
 *  \a target; each is checked when given (not null). */
template <typename Index, typename PointSource, typename PointTarget> std::string
inputProblem (const std::vector<Index>* indices, const pcl::PointCloud<PointSource>* source,
              const pcl::PointCloud<PointTarget>* target)
{
  std::string problem = indices && source ? indicesProblem (*indices, source->size ()) : "";
  if (problem.empty () && source)
    problem = coordinateProblem (*source, "source");
  if (problem.empty () && target)
    problem = coordinateProblem (*target, "target");
  return problem;
}

/** \brief toRigid2d (\a M), with a PCL_WARN naming what it drops when \a M is a finite
 *  transform that is not planar (nonPlanarPart ()): a guess or odometry in 3D, or one
 *  that scales. A non-finite \a M is left to the caller's own check.
 *  \param[in] where "Class::method", for the message */
template <typename Scalar> Rigid2d
toRigid2dWarning (const Eigen::Matrix<Scalar, 4, 4>& M, const std::string& where)
{
  if (M.allFinite ()) {
    const std::string lost = nonPlanarPart (M);
    if (!lost.empty ())
      PCL_WARN ("[pcl_crf::%s] the transform %s: only its rotation about z and its x/y translation are used\n",
                where.c_str (), lost.c_str ());
  }
  return toRigid2d (M);
}

/** \brief Makes a PCL cloud (z = 0) from a 2 x N matrix. */
template <typename PointT> void
fromMatrix2X (const Eigen::Matrix2Xd& xy, pcl::PointCloud<PointT>& cloud)
{
  cloud.resize (static_cast<std::size_t> (xy.cols ()));
  for (Eigen::Index i = 0; i < xy.cols (); ++i) {
    cloud[i].x = static_cast<float> (xy (0, i));
    cloud[i].y = static_cast<float> (xy (1, i));
    cloud[i].z = 0.0f;
  }
  cloud.width = static_cast<std::uint32_t> (cloud.size ());
  cloud.height = 1;
  cloud.is_dense = true;
}

}  // namespace pcl_crf
