#include <pcl_crf/matching/pass_geometry.h>
#include <pcl_crf/matching/shape_features.h>

#include <utility>

namespace pcl_crf {
namespace matching {

ScanShape
describeScan (const Eigen::Matrix2Xd& points)
{
  return {points, computeShapeFeatures (points)};
}

PreparedTarget
prepareTarget (const Eigen::Matrix2Xd& target, const CandidateParameters& parameters)
{
  PreparedTarget prepared;
  prepared.scan = describeScan (target);
  prepared.index.points.build (target);
  prepared.index.shapes.build (shapeEmbedding (prepared.scan.shape, target, parameters.shape_position_scale));
  prepared.segments = segmentScan (target, parameters.segments.breakpoint_angle, parameters.segments.range_noise);
  prepared.normals = segmentNormals (target, prepared.segments);
  return prepared;
}

namespace {

/** The shape neighbours of the source at T_current, from \a earlier where it proves them. */
ShapeNeighbours
shapeNeighboursAt (const ScanShape& source, const PreparedTarget& target, const Eigen::Matrix2Xd& source_current,
                   const CandidateParameters& parameters, const ShapeNeighbours* earlier)
{
  const int k = parameters.shape_neighbours;
  if (k <= 0)
    return {};
  Eigen::MatrixXd embedding = shapeEmbedding (source.shape, source_current, parameters.shape_position_scale);
  if (earlier != nullptr && earlier->used () >= k && earlier->queries.cols () == embedding.cols ())
    return updateShapeNeighbours (*earlier, std::move (embedding), target.index.shapes, k);
  return searchShapeNeighbours (std::move (embedding), target.index.shapes, k);
}

}  // namespace

PassGeometry
preparePassMotions (const ScanShape& source, const PreparedTarget& target, const Rigid2d& T_guess,
                    const Rigid2d& T_current, const CandidateParameters& parameters, const ShapeNeighbours* earlier)
{
  PassGeometry pass;
  pass.T_guess = T_guess;
  pass.T_current = T_current;
  pass.source_guess = T_guess * source.points;
  pass.source_current = T_current * source.points;
  pass.segment_motions = segmentMotionHypotheses (source.points, pass.source_current, target.scan.points,
                                                  target.segments, target.index.points, parameters.segments);
  pass.shape_neighbours = shapeNeighboursAt (source, target, pass.source_current, parameters, earlier);
  return pass;
}

Candidates
passCandidates (const PreparedTarget& target, const PassGeometry& pass, const CandidateParameters& parameters)
{
  return findCandidates (pass.source_current, pass.shape_neighbours, pass.segment_motions.translation,
                         pass.segment_motions.has_hypothesis, target.index, parameters);
}

PassGeometry
preparePass (const ScanShape& source, const PreparedTarget& target, const Rigid2d& T_guess, const Rigid2d& T_current,
             const CandidateParameters& parameters, const ShapeNeighbours* earlier)
{
  PassGeometry pass = preparePassMotions (source, target, T_guess, T_current, parameters, earlier);
  pass.candidates = passCandidates (target, pass, parameters);
  return pass;
}

}  // namespace matching
}  // namespace pcl_crf
