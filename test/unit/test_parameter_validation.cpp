// Settings that no model file can hold but code can: integers cast to an enum, and
// iteration counts that would run for hours. Each is named, not run.
#include <pcl_crf/clustering/crf_clustering.h>
#include <pcl_crf/joint/joint_model.h>
#include <pcl_crf/joint/ladder_inference.h>
#include <pcl_crf/matching/matching_model.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

/** The message of \a validate (), or "" when it accepts. */
template <typename Validate> std::string
messageOf (Validate validate)
{
  try {
    validate ();
  }
  catch (const std::invalid_argument& error) {
    return error.what ();
  }
  return "";
}

template <typename Enum> Enum
outOfRange (int value)
{
  return static_cast<Enum> (value);
}

TEST (ParameterValidation, MatchingNamesAnUnknownFitMetricAndEndlessFits)
{
  pcl_crf::matching::MatchingParameters p;
  EXPECT_EQ (messageOf ([&] { pcl_crf::matching::validateParameters (p); }), "");
  p.fit.metric = outOfRange<pcl_crf::matching::FitMetric> (42);
  EXPECT_NE (messageOf ([&] { pcl_crf::matching::validateParameters (p); }).find ("fit metric must be"),
             std::string::npos);
  p = {};
  p.fit.iterations = 1 << 30;  // 17 µs each: five hours
  EXPECT_NE (messageOf ([&] { pcl_crf::matching::validateParameters (p); }).find ("[1, 1000]"), std::string::npos);
  p.fit.iterations = 1000;
  EXPECT_EQ (messageOf ([&] { pcl_crf::matching::validateParameters (p); }), "");
}

TEST (ParameterValidation, ClusteringNamesUnknownMergeEvidenceAndMotionFits)
{
  pcl_crf::clustering::CrfClusteringParameters p;
  EXPECT_EQ (messageOf ([&] { pcl_crf::clustering::validateParameters (p); }), "");
  p.merge_evidence = outOfRange<pcl_crf::clustering::MergeEvidence> (9);
  EXPECT_NE (messageOf ([&] { pcl_crf::clustering::validateParameters (p); }).find ("merge_evidence must be"),
             std::string::npos);
  p = {};
  p.motion_fit = outOfRange<pcl_crf::clustering::MotionFit> (-1);
  EXPECT_NE (messageOf ([&] { pcl_crf::clustering::validateParameters (p); }).find ("motion_fit must be"),
             std::string::npos);
  EXPECT_TRUE (pcl_crf::clustering::isMotionFit (pcl_crf::clustering::MotionFit::OwnPoints));
  EXPECT_FALSE (pcl_crf::clustering::isMotionFit (outOfRange<pcl_crf::clustering::MotionFit> (2)));
}

TEST (ParameterValidation, JointNamesUnknownScheduleEvidenceAndFinalFit)
{
  pcl_crf::joint::JointParameters p;
  EXPECT_EQ (messageOf ([&] { pcl_crf::joint::validateParameters (p); }), "");
  p.final_motion_fit = outOfRange<pcl_crf::clustering::MotionFit> (77);
  EXPECT_NE (messageOf ([&] { pcl_crf::joint::validateParameters (p); }).find ("final_motion_fit must be"),
             std::string::npos);
  p = {};
  p.inference.schedule = outOfRange<pcl_crf::joint::MessageSchedule> (5);
  EXPECT_NE (messageOf ([&] { pcl_crf::joint::validateParameters (p); }).find ("schedule must be"),
             std::string::npos);
  p = {};
  p.inference.evidence = outOfRange<pcl_crf::joint::ClusterEvidence> (3);
  EXPECT_NE (messageOf ([&] { pcl_crf::joint::validateParameters (p); }).find ("evidence must be"),
             std::string::npos);
  p = {};
  p.initial_clustering.merge_evidence = outOfRange<pcl_crf::clustering::MergeEvidence> (4);
  EXPECT_NE (messageOf ([&] { pcl_crf::joint::validateParameters (p); }).find ("merge_evidence must be"),
             std::string::npos);
}

}  // namespace
