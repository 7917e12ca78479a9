// Tests of the PCL adapter pcl_crf::CRFMatcher (with the shipped default model).

#include <pcl_crf/cloud_conversion.h>
#include <pcl_crf/crf_matcher.h>
#include <pcl_crf/simulation/scan_pair_simulator.h>

#include "synthetic_scene.h"
#include "hokuyo_pairs.h"

#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <utility>

namespace {

using pcl_crf::makeRigid2d;
using pcl_crf::Rigid2d;

const std::string kModelPath = std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-matching.model";

/** The shipped model, read once. */
const pcl_crf::matching::CrfMatchingModel&
defaultModel ()
{
  static const pcl_crf::matching::CrfMatchingModel model = pcl_crf::matching::loadModel (kModelPath);
  return model;
}

template <typename PointT> typename pcl::PointCloud<PointT>::Ptr
cloudOf (const Eigen::Matrix2Xd& xy)
{
  typename pcl::PointCloud<PointT>::Ptr cloud (new pcl::PointCloud<PointT>);
  pcl_crf::fromMatrix2X (xy, *cloud);
  return cloud;
}

Eigen::Matrix4f
toMatrix4f (const Rigid2d& T)
{
  Eigen::Matrix4f M = Eigen::Matrix4f::Identity ();
  M.topLeftCorner<2, 2> () = T.linear ().cast<float> ();
  M.block<2, 1> (0, 3) = T.translation ().cast<float> ();
  return M;
}

template <typename PointT>
class CrfMatcherTest : public ::testing::Test
{
protected:
  using Matcher = pcl_crf::CRFMatcher<PointT, PointT>;

  void
  SetUp () override
  {
    truth_ = makeRigid2d (0.5, 0.2, 0.1);
    pair_ = pcl_crf::test::staticRoomPair (truth_, makeRigid2d (0.06, -0.05, 0.02));
    source_ = cloudOf<PointT> (pair_.source);
    target_ = cloudOf<PointT> (pair_.target);
    matcher_.setModel (defaultModel ());
    matcher_.setInputSource (source_);
    matcher_.setInputTarget (target_);
    matcher_.setOdometry (pair_.odometry);
  }

