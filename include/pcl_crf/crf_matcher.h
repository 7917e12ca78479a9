#pragma once

#include <pcl_crf/core/scan_pair.h>
#include <pcl_crf/matching/matching_model.h>
#include <pcl_crf/matching/pass_geometry.h>
#include <pcl_crf/matching/robust_rigid_fit.h>
#include <pcl_crf/matching/scan_matching.h>

#include <pcl/correspondence.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_estimation.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief CRF-Matching (Ramos, Fox & Durrant-Whyte, RSS 2007) as a PCL
 *  correspondence estimator: associates every point of a 2D laser scan with a
 *  point of another scan, or declares it an outlier, by exact inference on a
 *  conditional random field over the scan's chain of points.
 *
 *  Both clouds must hold one 2D scan each, x/y in metres in the sensor's frame, z
 *  ignored. The chain follows the beam order, counter-clockwise as the models learned:
 *  the points' order when it is one (the order the laser measured them), backwards when
 *  they go clockwise, else the points sorted by bearing (pcl_crf::beamOrder (): a cloud
 *  through pcl::VoxelGrid, say). setIndices () and
 *  setIndicesTarget () restrict the source points and the candidate target points. Points
 *  with a NaN x or y, and points at the sensor itself (x = y = 0, a driver's range of 0 for
 *  a beam without a return), are skipped, and a point repeated exactly (pcl_crf::firstOfEqualPoints)
 *  is matched as the first of its copies along the chain (in beam order, so the last in
 *  the cloud when it is listed clockwise), the only copy a candidate or match names; every
 *  index reported refers to the input clouds. A trained model is required (setModel / loadModel; pcl_crf_train
 *  writes one, data/models/crf-matching.model is the default).
 *
 *  determineCorrespondences returns the MAP association without the outliers, by source
 *  index:
 *  pcl::Correspondence::distance is the **squared** distance between the target
 *  point and the source point moved by the initial guess (inside
 *  pcl::IterativeClosestPoint the guess is the identity and the source cloud is
 *  already moved by ICP's current estimate, so this is PCL's usual meaning).
 *  The outliers, every point's marginals over its candidates and the rigid motion
 *  CRF-Matching estimates are available through getters afterwards.
 *
 *  \code
 *  pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ> matcher;
 *  if (!matcher.loadModel ("data/models/crf-matching.model"))
 *    return;
 *  matcher.setInputSource (source);          // one laser scan each
 *  matcher.setInputTarget (target);
 *  matcher.setOdometry (odometry);           // or setInitialGuess (T_target_source)
 *  pcl::Correspondences correspondences;
 *  matcher.determineCorrespondences (correspondences);
 *  const Eigen::Matrix4f T_target_source = matcher.getTransformation ();
 *  const pcl::Indices& outliers = matcher.getOutliers ();
 *
 *  // or inside ICP (#include <pcl/registration/icp.h>), which moves the source by its
 *  // own estimate: a matcher of its own, its guess left at the identity (a clone of the
 *  // one above would apply the odometry a second time). ICP's SVD fits every pair the
 *  // matcher keeps, a moving object's too: on the shipped test split, started at the
 *  // motion above, it ended 0.71 m off the static world's translation on average
 *  // (0.011 m for getTransformation (); 0.058 m with a CorrespondenceRejectorMedianDistance
 *  // of factor 1). Among movers, take getTransformation () or JointCRFEstimator.
 *  pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ>::Ptr inner (new pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ>);
 *  inner->loadModel ("data/models/crf-matching.model");
 *  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
 *  icp.setCorrespondenceEstimation (inner);
 *  icp.setInputSource (source);
 *  icp.setInputTarget (target);
 *  pcl::PointCloud<pcl::PointXYZ> aligned;
 *  icp.align (aligned, T_target_source);     // ICP's start: the motion found above
 *  \endcode
 */
