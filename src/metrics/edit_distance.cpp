#include <pcl_crf/metrics/edit_distance.h>

#include <cstdint>
#include <unordered_map>
#include <utility>

namespace pcl_crf {

namespace {

using Word = std::uint64_t;
constexpr int kWordBits = 64;

/** Where each label occurs in the pattern: per label, (block, bits) with bit k of block
 *  b set when the pattern holds the label at position 64 b + k (Myers' Peq, sparse:
 *  labels are target indices, far too many for a dense table). */
using PatternBits = std::unordered_map<int, std::vector<std::pair<int, Word>>>;

PatternBits
patternBits (const std::vector<int>& pattern)
{
  PatternBits bits;
  for (std::size_t i = 0; i < pattern.size (); ++i) {
    const int block = static_cast<int> (i / kWordBits);
    const Word bit = Word{1} << (i % kWordBits);
    auto& blocks = bits[pattern[i]];
    if (blocks.empty () || blocks.back ().first != block)
      blocks.emplace_back (block, bit);
    else
      blocks.back ().second |= bit;
  }
  return bits;
}

/** The vertical deltas of one block of a DP column, as bit vectors (Myers, 1999). */
struct Block
{
  Word positive = ~Word{0};  // D[i][j] − D[i−1][j] = +1 (every row at column 0)
  Word negative = 0;         // D[i][j] − D[i−1][j] = −1
};

/** Advances one block to the next column (Myers, 1999, advance_block): \a equal holds
 *  the rows whose pattern label equals the column's, \a in the horizontal delta at the
 *  block's top row, \a last_row the bit of the block's last row. Returns the horizontal
 *  delta at that row. */
int
advanceBlock (Block& block, Word equal, int in, Word last_row)
{
  const Word pv = block.positive, mv = block.negative;
  const Word xv = equal | mv;
  if (in < 0)
    equal |= 1;
  const Word xh = (((equal & pv) + pv) ^ pv) | equal;
  Word ph = mv | ~(xh | pv);
  Word mh = pv & xh;
  const int out = (ph & last_row) ? 1 : (mh & last_row) ? -1 : 0;
  ph <<= 1;
  mh <<= 1;
  if (in < 0)
    mh |= 1;
  else if (in > 0)
    ph |= 1;
  block.positive = mh | ~(xv | ph);
  block.negative = ph & xv;
  return out;
}

}  // namespace

int
editDistance (const std::vector<int>& a, const std::vector<int>& b)
{
  // Myers' bit-parallel algorithm (J. ACM 46(3), 1999) in blocks of 64 rows, with the
  // DP's first row D[0][j] = j entering the first block: the column of the shorter
  // sequence (the pattern) advances one text element at a time.
  const std::vector<int>& pattern = a.size () <= b.size () ? a : b;
  const std::vector<int>& text = a.size () <= b.size () ? b : a;
  if (pattern.empty ())
    return static_cast<int> (text.size ());
  const PatternBits bits = patternBits (pattern);
  const int blocks = static_cast<int> ((pattern.size () + kWordBits - 1) / kWordBits);
  const Word last_row_of_last_block = Word{1} << ((pattern.size () - 1) % kWordBits);
  std::vector<Block> column (static_cast<std::size_t> (blocks));
  int distance = static_cast<int> (pattern.size ());  // D[m][0]
  static const std::vector<std::pair<int, Word>> kNowhere;
  for (const int label : text) {
    const auto found = bits.find (label);
    const auto& where = found == bits.end () ? kNowhere : found->second;
    std::size_t next = 0;  // the next entry of where
    int delta = 1;         // D[0][j] − D[0][j−1]
    for (int k = 0; k < blocks; ++k) {
      const Word equal = next < where.size () && where[next].first == k ? where[next++].second : 0;
      delta = advanceBlock (column[k], equal, delta, k + 1 == blocks ? last_row_of_last_block : Word{1} << 63);
    }
    distance += delta;
  }
  return distance;
}

}  // namespace pcl_crf
