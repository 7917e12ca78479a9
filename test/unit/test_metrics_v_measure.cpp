#include <pcl_crf/metrics/v_measure.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace {

using pcl_crf::computeVMeasure;
using pcl_crf::VMeasure;

TEST (MetricsVMeasure, HandComputedTwoByTwoTable)
{
  // classes {0,0,1,1}, clusters {0,0,0,1}; contingency (rows = class, cols = cluster):
  //            K=0  K=1
  //   C=0       2    0
  //   C=1       1    1          n = 4, cluster sizes 3 and 1, class sizes 2 and 2
  // H(C)   = ln 2                                         = 0.693147
  // H(C|K) = -(2/4 ln(2/3) + 1/4 ln(1/3) + 1/4 ln(1/1))   = 1/2 ln(3/2) + 1/4 ln 3 = 0.477386
  // h      = 1 - 0.477386 / 0.693147                      = 0.311278
  // H(K)   = -(3/4 ln(3/4) + 1/4 ln(1/4))                 = 0.562335
  // H(K|C) = -(2/4 ln(2/2) + 1/4 ln(1/2) + 1/4 ln(1/2))   = 1/2 ln 2 = 0.346574
  // c      = 1 - 0.346574 / 0.562335                      = 0.383689
  // V      = 2 h c / (h + c)                              = 0.343711
  const VMeasure score = computeVMeasure ({0, 0, 1, 1}, {0, 0, 0, 1});
  const double h = 1.0 - (0.5 * std::log (1.5) + 0.25 * std::log (3.0)) / std::log (2.0);
  const double H_K = 0.75 * std::log (4.0 / 3.0) + 0.25 * std::log (4.0);
  const double c = 1.0 - 0.5 * std::log (2.0) / H_K;
  EXPECT_NEAR (h, 0.311278, 1e-6);
  EXPECT_NEAR (c, 0.383689, 1e-6);
  EXPECT_NEAR (score.homogeneity, h, 1e-12);
  EXPECT_NEAR (score.completeness, c, 1e-12);
  EXPECT_NEAR (score.v, 2.0 * h * c / (h + c), 1e-12);
  EXPECT_NEAR (score.v, 0.343711, 1e-6);
}