template <typename PointSource, typename PointTarget, typename Scalar = float>
class CRFMatcher : public pcl::registration::CorrespondenceEstimationBase<PointSource, PointTarget, Scalar>
{
public:
  using Ptr = pcl::shared_ptr<CRFMatcher<PointSource, PointTarget, Scalar>>;
  using ConstPtr = pcl::shared_ptr<const CRFMatcher<PointSource, PointTarget, Scalar>>;
  using Base = pcl::registration::CorrespondenceEstimationBase<PointSource, PointTarget, Scalar>;

  using PointCloudSource = typename Base::PointCloudSource;
  using PointCloudSourcePtr = typename Base::PointCloudSourcePtr;
  using PointCloudSourceConstPtr = typename Base::PointCloudSourceConstPtr;
  using PointCloudTarget = typename Base::PointCloudTarget;
  using PointCloudTargetPtr = typename Base::PointCloudTargetPtr;
  using PointCloudTargetConstPtr = typename Base::PointCloudTargetConstPtr;
  using KdTree = typename Base::KdTree;
  using KdTreePtr = typename Base::KdTreePtr;
  using Matrix4 = Eigen::Matrix<Scalar, 4, 4>;

  CRFMatcher ();
  ~CRFMatcher () override = default;

  // ------------------------------------------------------------------ model
  /** \brief Uses \a model (its parameters replace the current ones). */
  void
  setModel (const matching::CrfMatchingModel& model);

  const matching::CrfMatchingModel&
  getModel () const { return model_; }

  /** \brief Reads a model file (matching::loadModel). On failure prints a PCL_ERROR
   *  naming the file, line and problem, keeps the current model and returns false. */
  bool
  loadModel (const std::string& path);

  // ------------------------------------------------------------------ guess
  /** \brief Initial guess T_target_source (maps source points into the target frame),
   *  without a prior on the estimated motion; default identity. */
  void
  setInitialGuess (const Matrix4& T_target_source);

  /** \brief Initial guess from odometry: T_target_source = T_source_target⁻¹, the
   *  odometry covariance as a prior on the estimated motion, and its interval
   *  (setScanInterval). An unusable reading (odometryProblem ()) is reported with
   *  PCL_ERROR and leaves the guess unchanged. */
  void
  setOdometry (const Odometry& odometry);

  /** \brief Time from the source scan to the target scan [s] (0: unknown, the default).
   *  Bounds how far a moving object is searched for: no farther than the model's top
   *  speed (SegmentMotionParameters::max_speed, 30 m/s) travels in that time, nor than
   *  setMaxObjectDisplacement(). Kept by setInitialGuess, replaced by setOdometry. */
  void
  setScanInterval (double seconds) { guess_.interval = seconds; }
  double
  getScanInterval () const { return guess_.interval; }

  Matrix4
  getInitialGuess () const;

  // ------------------------------------------------------------------ parameters
  /** \brief All settings at once (a loaded model brings the ones it was trained with). */
  void
  setParameters (const matching::MatchingParameters& parameters) { model_.parameters = parameters; }

  const matching::MatchingParameters&
  getParameters () const { return model_.parameters; }

  /** \brief Candidates per point among the nearest target points under the guess [count]; default 4. */
  void
  setGuessNeighbours (int k) { model_.parameters.candidates.guess_neighbours = k; }
  int
  getGuessNeighbours () const { return model_.parameters.candidates.guess_neighbours; }

  /** \brief Candidates per point among the nearest in shape space [count]; default 2. */
  void
  setShapeNeighbours (int k) { model_.parameters.candidates.shape_neighbours = k; }
  int
  getShapeNeighbours () const { return model_.parameters.candidates.shape_neighbours; }

  /** \brief Weight of position in the shape space, as a displacement [m]; default 10. */
  void
  setShapePositionScale (double metres) { model_.parameters.candidates.shape_position_scale = metres; }
  double
  getShapePositionScale () const { return model_.parameters.candidates.shape_position_scale; }

  /** \brief Candidates per point under its segment's motion hypothesis [count]
   *  (0: no moving-object hypotheses); default 2. */
  void
  setSegmentNeighbours (int k) { model_.parameters.candidates.segments.neighbours = k; }
  int
  getSegmentNeighbours () const { return model_.parameters.candidates.segments.neighbours; }