  Rigid2d truth_;
  pcl_crf::ScanPair pair_;
  typename pcl::PointCloud<PointT>::Ptr source_, target_;
  Matcher matcher_;
};

using PointTypes = ::testing::Types<pcl::PointXYZ, pcl::PointXYZI, pcl::PointXYZL>;
TYPED_TEST_SUITE (CrfMatcherTest, PointTypes);

TYPED_TEST (CrfMatcherTest, CorrespondencesOfARigidlyMovedRoom)
{
  pcl::Correspondences correspondences;
  this->matcher_.determineCorrespondences (correspondences);
  const auto n = static_cast<std::size_t> (this->pair_.source.cols ());
  // Measured: 315 of the room's 316 points matched, all correctly.
  EXPECT_GT (correspondences.size (), 0.97 * n);
  std::size_t correct = 0;
  const Rigid2d guess = this->pair_.odometry.T_source_target.inverse ();
  for (const pcl::Correspondence& c : correspondences) {
    ASSERT_GE (c.index_query, 0);
    ASSERT_LT (static_cast<std::size_t> (c.index_query), n);
    correct += c.index_match == this->pair_.source_match[c.index_query] ? 1 : 0;
    // distance: squared distance under the guess, in float.
    const double expected =
        (guess * this->pair_.source.col (c.index_query) - this->pair_.target.col (c.index_match)).squaredNorm ();
    EXPECT_NEAR (c.distance, expected, 1e-4 * (1.0 + expected));
  }
  EXPECT_GT (correct, 0.97 * n);
  EXPECT_EQ (this->matcher_.getOutliers ().size () + correspondences.size (), n);
  // The estimated motion.
  const Eigen::Matrix4f T = this->matcher_.getTransformation ();
  const Eigen::Matrix4f error = T.inverse () * toMatrix4f (this->truth_);
  EXPECT_LT ((error.template block<2, 1> (0, 3).norm ()), 2e-3);
  EXPECT_LT (std::abs (std::atan2 (error (1, 0), error (0, 0))), 5e-4);
  // Marginals and candidates per cloud point.
  ASSERT_EQ (this->matcher_.getMarginals ().size (), n);
  ASSERT_EQ (this->matcher_.getCandidates ().size (), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ (this->matcher_.getMarginals ()[i].size (),
               static_cast<Eigen::Index> (this->matcher_.getCandidates ()[i].size () + 1));
    EXPECT_NEAR (this->matcher_.getMarginals ()[i].sum (), 1.0, 1e-9);
  }
}

TYPED_TEST (CrfMatcherTest, ShuffledCloudsAreMatchedInBeamOrder)
{
  // Clouds out of beam order (a kd-tree's or a voxel grid's, here shuffled) are chained
  // in beam order: the same matches and motion, with the shuffled clouds' indices.
  std::mt19937 rng (7);
  const auto shuffle = [&rng] (const pcl::PointCloud<TypeParam>& cloud, std::vector<int>& order) {
    order.resize (cloud.size ());
    std::iota (order.begin (), order.end (), 0);
    std::shuffle (order.begin (), order.end (), rng);
    typename pcl::PointCloud<TypeParam>::Ptr out (new pcl::PointCloud<TypeParam>);
    for (const int i : order)
      out->push_back (cloud[static_cast<std::size_t> (i)]);
    return out;
  };
  std::vector<int> source_order, target_order;
  typename TestFixture::Matcher shuffled;
  shuffled.setModel (defaultModel ());
  shuffled.setInputSource (shuffle (*this->source_, source_order));
  shuffled.setInputTarget (shuffle (*this->target_, target_order));
  shuffled.setOdometry (this->pair_.odometry);
  pcl::Correspondences ordered_correspondences, shuffled_correspondences;
  this->matcher_.determineCorrespondences (ordered_correspondences);
  shuffled.determineCorrespondences (shuffled_correspondences);
  std::vector<int> ordered_match (this->source_->size (), pcl_crf::kNoMatch);
  for (const pcl::Correspondence& c : ordered_correspondences)
    ordered_match[c.index_query] = c.index_match;
  ASSERT_EQ (shuffled_correspondences.size (), ordered_correspondences.size ());
  for (const pcl::Correspondence& c : shuffled_correspondences)
    EXPECT_EQ (target_order[c.index_match], ordered_match[source_order[c.index_query]]);
  // The room goes all round the sensor: its chain starts elsewhere (after the widest gap
  // between bearings), the same points in the same cyclic order.
  EXPECT_TRUE (shuffled.getTransformation ().isApprox (this->matcher_.getTransformation (), 1e-5));
  const std::vector<int>& chain = shuffled.getMatchResultSourceIndices ();
  const std::vector<int>& ordered_chain = this->matcher_.getMatchResultSourceIndices ();
  ASSERT_EQ (chain.size (), ordered_chain.size ());
  const std::size_t start = std::find (ordered_chain.begin (), ordered_chain.end (), source_order[chain[0]]) - ordered_chain.begin ();
  for (std::size_t k = 0; k < chain.size (); ++k)
    EXPECT_EQ (source_order[chain[k]], ordered_chain[(start + k) % chain.size ()]) << k;
}

TYPED_TEST (CrfMatcherTest, TargetIndicesRestrictTheCandidates)
{
  // setIndicesTarget () (PCL's CorrespondenceEstimation): only those target points are
  // candidates, named by their cloud indices; as on a cloud of just those points.
  pcl::IndicesPtr half (new pcl::Indices);
  typename pcl::PointCloud<TypeParam>::Ptr part (new pcl::PointCloud<TypeParam>);
  for (std::size_t j = 0; j < this->target_->size () / 2; ++j) {
    half->push_back (static_cast<int> (j));
    part->push_back ((*this->target_)[j]);
  }
  this->matcher_.setIndicesTarget (half);
  pcl::Correspondences restricted, on_part;
  this->matcher_.determineCorrespondences (restricted);
  typename TestFixture::Matcher expected;
  expected.setModel (defaultModel ());
  expected.setInputSource (this->source_);
  expected.setInputTarget (part);
  expected.setOdometry (this->pair_.odometry);
  expected.determineCorrespondences (on_part);
  ASSERT_GT (restricted.size (), 50u);
  ASSERT_EQ (restricted.size (), on_part.size ());
  for (std::size_t c = 0; c < restricted.size (); ++c) {
    EXPECT_LT (restricted[c].index_match, static_cast<int> (half->size ()));
    EXPECT_EQ (restricted[c].index_query, on_part[c].index_query);
    EXPECT_EQ (restricted[c].index_match, on_part[c].index_match);  // index j of part is index j of target
  }
  // An index outside the target is named, and nothing is matched.
  half->push_back (static_cast<int> (this->target_->size ()));
  this->matcher_.setIndicesTarget (half);
  this->matcher_.determineCorrespondences (restricted);
  EXPECT_TRUE (restricted.empty ());
}

TYPED_TEST (CrfMatcherTest, MaxDistanceIsRespected)
{
  pcl::Correspondences all, near;
  this->matcher_.determineCorrespondences (all);
  this->matcher_.determineCorrespondences (near, 0.1);
  EXPECT_LT (near.size (), all.size ());
  EXPECT_GT (near.size (), 0u);
  for (const pcl::Correspondence& c : near)
    EXPECT_LE (c.distance, 0.01f + 1e-6f);
}

TYPED_TEST (CrfMatcherTest, NanPointsAreSkippedAndIndicesMappedBack)
{
  auto source = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->source_);
  auto target = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->target_);
  const float nan = std::numeric_limits<float>::quiet_NaN ();
  (*source)[5].x = nan;
  (*target)[40].y = nan;
  this->matcher_.setInputSource (source);
  this->matcher_.setInputTarget (target);
  pcl::Correspondences correspondences;
  this->matcher_.determineCorrespondences (correspondences);
  EXPECT_GT (correspondences.size (), 0.95 * source->size ());
  std::size_t correct = 0;
  for (const pcl::Correspondence& c : correspondences) {
    EXPECT_NE (c.index_query, 5);
    EXPECT_NE (c.index_match, 40);
    correct += c.index_match == this->pair_.source_match[c.index_query] ? 1 : 0;
  }
  EXPECT_GT (correct, 0.95 * source->size ());
  EXPECT_TRUE (this->matcher_.getMarginals ()[5].size () == 0);
  for (const auto index : this->matcher_.getOutliers ())
    EXPECT_NE (index, 5);
}

