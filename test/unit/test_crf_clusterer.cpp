// The PCL interface: pcl_crf::CRFClusterer over the precompiled point types.

#include <pcl_crf/clustering/clustering_features.h>
#include <pcl_crf/crf_clusterer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace {

using pcl_crf::makeRigid2d;
using pcl_crf::Rigid2d;

const Rigid2d kWorld = makeRigid2d (-2.0, 0.1, -0.02);  // T_target_source of the world
const Rigid2d kCar = makeRigid2d (-0.5, 1.0, 0.08);     // and of a car crossing the street

/** A back wall at x = 10 m and a car (x = 5 m, |y| ≤ 1 m) in front of it, seen by
 *  241 beams over ±60°; the target holds every source point moved by its motion. */
template <typename PointT> struct Scene
{
  typename pcl::PointCloud<PointT>::Ptr source{new pcl::PointCloud<PointT>};
  typename pcl::PointCloud<PointT>::Ptr target{new pcl::PointCloud<PointT>};
  pcl::CorrespondencesPtr correspondences{new pcl::Correspondences};
  std::vector<int> object;

  Scene ()
  {
    for (int beam = 0; beam <= 240; ++beam)
    {
      const double angle = (-60.0 + 0.5 * beam) * M_PI / 180.0;
      const bool car = std::abs (5.0 * std::tan (angle)) <= 1.0;
      const double x = car ? 5.0 : 10.0;
      const Eigen::Vector2d s (x, x * std::tan (angle));
      const Eigen::Vector2d g = (car ? kCar : kWorld) * s;
      add (*source, s);
      add (*target, g);
      object.push_back (car ? 1 : 0);
      correspondences->emplace_back (beam, beam, 0.0f);
    }
  }

  static void
  add (pcl::PointCloud<PointT>& cloud, const Eigen::Vector2d& p)
  {
    PointT point;
    point.x = static_cast<float> (p.x ());
    point.y = static_cast<float> (p.y ());
    point.z = 0.0f;
    cloud.push_back (point);
  }
};

Eigen::VectorXd
weights ()
{
  Eigen::VectorXd w (pcl_crf::clustering::kWeightCount);
  w << 0.0, -3.3, 0.0, 4.5, -0.7;
  return w;
}

/** Translation [m] and rotation [rad] error of a 4x4 estimate against a 2D motion. */
std::pair<double, double>
error (const Eigen::Matrix4f& estimate, const Rigid2d& truth)
{
  Rigid2d T = Rigid2d::Identity ();
  T.linear () = estimate.topLeftCorner<2, 2> ().cast<double> ();
  T.translation () = estimate.topRightCorner<2, 1> ().cast<double> ();
  const Rigid2d e = T.inverse () * truth;
  return {e.translation ().norm (), std::abs (pcl_crf::rotationAngle (e))};
}

template <typename PointT> class CRFClustererTest : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    clusterer.setInputSource (scene.source);
    clusterer.setInputTarget (scene.target);
    clusterer.setCorrespondences (scene.correspondences);
    clusterer.setWeights (weights ());
    Eigen::Matrix4f odometry = Eigen::Matrix4f::Identity ();  // T_source_target of the sensor
    const Rigid2d sensor = kWorld.inverse ();
    odometry.topLeftCorner<2, 2> () = sensor.linear ().cast<float> ();
    odometry.topRightCorner<2, 1> () = sensor.translation ().cast<float> ();
    clusterer.setOdometry (odometry, Eigen::Vector3d (0.01, 0.01, 1e-4).asDiagonal ());
  }

  Scene<PointT> scene;
  pcl_crf::CRFClusterer<PointT> clusterer;
  std::vector<pcl::PointIndices> clusters;
};

using PointTypes = ::testing::Types<pcl::PointXYZ, pcl::PointXYZI, pcl::PointXYZL>;
TYPED_TEST_SUITE (CRFClustererTest, PointTypes);

