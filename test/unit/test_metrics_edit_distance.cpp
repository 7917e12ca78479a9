#include <pcl_crf/metrics/edit_distance.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

using pcl_crf::editDistance;

std::vector<int>
codesOf (const std::string& text)
{
  return {text.begin (), text.end ()};
}

/** The textbook O(|a| |b|) dynamic programme, the reference editDistance () must equal. */
int
referenceDistance (const std::vector<int>& a, const std::vector<int>& b)
{
  std::vector<int> previous (b.size () + 1), current (b.size () + 1);
  std::iota (previous.begin (), previous.end (), 0);
  for (std::size_t i = 1; i <= a.size (); ++i) {
    current[0] = static_cast<int> (i);
    for (std::size_t j = 1; j <= b.size (); ++j)
      current[j] = std::min ({previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1), previous[j] + 1, current[j - 1] + 1});
    std::swap (previous, current);
  }
  return previous.back ();
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

TEST (MetricsEditDistance, EqualsTheDynamicProgrammeAcrossBlockBoundaries)
{
  // The bit-parallel blocks of 64 rows: lengths around 64 and 128, small alphabets
  // (many equal labels) and large ones (labels as target indices, with kNoMatch).
  std::mt19937 random (2024);
  for (int trial = 0; trial < 400; ++trial) {
    const int alphabet = trial % 4 == 0 ? 2 : trial % 4 == 1 ? 5 : trial % 4 == 2 ? 400 : 40;
    std::uniform_int_distribution<int> label (-1, alphabet - 2), length (0, 200);
    std::vector<int> a (static_cast<std::size_t> (length (random))), b;
    for (int& x : a)
      x = label (random);
    b = a;  // b: a with a few edits, or unrelated
    if (trial % 5 == 0) {
      b.resize (static_cast<std::size_t> (length (random)));
      for (int& x : b)
        x = label (random);
    }
    else
      for (int edit = 0; edit < trial % 17 && !b.empty (); ++edit) {
        const auto at = static_cast<std::size_t> (random () % b.size ());
        if (edit % 3 == 0)
          b.erase (b.begin () + static_cast<std::ptrdiff_t> (at));
        else if (edit % 3 == 1)
          b.insert (b.begin () + static_cast<std::ptrdiff_t> (at), label (random));
        else
          b[at] = label (random);
      }
    ASSERT_EQ (editDistance (a, b), referenceDistance (a, b)) << "trial " << trial << ", |a| " << a.size ()
                                                               << ", |b| " << b.size ();
    ASSERT_EQ (editDistance (b, a), referenceDistance (a, b)) << "trial " << trial;
  }
}

TEST (MetricsEditDistance, ScansOfTheFormatsLargestSizeGetTheirExactDistance)
{
  // 100 000 labels, a scan of the dataset format's largest size: one shift of a
  // sequence of distinct labels costs a deletion and an insertion.
  std::vector<int> a (100000);
  std::iota (a.begin (), a.end (), 0);
  std::vector<int> b (a.begin () + 1, a.end ());
  b.push_back (-1);
  EXPECT_EQ (editDistance (a, b), 2);
  EXPECT_EQ (editDistance (std::vector<int> (100000, 7), std::vector<int> (99990, 7)), 10);
}

}  // namespace
