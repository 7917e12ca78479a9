#include <pcl_crf/metrics/edit_distance.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using pcl_crf::editDistance;

std::vector<int>
codesOf (const std::string& text)
{
  return {text.begin (), text.end ()};
}

TEST (MetricsEditDistance, KittenToSittingIsThree)
{
  // k->s, e->i, insert g.
  EXPECT_EQ (editDistance (codesOf ("kitten"), codesOf ("sitting")), 3);
  EXPECT_EQ (editDistance (codesOf ("sitting"), codesOf ("kitten")), 3);
}

TEST (MetricsEditDistance, FlawToLawnIsTwo)
{
  // delete f, insert n.
  EXPECT_EQ (editDistance (codesOf ("flaw"), codesOf ("lawn")), 2);
}

TEST (MetricsEditDistance, EmptyAgainstNIsN)
{
  EXPECT_EQ (editDistance ({}, {1, 2, 3, 4}), 4);
  EXPECT_EQ (editDistance ({1, 2, 3, 4}, {}), 4);
  EXPECT_EQ (editDistance ({}, {}), 0);
}

TEST (MetricsEditDistance, IdenticalSequencesAreZero)
{
  EXPECT_EQ (editDistance ({-1, 0, 5, 5}, {-1, 0, 5, 5}), 0);
}

TEST (MetricsEditDistance, ReversalCostsTwoSubstitutions)
{
  EXPECT_EQ (editDistance ({1, 2, 3}, {3, 2, 1}), 2);
}

TEST (MetricsEditDistance, ShiftCostsOneDeleteAndOneInsert)
{
  // {1,2,3,4} -> delete 1 -> {2,3,4} -> insert 5 -> {2,3,4,5}; Hamming would say 4.
  EXPECT_EQ (editDistance ({1, 2, 3, 4}, {2, 3, 4, 5}), 2);
}

}  // namespace
