#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/candidates.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_crf {
namespace matching {

/** \brief A scan in beam order with its shape descriptor (computeShapeFeatures). */
struct ScanShape
{
  Eigen::Matrix2Xd points;
  Eigen::MatrixXd shape;
};

/** \brief The target scan prepared once per pair: points, shapes and kNN indices. */
struct PreparedTarget
{
  ScanShape scan;
  TargetIndex index;
  /** the target's segments (segmentScan). */
  std::vector<ScanSegment> segments;
  /** the target scan's unit normals (segmentNormals), for the point-to-line fit. */
  Eigen::Matrix2Xd normals;
};

/** \brief Computes the shape descriptor of a scan [points in its sensor frame, m]. */
ScanShape
describeScan (const Eigen::Matrix2Xd& points);

/** \brief Describes the target scan and builds its point and shape-embedding indices.
 *  \throws std::invalid_argument for non-finite points. */
PreparedTarget
prepareTarget (const Eigen::Matrix2Xd& target, const CandidateParameters& parameters);

/** \brief Where the source points are assumed to be during one association pass,
 *  and their candidate target points.
 *
 *  \code
 *  const pcl_crf::matching::PreparedTarget target = pcl_crf::matching::prepareTarget (pair.target, {});
 *  const pcl_crf::matching::ScanShape source = pcl_crf::matching::describeScan (pair.source);
 *  const pcl_crf::matching::PassGeometry pass =
 *      pcl_crf::matching::preparePass (source, target, T_guess, T_current, {});
 *  \endcode
 */
struct PassGeometry
{
  /** the initial guess T_target_source (from odometry): the "translation" feature. */
  Rigid2d T_guess = Rigid2d::Identity ();
  /** the current estimate T_target_source: the candidates and the "registered translation". */
  Rigid2d T_current = Rigid2d::Identity ();
  /** T_guess * source [m, target frame]. */
  Eigen::Matrix2Xd source_guess;
  /** T_current * source [m, target frame]. */
  Eigen::Matrix2Xd source_current;
  /** per source point: its segment's motion hypothesis beyond T_current and supports. */
  SegmentMotions segment_motions;
  /** the source's shape neighbours at T_current (CandidateParameters::shape_neighbours
   *  of them are candidates; empty when that is 0). */
  ShapeNeighbours shape_neighbours;
  /** candidate target points of every source point. */
  Candidates candidates;
};

/** \brief Moves the source points by both motions, finds the segment motion
 *  hypotheses and the candidates (guess neighbours around T_current * s_i, shape
 *  neighbours, segment-hypothesis neighbours).
 *  \param[in] earlier the shape neighbours of an earlier pass over the same source and
 *             target, or nullptr: reused where provably exact (updateShapeNeighbours)
 */
PassGeometry
preparePass (const ScanShape& source, const PreparedTarget& target, const Rigid2d& T_guess, const Rigid2d& T_current,
             const CandidateParameters& parameters, const ShapeNeighbours* earlier = nullptr);

/** \brief preparePass without the candidates: both motions applied, the segment
 *  motion hypotheses and the shape neighbours found, so that a caller may change the
 *  hypotheses (the joint model gives the points of a moving cluster its motion)
 *  before passCandidates. */
PassGeometry
preparePassMotions (const ScanShape& source, const PreparedTarget& target, const Rigid2d& T_guess,
                    const Rigid2d& T_current, const CandidateParameters& parameters,
                    const ShapeNeighbours* earlier = nullptr);

/** \brief The candidates of a pass from its motions and hypotheses (findCandidates). */
Candidates
passCandidates (const PreparedTarget& target, const PassGeometry& pass, const CandidateParameters& parameters);

}  // namespace matching
}  // namespace pcl_crf