TYPED_TEST (CrfMatcherTest, RepeatedPointsAreMatchedAsTheirFirstCopy)
{
  // Copies of source points 3 and 10 and of target points 7 and 20 appended to the
  // clouds: the original points keep their correspondences, a source copy takes its first
  // copy's, and no correspondence or candidate names a target copy.
  pcl::Correspondences plain;
  this->matcher_.determineCorrespondences (plain);
  auto source = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->source_);
  auto target = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->target_);
  const int n = static_cast<int> (source->size ()), m = static_cast<int> (target->size ());
  source->push_back ((*source)[3]);
  source->push_back ((*source)[10]);
  target->push_back ((*target)[7]);
  target->push_back ((*target)[20]);
  this->matcher_.setInputSource (source);
  this->matcher_.setInputTarget (target);
  pcl::Correspondences with_copies;
  this->matcher_.determineCorrespondences (with_copies);
  ASSERT_EQ (with_copies.size (), plain.size () + 2);  // points 3 and 10 are matched, so are their copies
  std::map<int, int> match_of;
  for (const pcl::Correspondence& c : with_copies) {
    EXPECT_LT (c.index_match, m) << c.index_query;
    match_of[c.index_query] = c.index_match;
  }
  for (const pcl::Correspondence& c : plain)
    EXPECT_EQ (match_of.at (c.index_query), c.index_match) << c.index_query;
  EXPECT_EQ (match_of.at (n), match_of.at (3));
  EXPECT_EQ (match_of.at (n + 1), match_of.at (10));
  for (const pcl::Indices& states : this->matcher_.getCandidates ())
    for (const auto j : states)
      EXPECT_LT (j, m);
  // A copy is reciprocal when its first copy is (the backward chain names first copies).
  pcl::Correspondences reciprocal;
  this->matcher_.determineReciprocalCorrespondences (reciprocal);
  EXPECT_GT (reciprocal.size (), 0.9 * plain.size ());
  std::map<int, int> reciprocal_match;
  for (const pcl::Correspondence& c : reciprocal)
    reciprocal_match[c.index_query] = c.index_match;
  for (const auto& [copy, first] : {std::pair<int, int>{n, 3}, {n + 1, 10}}) {
    EXPECT_EQ (reciprocal_match.count (copy), reciprocal_match.count (first)) << copy;
    if (reciprocal_match.count (first) > 0)
      EXPECT_EQ (reciprocal_match.at (copy), reciprocal_match.at (first)) << copy;
  }
  EXPECT_GT (reciprocal_match.count (3) + reciprocal_match.count (10), 0u);  // the check above bites
}