TEST (MetricsVMeasure, HandComputedThreeClusters)
{
  // classes {0,0,0,1,1,1}, clusters {0,0,1,1,2,2}: clusters 0 and 2 are pure,
  // cluster 1 holds one item of each class.
  // H(C) = ln 2, H(C|K) = -(1/6 ln(1/2) + 1/6 ln(1/2)) = 1/3 ln 2  ->  h = 2/3 exactly.
  // H(K) = ln 3 (three clusters of 2),
  // H(K|C) = -2 (2/6 ln(2/3) + 1/6 ln(1/3)) = 2/3 ln(3/2) + 1/3 ln 3 = 0.636514
  // c = 1 - 0.636514 / 1.098612 = 0.420620, V = 2 (2/3) c / (2/3 + c) = 0.515804
  const VMeasure score = computeVMeasure ({0, 0, 0, 1, 1, 1}, {0, 0, 1, 1, 2, 2});
  EXPECT_NEAR (score.homogeneity, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR (score.completeness, 0.420620, 1e-6);
  EXPECT_NEAR (score.v, 0.515804, 1e-6);
}

TEST (MetricsVMeasure, BetaWeighsCompleteness)
{
  // Same table as HandComputedTwoByTwoTable, beta = 2:
  // V_2 = 3 h c / (2 h + c) = 3 * 0.311278 * 0.383689 / (0.622556 + 0.383689) = 0.356078
  const VMeasure score = computeVMeasure ({0, 0, 1, 1}, {0, 0, 0, 1}, 2.0);
  EXPECT_NEAR (score.homogeneity, 0.311278, 1e-6);
  EXPECT_NEAR (score.v, 0.356078, 1e-6);
  // beta = 0 keeps only homogeneity: V_0 = h c / c = h.
  EXPECT_NEAR (computeVMeasure ({0, 0, 1, 1}, {0, 0, 0, 1}, 0.0).v, 0.311278, 1e-6);
}

TEST (MetricsVMeasure, PerfectClusteringScoresOne)
{
  const VMeasure score = computeVMeasure ({0, 0, 1, 2, 2}, {5, 5, 3, 1, 1});
  EXPECT_DOUBLE_EQ (score.homogeneity, 1.0);
  EXPECT_DOUBLE_EQ (score.completeness, 1.0);
  EXPECT_DOUBLE_EQ (score.v, 1.0);
}

TEST (MetricsVMeasure, SingleClassIsHomogeneous)
{
  // H(C) = 0 -> h = 1; every item its own cluster: H(K|C) = H(K) = ln 3 -> c = 0; V = 0.
  const VMeasure score = computeVMeasure ({5, 5, 5}, {0, 1, 2});
  EXPECT_DOUBLE_EQ (score.homogeneity, 1.0);
  EXPECT_NEAR (score.completeness, 0.0, 1e-12);
  EXPECT_NEAR (score.v, 0.0, 1e-12);
}

TEST (MetricsVMeasure, SingleClusterIsComplete)
{
  // H(K) = 0 -> c = 1; one cluster for three classes: H(C|K) = H(C) -> h = 0; V = 0.
  const VMeasure score = computeVMeasure ({0, 1, 2}, {7, 7, 7});
  EXPECT_NEAR (score.homogeneity, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ (score.completeness, 1.0);
  EXPECT_NEAR (score.v, 0.0, 1e-12);
}

TEST (MetricsVMeasure, SingleClassAndSingleClusterIsPerfect)
{
  const VMeasure score = computeVMeasure ({3, 3}, {9, 9});
  EXPECT_DOUBLE_EQ (score.homogeneity, 1.0);
  EXPECT_DOUBLE_EQ (score.completeness, 1.0);
  EXPECT_DOUBLE_EQ (score.v, 1.0);
}

TEST (MetricsVMeasure, IndependentLabellingsScoreZero)
{
  // Clusters independent of classes: H(C|K) = H(C), H(K|C) = H(K) -> h = c = 0,
  // beta h + c = 0 -> V = 0 by definition.
  const VMeasure score = computeVMeasure ({0, 0, 1, 1}, {0, 1, 0, 1});
  EXPECT_NEAR (score.homogeneity, 0.0, 1e-12);
  EXPECT_NEAR (score.completeness, 0.0, 1e-12);
  EXPECT_EQ (score.v, 0.0);
}

TEST (MetricsVMeasure, RenamedLabelsGiveIdenticalScores)
{
  const VMeasure original = computeVMeasure ({0, 0, 1, 1, 2}, {0, 0, 0, 1, 1});
  const VMeasure renamed = computeVMeasure ({7, 7, -3, -3, 100}, {4, 4, 4, -1, -1});
  EXPECT_NEAR (original.homogeneity, 0.375150, 1e-6);
  EXPECT_NEAR (original.completeness, 0.588033, 1e-6);
  EXPECT_DOUBLE_EQ (renamed.homogeneity, original.homogeneity);
  EXPECT_DOUBLE_EQ (renamed.completeness, original.completeness);
  EXPECT_DOUBLE_EQ (renamed.v, original.v);
}

TEST (MetricsVMeasure, EmptyInputThrows)
{
  EXPECT_THROW (computeVMeasure ({}, {}), std::invalid_argument);
}

TEST (MetricsVMeasure, SizeMismatchThrowsNamingTheSizes)
{
  try {
    computeVMeasure ({0, 1, 1, 0}, {0, 1, 2});
    FAIL () << "expected std::invalid_argument";
  }
  catch (const std::invalid_argument& error) {
    const std::string message = error.what ();
    EXPECT_NE (message.find ("4 class labels but 3 cluster labels"), std::string::npos) << message;
  }
}

TEST (MetricsVMeasure, NegativeBetaThrows)
{
  EXPECT_THROW (computeVMeasure ({0, 1}, {0, 1}, -1.0), std::invalid_argument);
}

}  // namespace