TYPED_TEST (CRFClustererTest, RecoversKnownMotions)
{
  this->clusterer.extract (this->clusters);
  ASSERT_EQ (this->clusters.size (), 2u);
  EXPECT_GT (this->clusters[0].indices.size (), this->clusters[1].indices.size ());  // largest first
  EXPECT_EQ (this->clusterer.getStaticCluster (), 0);
  EXPECT_TRUE (this->clusterer.isStatic (0));
  EXPECT_FALSE (this->clusterer.isStatic (1));
  EXPECT_TRUE (this->clusterer.hasConverged ());
  const Rigid2d truth[2] = {kWorld, kCar};
  for (int c = 0; c < 2; ++c)
  {
    const auto [translation, rotation] = error (this->clusterer.getTransformations ()[c], truth[c]);
    EXPECT_LT (translation, 1e-3);
    EXPECT_LT (rotation, 1e-3);
    EXPECT_EQ (this->clusterer.getClusterSizes ()[c], static_cast<int> (this->clusters[c].indices.size ()));
    for (const auto i : this->clusters[c].indices)
      EXPECT_EQ (this->scene.object[i], c);
  }
  const auto& marginals = this->clusterer.getMarginals ();
  ASSERT_EQ (marginals.size (), this->scene.source->size ());
  EXPECT_EQ (marginals[0].size (), 2);
  EXPECT_NEAR (marginals[0].sum (), 1.0, 1e-9);
  EXPECT_GT (marginals[0] (0), 0.99);
}

TYPED_TEST (CRFClustererTest, AShuffledSourceIsChainedInBeamOrder)
{
  // A source cloud out of beam order (a kd-tree's or a voxel grid's, here shuffled) is
  // chained in beam order: the same clusters and motions, with the shuffled cloud's indices.
  this->clusterer.extract (this->clusters);
  const auto transformations = this->clusterer.getTransformations ();
  std::vector<int> order (this->scene.source->size ()), position (order.size ());
  std::iota (order.begin (), order.end (), 0);
  std::mt19937 rng (9);
  std::shuffle (order.begin (), order.end (), rng);
  typename pcl::PointCloud<TypeParam>::Ptr source (new pcl::PointCloud<TypeParam>);
  for (std::size_t k = 0; k < order.size (); ++k) {
    source->push_back ((*this->scene.source)[static_cast<std::size_t> (order[k])]);
    position[static_cast<std::size_t> (order[k])] = static_cast<int> (k);
  }
  pcl::CorrespondencesPtr correspondences (new pcl::Correspondences);
  for (const pcl::Correspondence& c : *this->scene.correspondences)
    correspondences->emplace_back (position[c.index_query], c.index_match, c.distance);
  this->clusterer.setInputSource (source);
  this->clusterer.setCorrespondences (correspondences);
  std::vector<pcl::PointIndices> shuffled;
  this->clusterer.extract (shuffled);
  ASSERT_EQ (shuffled.size (), this->clusters.size ());
  for (std::size_t l = 0; l < shuffled.size (); ++l) {
    std::vector<int> mapped;
    for (const int i : shuffled[l].indices)
      mapped.push_back (order[static_cast<std::size_t> (i)]);
    std::sort (mapped.begin (), mapped.end ());
    std::vector<int> expected (this->clusters[l].indices.begin (), this->clusters[l].indices.end ());
    std::sort (expected.begin (), expected.end ());
    EXPECT_EQ (mapped, expected) << "cluster " << l;
    EXPECT_EQ (this->clusterer.getTransformations ()[l], transformations[l]) << "cluster " << l;
  }
}

TYPED_TEST (CRFClustererTest, ASourcePointAtTheSensorIsLeftOut)
{
  // (0, 0) appended to the source, with a correspondence (a driver's range of 0 for a beam
  // without a return): left out of the chain, like a point outside the indices; the
  // clusters and motions of the other points stay.
  this->clusterer.extract (this->clusters);
  const auto clusters = this->clusters;
  const auto transformations = this->clusterer.getTransformations ();
  typename pcl::PointCloud<TypeParam>::Ptr source (new pcl::PointCloud<TypeParam> (*this->scene.source));
  TypeParam origin;
  origin.x = origin.y = origin.z = 0.0f;
  source->push_back (origin);
  const auto at_sensor = static_cast<int> (source->size ()) - 1;
  pcl::CorrespondencesPtr correspondences (new pcl::Correspondences (*this->scene.correspondences));
  correspondences->emplace_back (at_sensor, 0, 0.0f);
  this->clusterer.setInputSource (source);
  this->clusterer.setCorrespondences (correspondences);
  this->clusterer.extract (this->clusters);
  ASSERT_EQ (this->clusters.size (), clusters.size ());
  for (std::size_t c = 0; c < clusters.size (); ++c) {
    EXPECT_EQ (this->clusters[c].indices, clusters[c].indices) << c;
    EXPECT_EQ (this->clusterer.getTransformations ()[c], transformations[c]) << c;
  }
}