TYPED_TEST (CrfMatcherTest, PointsAtTheSensorAreSkipped)
{
  // (0, 0) appended to both clouds, twice (a driver's range of 0 for a beam without a
  // return): the other points keep their correspondences, and nothing names those points.
  pcl::Correspondences plain;
  this->matcher_.determineCorrespondences (plain);
  auto source = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->source_);
  auto target = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->target_);
  const int n = static_cast<int> (source->size ()), m = static_cast<int> (target->size ());
  TypeParam origin;
  origin.x = origin.y = origin.z = 0.0f;
  for (int copy = 0; copy < 2; ++copy) {
    source->push_back (origin);
    target->push_back (origin);
  }
  this->matcher_.setInputSource (source);
  this->matcher_.setInputTarget (target);
  pcl::Correspondences padded;
  this->matcher_.determineCorrespondences (padded);
  ASSERT_EQ (padded.size (), plain.size ());
  for (std::size_t c = 0; c < plain.size (); ++c) {
    EXPECT_EQ (padded[c].index_query, plain[c].index_query);
    EXPECT_EQ (padded[c].index_match, plain[c].index_match);
  }
  for (int i = n; i < n + 2; ++i)
    EXPECT_TRUE (this->matcher_.getCandidates ()[static_cast<std::size_t> (i)].empty ()) << i;
  for (const pcl::Indices& states : this->matcher_.getCandidates ())
    for (const auto j : states)
      EXPECT_LT (j, m);
  for (const auto i : this->matcher_.getOutliers ())
    EXPECT_LT (i, n);
}

TYPED_TEST (CrfMatcherTest, FarPointsAreOutliers)
{
  auto source = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->source_);
  for (int k = 0; k < 6; ++k) {  // a small object 40 m away, nowhere in the target
    (*source)[100 + k].x = 40.0f;
    (*source)[100 + k].y = 0.1f * k;
  }
  this->matcher_.setInputSource (source);
  pcl::Correspondences correspondences;
  this->matcher_.determineCorrespondences (correspondences);
  const pcl::Indices& outliers = this->matcher_.getOutliers ();
  for (int k = 0; k < 6; ++k)
    EXPECT_NE (std::find (outliers.begin (), outliers.end (), 100 + k), outliers.end ()) << k;
}