  /** \brief Largest displacement of a moving object between the scans [m]; default 6. */
  void
  setMaxObjectDisplacement (double metres) { model_.parameters.candidates.segments.max_displacement = metres; }
  double
  getMaxObjectDisplacement () const { return model_.parameters.candidates.segments.max_displacement; }

  /** \brief Top speed of a moving object [m/s] (0: no bound); with setScanInterval() it
   *  bounds the displacement searched; default 30. */
  void
  setMaxObjectSpeed (double metres_per_second) { model_.parameters.candidates.segments.max_speed = metres_per_second; }
  double
  getMaxObjectSpeed () const { return model_.parameters.candidates.segments.max_speed; }

  /** \brief A moved point is explained when a target point lies at most this close [m]; default 0.15. */
  void
  setOverlapRadius (double metres) { model_.parameters.candidates.segments.overlap_radius = metres; }
  double
  getOverlapRadius () const { return model_.parameters.candidates.segments.overlap_radius; }

  /** \brief The overlap radius in spacings of the point on its surface, between 3 range
   *  noise σ and the overlap radius (0: the overlap radius everywhere) [spacings]; default 2. */
  void
  setOverlapSpacings (double spacings) { model_.parameters.candidates.segments.overlap_spacings = spacings; }
  double
  getOverlapSpacings () const { return model_.parameters.candidates.segments.overlap_spacings; }

  /** \brief Worst incidence angle λ on one surface, for the scan's breakpoints [rad];
   *  default 0.1745 (10°). */
  void
  setBreakpointAngle (double radians) { model_.parameters.candidates.segments.breakpoint_angle = radians; }
  double
  getBreakpointAngle () const { return model_.parameters.candidates.segments.breakpoint_angle; }

  /** \brief Fewest points of a segment that gets motion hypotheses [count]; default 3. */
  void
  setMinSegmentPoints (int points) { model_.parameters.candidates.segments.min_segment_points = points; }
  int
  getMinSegmentPoints () const { return model_.parameters.candidates.segments.min_segment_points; }

  /** \brief Laser range noise σ, for the scan's breakpoints [m]; default 0.01. */
  void
  setRangeNoise (double metres) { model_.parameters.candidates.segments.range_noise = metres; }
  double
  getRangeNoise () const { return model_.parameters.candidates.segments.range_noise; }

  /** \brief Association passes, 1 or 2 (pass 2 re-associates under pass 1's motion); default 2. */
  void
  setPasses (int passes) { model_.parameters.passes = passes; }
  int
  getPasses () const { return model_.parameters.passes; }

  /** \brief IRLS iterations of the motion estimate; default 8. */
  void
  setFitIterations (int iterations) { model_.parameters.fit.iterations = iterations; }
  int
  getFitIterations () const { return model_.parameters.fit.iterations; }

  /** \brief Residual scale of the first / last IRLS iteration [m]; defaults 1.0 / 0.1. */
  void
  setFitScales (double initial_metres, double final_metres)
  {
    model_.parameters.fit.initial_scale = initial_metres;
    model_.parameters.fit.final_scale = final_metres;
  }
  double
  getFitInitialScale () const { return model_.parameters.fit.initial_scale; }
  double
  getFitFinalScale () const { return model_.parameters.fit.final_scale; }

  /** \brief The pair error of the motion fit; default matching::FitMetric::PointToLine. */
  void
  setFitMetric (matching::FitMetric metric) { model_.parameters.fit.metric = metric; }
  matching::FitMetric
  getFitMetric () const { return model_.parameters.fit.metric; }

  /** \brief Re-choose the fit's pairs among the candidates at every iteration; default false. */
  void
  setFitReassociate (bool reassociate) { model_.parameters.fit.reassociate = reassociate; }
  bool
  getFitReassociate () const { return model_.parameters.fit.reassociate; }

