#include <pcl_crf/crf/adaboost_stumps.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <limits>
#include <locale>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pcl_crf {
namespace crf {

namespace {

const char* const kMagic = "pcl_crf_adaboost_stumps";
constexpr int kVersion = 1;

/** Reads the lines of a model, counting them for error messages. */
class LineReader
{
public:
  explicit LineReader (std::istream& is) : is_ (is) {}

  /** Next line as a stream of fields (classic locale). \throws std::runtime_error at end of input. */
  std::istringstream
  next (const std::string& expected)
  {
    std::string line;
    ++line_number_;
    if (!std::getline (is_, line))
      fail ("unexpected end of input, expected " + expected);
    std::istringstream fields (line);
    fields.imbue (std::locale::classic ());
    return fields;
  }

  [[noreturn]] void
  fail (const std::string& what) const
  {
    throw std::runtime_error ("[pcl_crf::crf::AdaBoostStumps::read] line " + std::to_string (line_number_) + ": " +
                              what);
  }

  /** Checks that nothing but blanks follows on the line. */
  void
  expectEnd (std::istringstream& fields, const std::string& what) const
  {
    std::string extra;
    if (fields >> extra)
      fail ("unexpected '" + extra + "' after " + what);
  }

  /** Reads "<keyword> <non-negative integer>". */
  int
  keyValue (const std::string& keyword)
  {
    std::istringstream fields = next ("'" + keyword + " <count>'");
    std::string key;
    long long value = -1;
    if (!(fields >> key) || key != keyword || !(fields >> value) || value < 0 ||
        value > std::numeric_limits<int>::max ())
      fail ("expected '" + keyword + " <non-negative integer>'");
    expectEnd (fields, keyword);
    return static_cast<int> (value);
  }

private:
  std::istream& is_;
  int line_number_ = 0;
};

AdaBoostStumps::Stump
readStump (LineReader& reader, int dimension, int index)
{
  const std::string name = "stump " + std::to_string (index);
  std::istringstream fields = reader.next (name);
  AdaBoostStumps::Stump stump;
  if (!(fields >> stump.feature >> stump.threshold >> stump.polarity >> stump.alpha))
    reader.fail (name + ": expected '<feature> <threshold> <polarity> <alpha>'");
  reader.expectEnd (fields, name);
  if (stump.feature < -1 || stump.feature >= dimension)
    reader.fail (name + ": feature " + std::to_string (stump.feature) + " outside [-1, " +
                 std::to_string (dimension) + ")");
  if (stump.polarity != 1 && stump.polarity != -1)
    reader.fail (name + ": polarity " + std::to_string (stump.polarity) + " is not +1 or -1");
  if (!std::isfinite (stump.threshold) || !std::isfinite (stump.alpha) || stump.alpha < 0.0)
    reader.fail (name + ": threshold and alpha must be finite, alpha >= 0");
  return stump;
}

}  // namespace

void
AdaBoostStumps::write (std::ostream& os) const
{
  std::ostringstream text;
  text.imbue (std::locale::classic ());
  text.precision (std::numeric_limits<double>::max_digits10);  // exact round trip
  text << kMagic << ' ' << kVersion << '\n';
  text << "dimension " << dimension_ << '\n';
  text << "stumps " << stumps_.size () << '\n';
  for (const Stump& stump : stumps_)
    text << stump.feature << ' ' << stump.threshold << ' ' << stump.polarity << ' ' << stump.alpha << '\n';
  os << text.str ();
}

void
AdaBoostStumps::read (std::istream& is)
{
  LineReader reader (is);
  {
    std::istringstream fields = reader.next ("the header");
    std::string magic;
    int version = 0;
    if (!(fields >> magic) || magic != kMagic)
      reader.fail (std::string ("expected the header '") + kMagic + " " + std::to_string (kVersion) + "'");
    if (!(fields >> version) || version != kVersion)
      reader.fail ("unsupported version, expected " + std::to_string (kVersion));
    reader.expectEnd (fields, "the header");
  }
  const int dimension = reader.keyValue ("dimension");
  const int count = reader.keyValue ("stumps");
  std::vector<Stump> stumps;
  stumps.reserve (std::min (count, 1 << 16));  // a corrupt count must not allocate first
  for (int t = 0; t < count; ++t)
    stumps.push_back (readStump (reader, dimension, t));
  stumps_ = std::move (stumps);
  dimension_ = dimension;
}

}  // namespace crf
}  // namespace pcl_crf