TYPED_TEST (CrfMatcherTest, BadInputGivesAnEmptyResult)
{
  using Matcher = typename TestFixture::Matcher;
  pcl::Correspondences correspondences{pcl::Correspondence (0, 0, 1.0f)};
  pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel ();
  pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);  // the PCL_ERRORs are expected
  {  // no source cloud
    Matcher matcher;
    matcher.setModel (defaultModel ());
    matcher.setInputTarget (this->target_);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
  }
  {  // no target cloud (an empty target is refused by setInputTarget)
    Matcher matcher;
    matcher.setModel (defaultModel ());
    matcher.setInputSource (this->source_);
    matcher.setInputTarget (pcl::make_shared<pcl::PointCloud<TypeParam>> ());
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
  }
  {  // empty source cloud
    Matcher matcher;
    matcher.setModel (defaultModel ());
    matcher.setInputSource (pcl::make_shared<pcl::PointCloud<TypeParam>> ());
    matcher.setInputTarget (this->target_);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    EXPECT_TRUE (matcher.getOutliers ().empty ());
  }
  {  // only NaN points
    auto nan_cloud = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->source_);
    for (auto& p : *nan_cloud)
      p.x = std::numeric_limits<float>::quiet_NaN ();
    this->matcher_.setInputSource (nan_cloud);
    correspondences.emplace_back (0, 0, 1.0f);
    this->matcher_.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
  }
  {  // no model, then a bad parameter
    Matcher matcher;
    matcher.setInputSource (this->source_);
    matcher.setInputTarget (this->target_);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    EXPECT_FALSE (matcher.loadModel ("/nonexistent/crf-matching.model"));
    matcher.setModel (defaultModel ());
    matcher.setPasses (5);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    matcher.setPasses (2);
    matcher.determineCorrespondences (correspondences);
    EXPECT_FALSE (correspondences.empty ());
  }
  {  // a NaN odometry reading is refused; a NaN guess is named when matching
    Matcher matcher;
    matcher.setModel (defaultModel ());
    matcher.setInputSource (this->source_);
    matcher.setInputTarget (this->target_);
    matcher.setOdometry (this->pair_.odometry);
    const Eigen::Matrix4f before = matcher.getInitialGuess ();
    pcl_crf::Odometry nan_odometry = this->pair_.odometry;
    nan_odometry.T_source_target.translation ().x () = std::numeric_limits<double>::quiet_NaN ();
    matcher.setOdometry (nan_odometry);
    EXPECT_TRUE (matcher.getInitialGuess ().isApprox (before));
    Eigen::Matrix4f nan_guess = Eigen::Matrix4f::Identity ();
    nan_guess (0, 3) = std::numeric_limits<float>::quiet_NaN ();
    matcher.setInitialGuess (nan_guess);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);  // once a crash in the features
    EXPECT_TRUE (correspondences.empty ());
  }
  {  // a guess that is not planar is warned about, and its planar part used
    Matcher matcher;
    Eigen::Matrix4f tilted = Eigen::Matrix4f::Identity ();
    tilted.topLeftCorner<3, 3> () = Eigen::AngleAxisf (0.3f, Eigen::Vector3f::UnitX ()).toRotationMatrix ();
    tilted (0, 3) = 1.5f;
    pcl::console::setVerbosityLevel (pcl::console::L_WARN);
    testing::internal::CaptureStderr ();
    matcher.setInitialGuess (tilted);
    const std::string warning = testing::internal::GetCapturedStderr ();
    EXPECT_NE (warning.find ("setInitialGuess] the transform rotates about the x or y axis"), std::string::npos)
        << warning;
    EXPECT_TRUE (matcher.getInitialGuess ().isApprox (pcl_crf::toMatrix4<float> (makeRigid2d (1.5, 0.0, 0.0))));
    testing::internal::CaptureStderr ();
    matcher.setInitialGuess (pcl_crf::toMatrix4<float> (makeRigid2d (1.0, 2.0, 0.4)));  // planar: nothing to say
    EXPECT_EQ (testing::internal::GetCapturedStderr (), "");
    pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);
  }
  {  // coordinates beyond 1e18 m: squared distances overflow PCL's floats
    Matcher matcher;
    matcher.setModel (defaultModel ());
    auto far = pcl::make_shared<pcl::PointCloud<TypeParam>> (*this->target_);
    (*far)[3].y = 1e37f;
    matcher.setInputSource (this->source_);
    matcher.setInputTarget (far);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
  }
  {  // source indices outside the cloud (once a crash)
    Matcher matcher;
    matcher.setModel (defaultModel ());
    matcher.setInputSource (this->source_);
    matcher.setInputTarget (this->target_);
    auto outside = pcl::make_shared<pcl::Indices> (pcl::Indices{0, 1, static_cast<int> (this->source_->size ())});
    matcher.setIndicesSource (outside);
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    (*outside)[2] = -5;
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    (*outside)[2] = 1;  // every source point is one node of the chain
    correspondences.emplace_back (0, 0, 1.0f);
    matcher.determineCorrespondences (correspondences);
    EXPECT_TRUE (correspondences.empty ());
    outside->resize (this->source_->size ());
    std::iota (outside->begin (), outside->end (), 0);  // every point: it recovers
    matcher.determineCorrespondences (correspondences);
    EXPECT_FALSE (correspondences.empty ());
  }
  pcl::console::setVerbosityLevel (level);
}