TYPED_TEST (CRFClustererTest, WithoutOdometryTheLargestClusterIsStatic)
{
  this->clusterer.clearOdometry ();
  this->clusterer.extract (this->clusters);
  ASSERT_EQ (this->clusters.size (), 2u);
  EXPECT_EQ (this->clusterer.getStaticCluster (), 0);
}

TYPED_TEST (CRFClustererTest, PointsWithoutCorrespondenceAreLabelledOnRequest)
{
  // Drop every other correspondence and one NaN source point nobody refers to.
  pcl::CorrespondencesPtr half (new pcl::Correspondences);
  for (std::size_t k = 0; k < this->scene.correspondences->size (); k += 2)
    half->push_back ((*this->scene.correspondences)[k]);
  (*this->scene.source)[1].x = std::numeric_limits<float>::quiet_NaN ();
  this->clusterer.setCorrespondences (half);
  this->clusterer.extract (this->clusters);
  ASSERT_EQ (this->clusters.size (), 2u);
  EXPECT_EQ (this->clusters[0].indices.size () + this->clusters[1].indices.size (), half->size ());
  EXPECT_TRUE (this->clusterer.getMarginals ()[1].size () == 0);
  this->clusterer.setLabelUnassociated (true);
  this->clusterer.extract (this->clusters);
  ASSERT_EQ (this->clusters.size (), 2u);
  EXPECT_EQ (this->clusters[0].indices.size () + this->clusters[1].indices.size (), this->scene.source->size () - 1);
  for (int c = 0; c < 2; ++c)
    for (const auto i : this->clusters[c].indices)
      EXPECT_EQ (this->scene.object[i], c) << "point " << i;
}