  // ------------------------------------------------------------------ action
  /** \brief The MAP association without the outliers (see the class documentation).
   *  \param[out] correspondences (source index, target index, squared distance under the guess)
   *  \param[in] max_distance pairs farther apart under the guess are left out [m]
   */
  void
  determineCorrespondences (pcl::Correspondences& correspondences,
                            double max_distance = std::numeric_limits<double>::max ()) override;

  /** \brief The pairs CRF-Matching finds in both directions (source → target and,
   *  with the inverse guess, target → source); getters describe the forward run. */
  void
  determineReciprocalCorrespondences (pcl::Correspondences& correspondences,
                                      double max_distance = std::numeric_limits<double>::max ()) override;

  typename Base::Ptr
  clone () const override
  {
    return pcl::make_shared<CRFMatcher<PointSource, PointTarget, Scalar>> (*this);
  }

  // ------------------------------------------------------------------ results
  /** \brief Source cloud indices declared outliers by the last run, increasing. */
  const pcl::Indices&
  getOutliers () const { return outliers_; }

  /** \brief Per source cloud point: the target cloud indices of its candidate states
   *  (empty for skipped NaN points). */
  const std::vector<pcl::Indices>&
  getCandidates () const { return candidates_; }

  /** \brief Per source cloud point: its marginals p(y_i = s) over getCandidates ()[i]
   *  followed by the outlier state (empty for skipped NaN points). */
  const std::vector<Eigen::VectorXd>&
  getMarginals () const { return marginals_; }

  /** \brief The rigid motion T_target_source estimated by the last run (of the input
   *  source cloud's frame); the guess when nothing could be estimated. */
  Matrix4
  getTransformation () const;

  /** \brief The full result of the last run: its source point k is the source cloud's
   *  point getMatchResultSourceIndices ()[k], its target point j the target cloud's
   *  getMatchResultTargetIndices ()[j] (the finite points, in beam order). */
  const matching::MatchResult&
  getMatchResult () const { return result_; }

  /** \brief The source cloud index of every source point of getMatchResult (). */
  const std::vector<int>&
  getMatchResultSourceIndices () const { return source_index_; }

  /** \brief The target cloud index of every target point of getMatchResult (). */
  const std::vector<int>&
  getMatchResultTargetIndices () const { return target_index_; }

protected:
  using Base::corr_name_;
  using Base::getClassName;
  using Base::indices_;
  using Base::input_;
  using Base::target_;
  using Base::target_cloud_updated_;
  using Base::target_indices_;

  /** \brief Validates the input and prepares the target when it changed. */
  bool
  initCompute ();

  /** \brief Runs CRF-Matching on the valid source points; false after a PCL_ERROR. */
  bool
  computeMatches ();

  /** \brief Clears the results of the previous run. */
  void
  clearResults ();

  /** \brief The correspondence of the \a k-th valid source point: its match, if any, within
   *  \a max_distance under the guess; false for an outlier or a farther match. */
  bool
  correspondenceOf (std::size_t k, double max_distance, pcl::Correspondence& c) const;

private:
  matching::CrfMatchingModel model_;
  matching::MotionGuess guess_;

  /** the valid source points [m] and their cloud indices. */
  Eigen::Matrix2Xd source_xy_;
  std::vector<int> source_index_;
  /** the prepared target (immutable, shared by clones), its settings and cloud indices. */
  std::shared_ptr<const matching::MatchingTarget> target_prepared_;
  matching::MatchingParameters target_prepared_parameters_;
  std::vector<int> target_index_;

  matching::MatchResult result_;
  pcl::Indices outliers_;
  std::vector<pcl::Indices> candidates_;
  std::vector<Eigen::VectorXd> marginals_;
};

}  // namespace pcl_crf

#if !defined(PCL_NO_PRECOMPILE)
extern template class pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ, float>;
extern template class pcl_crf::CRFMatcher<pcl::PointXYZI, pcl::PointXYZI, float>;
extern template class pcl_crf::CRFMatcher<pcl::PointXYZL, pcl::PointXYZL, float>;
#else
#include <pcl_crf/impl/crf_matcher.hpp>
#endif