TYPED_TEST (CrfMatcherTest, ReciprocalCorrespondencesAgreeBothWays)
{
  pcl::Correspondences forward, reciprocal;
  this->matcher_.determineCorrespondences (forward);
  this->matcher_.determineReciprocalCorrespondences (reciprocal);
  EXPECT_LE (reciprocal.size (), forward.size ());
  EXPECT_GT (reciprocal.size (), 0.9 * forward.size ());
  for (const pcl::Correspondence& c : reciprocal)
    EXPECT_EQ (c.index_match, this->pair_.source_match[c.index_query]);
}

TYPED_TEST (CrfMatcherTest, SettersAndClone)
{
  EXPECT_EQ (this->matcher_.getGuessNeighbours (), defaultModel ().parameters.candidates.guess_neighbours);
  this->matcher_.setGuessNeighbours (3);
  this->matcher_.setSegmentNeighbours (1);
  this->matcher_.setMaxObjectDisplacement (4.0);
  EXPECT_DOUBLE_EQ (this->matcher_.getOverlapSpacings (), defaultModel ().parameters.candidates.segments.overlap_spacings);
  this->matcher_.setOverlapSpacings (3.0);
  EXPECT_EQ (this->matcher_.getGuessNeighbours (), 3);
  EXPECT_EQ (this->matcher_.getSegmentNeighbours (), 1);
  EXPECT_DOUBLE_EQ (this->matcher_.getMaxObjectDisplacement (), 4.0);
  EXPECT_DOUBLE_EQ (this->matcher_.getOverlapSpacings (), 3.0);
  const Eigen::Matrix4f guess = toMatrix4f (makeRigid2d (0.1, 0.2, 0.3));
  this->matcher_.setInitialGuess (guess);
  EXPECT_TRUE (this->matcher_.getInitialGuess ().isApprox (guess, 1e-6f));
  auto copy = this->matcher_.clone ();
  pcl::Correspondences a, b;
  this->matcher_.determineCorrespondences (a);
  copy->determineCorrespondences (b);
  ASSERT_EQ (a.size (), b.size ());
  for (std::size_t k = 0; k < a.size (); ++k)
    EXPECT_EQ (a[k].index_match, b[k].index_match);
}

TYPED_TEST (CrfMatcherTest, WorksInsideIterativeClosestPoint)
{
  pcl::IterativeClosestPoint<TypeParam, TypeParam> icp;
  typename pcl_crf::CRFMatcher<TypeParam, TypeParam>::Ptr matcher (new pcl_crf::CRFMatcher<TypeParam, TypeParam>);
  matcher->setModel (defaultModel ());  // guess: identity, ICP moves the source itself
  icp.setCorrespondenceEstimation (matcher);
  icp.setTransformationEstimation (
      pcl::make_shared<pcl::registration::TransformationEstimation2D<TypeParam, TypeParam>> ());
  icp.setInputSource (this->source_);
  icp.setInputTarget (this->target_);
  icp.setMaximumIterations (10);
  icp.setTransformationEpsilon (1e-10);
  icp.setMaxCorrespondenceDistance (1.0);
  pcl::PointCloud<TypeParam> aligned;
  icp.align (aligned, toMatrix4f (this->pair_.odometry.T_source_target.inverse ()));
  ASSERT_TRUE (icp.hasConverged ());
  const Eigen::Matrix4f error = icp.getFinalTransformation ().inverse () * toMatrix4f (this->truth_);
  EXPECT_LT ((error.template block<2, 1> (0, 3).norm ()), 2e-3);
  EXPECT_LT (std::abs (std::atan2 (error (1, 0), error (0, 0))), 5e-4);
}

}  // namespace