TYPED_TEST (CRFClustererTest, BadInputGivesAnEmptyResult)
{
  using Cloud = pcl::PointCloud<TypeParam>;
  auto expectEmpty = [this] (const char* what) {
    this->clusters.assign (3, pcl::PointIndices ());
    this->clusterer.extract (this->clusters);
    EXPECT_TRUE (this->clusters.empty ()) << what;
    EXPECT_TRUE (this->clusterer.getTransformations ().empty ()) << what;
    EXPECT_EQ (this->clusterer.getStaticCluster (), -1) << what;
  };
  pcl_crf::CRFClusterer<TypeParam> fresh;
  fresh.extract (this->clusters);
  EXPECT_TRUE (this->clusters.empty ());  // no cloud at all

  this->clusterer.setInputTarget (typename Cloud::Ptr (new Cloud));
  expectEmpty ("empty target");
  this->clusterer.setInputTarget (this->scene.target);
  this->clusterer.setInputSource (typename Cloud::Ptr (new Cloud));
  expectEmpty ("empty source");
  this->clusterer.setInputSource (this->scene.source);

  pcl::CorrespondencesPtr bad (new pcl::Correspondences (*this->scene.correspondences));
  this->clusterer.setCorrespondences (pcl::CorrespondencesPtr (new pcl::Correspondences));
  expectEmpty ("no correspondences");
  (*bad)[5].index_match = static_cast<int> (this->scene.target->size ());
  this->clusterer.setCorrespondences (bad);
  expectEmpty ("match out of range");
  (*bad)[5] = pcl::Correspondence (-1, 5, 0.0f);
  expectEmpty ("query out of range");
  (*bad)[5] = pcl::Correspondence (5, 5, 0.0f);
  const float y7 = (*this->scene.source)[7].y, x9 = (*this->scene.target)[9].x;
  (*this->scene.source)[7].y = std::numeric_limits<float>::quiet_NaN ();
  expectEmpty ("NaN source point");
  (*this->scene.source)[7].y = y7;
  (*this->scene.target)[9].x = std::numeric_limits<float>::infinity ();
  expectEmpty ("infinite target point");
  (*this->scene.target)[9].x = x9;
  (*this->scene.target)[9].x = 1e37f;  // beyond 1e18 m: squared distances overflow PCL's floats
  expectEmpty ("target point at 1e37 m");
  (*this->scene.target)[9].x = x9;
  (*bad)[5].distance = std::numeric_limits<float>::quiet_NaN ();  // once dropped unnamed
  expectEmpty ("NaN correspondence distance");
  (*bad)[5].distance = 0.0f;

  pcl::CorrespondencesPtr one (new pcl::Correspondences (1, (*this->scene.correspondences)[0]));
  this->clusterer.setCorrespondences (one);
  expectEmpty ("one correspondence");
  this->clusterer.setCorrespondences (this->scene.correspondences);

  auto outside = pcl::make_shared<pcl::Indices> (pcl::Indices{0, 1, static_cast<int> (this->scene.source->size ())});
  this->clusterer.setIndices (outside);  // once a crash
  expectEmpty ("source index out of range");
  (*outside)[2] = -5;
  expectEmpty ("negative source index");
  (*outside)[2] = 1;
  expectEmpty ("repeated source index");
  auto twice = pcl::make_shared<pcl::Indices> ();  // every point twice: once a crash (writes past a buffer)
  for (int i = 0; i < static_cast<int> (this->scene.source->size ()); ++i)
    twice->insert (twice->end (), {i, i});
  this->clusterer.setIndices (twice);
  expectEmpty ("every source index twice");
  this->clusterer.setIndices (pcl::IndicesPtr ());  // the whole cloud again

  this->clusterer.setMaximumIterations (0);
  expectEmpty ("zero iterations");
  this->clusterer.setMaximumIterations (20);
  this->clusterer.setWeights (Eigen::VectorXd::Ones (3));  // rejected, weights kept
  EXPECT_EQ (this->clusterer.getWeights ().size (), pcl_crf::clustering::kWeightCount);
  pcl_crf::CRFClusterer<TypeParam> unweighted;
  unweighted.setInputSource (this->scene.source);
  unweighted.setInputTarget (this->scene.target);
  unweighted.setCorrespondences (this->scene.correspondences);
  unweighted.extract (this->clusters);
  EXPECT_TRUE (this->clusters.empty ());  // no weights
  EXPECT_FALSE (unweighted.loadModel ("/nonexistent.model"));
  this->clusterer.extract (this->clusters);
  EXPECT_EQ (this->clusters.size (), 2u);  // and it recovers
}

TEST (CRFClusterer, LoadsTheShippedModelAndKeepsParameters)
{
  pcl_crf::CRFClusterer<pcl::PointXYZ> clusterer;
  ASSERT_TRUE (clusterer.loadModel (std::string (PCL_CRF_SOURCE_DIR) + "/data/models/crf-t.model"));
  EXPECT_LT (clusterer.getWeights () (1), 0.0);  // a residual makes its cluster less likely
  EXPECT_GT (clusterer.getWeights () (3), 0.0);  // close neighbours share their cluster
  clusterer.setSegmentBreakDistance (0.7);
  clusterer.setMaxSegmentPoints (30);
  clusterer.setMaxStates (4);
  clusterer.setPruningMargin (20.0);
  clusterer.setMaxAverageEffectiveClusters (1.5);
  EXPECT_EQ (clusterer.getMotionFit (), pcl_crf::clustering::MotionFit::Marginals);  // the paper's Eq. (3)
  clusterer.setMotionFit (pcl_crf::clustering::MotionFit::OwnPoints);
  EXPECT_EQ (clusterer.getMotionFit (), pcl_crf::clustering::MotionFit::OwnPoints);
  EXPECT_EQ (clusterer.getSegmentBreakDistance (), 0.7);
  EXPECT_EQ (clusterer.getMaxSegmentPoints (), 30);
  EXPECT_EQ (clusterer.getMaxStates (), 4);
  EXPECT_EQ (clusterer.getPruningMargin (), 20.0);
  EXPECT_EQ (clusterer.getMaxAverageEffectiveClusters (), 1.5);
  EXPECT_FALSE (clusterer.getLabelUnassociated ());
}

}  // namespace
