#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/core/scan_thinning.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief A scan pair thinned to the beam spacing a model was trained at
 *  (MatchingParameters::training_beam_spacing): the models run on these, and
 *  their associations and labels are lifted back to every point (liftMatches).
 */
struct ThinnedPair
{
  ThinnedScan source;
  ThinnedScan target;
  /** per full source point: the kept source point that stands for it, as a
   *  position in source.kept (thinnedAnchors). */
  std::vector<int> anchors;

  /** \brief true when either scan was thinned. */
  bool
  isThinned (const Eigen::Matrix2Xd& full_source, const Eigen::Matrix2Xd& full_target) const
  {
    return source.isThinned (full_source.cols ()) || target.isThinned (full_target.cols ());
  }
};

/** \brief Thins both scans to \a model_spacing (thinToSpacing) and finds the anchors. */
ThinnedPair
thinPair (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, double model_spacing);

/** \brief Per full source point, the kept point that stands for it: itself when
 *  kept, else the nearer (Euclidean) of the kept points before and after it in scan
 *  order. \return positions in \a thinned .kept */
std::vector<int>
thinnedAnchors (const Eigen::Matrix2Xd& source, const ThinnedScan& thinned);

/** \brief Per full source point, its anchor's label (cluster, outlier flag, …).
 *  \throws std::invalid_argument for an anchor that is not a labelled point. */
std::vector<int>
liftLabels (const std::vector<int>& anchors, const std::vector<int>& coarse_labels);

/** \brief The full target indices a kept target point stands for: itself and the
 *  points dropped between it and its kept neighbours. \return [first, last]
 *  \throws std::invalid_argument when \a kept_position is not a kept point or the
 *  kept points are not points of a scan of \a full_size. */
Eigen::Vector2i
targetSpan (const ThinnedScan& target, Eigen::Index full_size, int kept_position);

/** \brief The association of the full scans from the association of the thinned ones.
 *
 *  A source point is matched when its anchor is. Its target point is the one
 *  nearest to where its anchor's motion puts it, among:
 *  - for a kept point, the full target points its match stands for (targetSpan);
 *  - for a dropped point whose other kept neighbour moves with the same motion and
 *    is matched (at most 32 kept target points away), every target point from the
 *    first of their matches' spans to the last;
 *  - for another dropped point, its anchor's match's span widened by one point.
 *
 *  When the matched kept neighbours (up to two on either side, same motion) lie on
 *  average farther from where that motion puts them than twice the thinned target's
 *  point step, the point moves differently from its motion (a mover the matcher left
 *  in the static world): their mean offset is added to where it is put.
 *
 *  \param[in] source, target the full scans [m]
 *  \param[in] thinned thinPair of them
 *  \param[in] coarse_matches per kept source point: a position in thinned.target.kept, or kNoMatch
 *  \param[in] groups per kept source point: the index in \a motions of the motion it moves with, or −1 (unmatched)
 *  \param[in] motions T_target_source of every group
 *  \return per full source point: a full target index, or kNoMatch
 */
std::vector<int>
liftMatches (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const ThinnedPair& thinned,
             const std::vector<int>& coarse_matches, const std::vector<int>& groups,
             const std::vector<Rigid2d>& motions);

}  // namespace matching
}  // namespace pcl_crf