namespace {

/** \a xy as a cloud with a NaN point before the points that would land at \a nan_at;
 *  \a index receives the cloud index of every column. */
pcl::PointCloud<pcl::PointXYZ>::Ptr
cloudWithNans (const Eigen::Matrix2Xd& xy, const std::vector<std::size_t>& nan_at, std::vector<int>& index)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>> ();
  const float nan = std::numeric_limits<float>::quiet_NaN ();
  index.clear ();
  for (Eigen::Index k = 0; k < xy.cols (); ++k) {
    if (std::find (nan_at.begin (), nan_at.end (), cloud->size ()) != nan_at.end ())
      cloud->push_back (pcl::PointXYZ (nan, nan, nan));
    index.push_back (static_cast<int> (cloud->size ()));
    cloud->push_back (pcl::PointXYZ (static_cast<float> (xy (0, k)), static_cast<float> (xy (1, k)), 0.0f));
  }
  return cloud;
}

TEST (CrfMatcherOnAFinerScan, MatchesThinnedLikeMatchScansWithCloudIndicesMappedBack)
{
  // A Hokuyo-like pair (1081 beams over 270°, 0.25° apart) with NaN points in both
  // clouds: the adapter thins the valid points to the model's 0.5° as matchScans does,
  // and maps the lifted matches back to cloud indices.
  const pcl_crf::ScanPair pair = pcl_crf::test::hokuyoPair (5, 0);
  // The simulator's clouds hold floats; the adapter sees them as floats too.
  const Eigen::Matrix2Xd source = pair.source.cast<float> ().cast<double> ();
  const Eigen::Matrix2Xd target = pair.target.cast<float> ().cast<double> ();
  ASSERT_LT (pcl_crf::thinToSpacing (source, defaultModel ().parameters.training_beam_spacing).kept.size (),
             static_cast<std::size_t> (source.cols ()));  // it is thinned
  std::vector<int> source_index, target_index;
  const auto source_cloud = cloudWithNans (source, {10, 500}, source_index);
  const auto target_cloud = cloudWithNans (target, {3, 300}, target_index);
  pcl_crf::CRFMatcher<pcl::PointXYZ, pcl::PointXYZ> matcher;
  matcher.setModel (defaultModel ());
  matcher.setOdometry (pair.odometry);
  matcher.setInputSource (source_cloud);
  matcher.setInputTarget (target_cloud);
  pcl::Correspondences correspondences;
  matcher.determineCorrespondences (correspondences);

  const pcl_crf::matching::MatchResult direct = pcl_crf::matching::matchScans (
      source, target, pcl_crf::matching::MotionGuess::fromOdometry (pair.odometry), defaultModel ());
  pcl::Correspondences expected;
  for (Eigen::Index k = 0; k < source.cols (); ++k)
    if (direct.matches[k] != pcl_crf::kNoMatch)
      expected.emplace_back (source_index[k], target_index[direct.matches[k]], 0.0f);
  ASSERT_EQ (correspondences.size (), expected.size ());
  EXPECT_GT (expected.size (), source.cols () / 2);
  for (std::size_t c = 0; c < expected.size (); ++c) {
    EXPECT_EQ (correspondences[c].index_query, expected[c].index_query);
    EXPECT_EQ (correspondences[c].index_match, expected[c].index_match);
  }
  // Every valid source point has states, the NaN ones none.
  EXPECT_TRUE (matcher.getMarginals ()[10].size () == 0);
  EXPECT_EQ (matcher.getMarginals ()[source_index[700]].size (),
             static_cast<Eigen::Index> (matcher.getCandidates ()[source_index[700]].size ()) + 1);
}

}  // namespace
