#pragma once
// Internal: the line reader of the CRF-Matching model file (matching_model_io.cpp).

#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/crf/adaboost_stumps.h>

#include <cmath>
#include <istream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl_crf {
namespace matching {
namespace detail {

/** Reads the model line by line, skipping blank and '#' lines, with errors
 *  "<name>: line <n>: <problem>". */
class ModelReader
{
public:
  ModelReader (std::istream& is, std::string name) : is_ (is), name_ (std::move (name)) {}

  [[noreturn]] void
  fail (const std::string& what) const
  {
    throw std::runtime_error (name_ + ": line " + std::to_string (line_number_) + ": " + what);
  }

  /** The next meaningful line, split into words; \a expected names it for errors. */
  std::vector<std::string>
  nextLine (const std::string& expected)
  {
    if (!pending_.empty ()) {
      std::vector<std::string> tokens;
      tokens.swap (pending_);
      return tokens;
    }
    std::string line;
    while (std::getline (is_, line)) {
      ++line_number_;
      std::istringstream words (line);
      std::vector<std::string> tokens;
      for (std::string word; words >> word;)
        tokens.push_back (word);
      if (!tokens.empty () && tokens.front ()[0] != '#')
        return tokens;
    }
    ++line_number_;
    fail ("unexpected end of file, missing " + expected);
  }

  /** The next line "key v1 … vN" (N = \a count, or any when count < 0); returns the values. */
  std::vector<std::string>
  keyLine (const std::string& key, int count = 1)
  {
    std::vector<std::string> tokens = nextLine ("'" + key + "'");
    if (tokens.front () != key)
      fail ("expected '" + key + "', found '" + tokens.front () + "' (missing or misplaced field)");
    tokens.erase (tokens.begin ());
    if (count >= 0 && static_cast<int> (tokens.size ()) != count)
      fail ("'" + key + "' needs " + std::to_string (count) + " value(s), found " + std::to_string (tokens.size ()));
    return tokens;
  }

  double
  number (const std::string& key, const std::string& text) const
  {
    const std::optional<double> value = parseDecimal (text);
    if (!value)
      fail ("'" + key + "': '" + text + "' is not a finite decimal number");
    return *value;
  }

  /** \a value as the shortest text that reads back as it ("0.25", "-1", "1e-09"). */
  static std::string
  shortest (double value)
  {
    std::string text;
    for (int digits = 1; digits <= 17; ++digits) {
      text = formatGeneral (value, digits);
      if (parseDecimal (text) == value)
        break;
    }
    return text;
  }

  /** [\a min, \a max] in words: "in [0, 1.5]", ">= 0", or "> 0" for the smallest positive double. */
  static std::string
  range (double min, double max)
  {
    if (max < std::numeric_limits<double>::max ())
      return "in [" + shortest (min) + ", " + shortest (max) + "]";
    return min == std::numeric_limits<double>::min () ? "> 0" : ">= " + shortest (min);
  }

  double
  real (const std::string& key, double min, double max = std::numeric_limits<double>::max ())
  {
    const double value = number (key, keyLine (key).front ());
    if (value < min || value > max)
      fail ("'" + key + "' = " + shortest (value) + " must be " + range (min, max));
    return value;
  }

  /** A "key value" line that older files lack: \a absent when the next line is another key. */
  double
  optionalReal (const std::string& key, double absent, double min, double max)
  {
    return nextLineIs (key) ? real (key, min, max) : absent;
  }

  /** optionalReal () for an integer (key, min, max). */
  int
  optionalInteger (const std::string& key, int absent, int min, int max)
  {
    return nextLineIs (key) ? integer (key, min, max) : absent;
  }

  int
  integer (const std::string& key, int min, int max)
  {
    const std::string text = keyLine (key).front ();
    const double value = number (key, text);
    if (value != std::floor (value) || value < min || value > max)
      fail ("'" + key + "' = " + text + " is not an integer in [" + std::to_string (min) + ", " +
            std::to_string (max) + "]");
    return static_cast<int> (value);
  }

  /** An AdaBoost block as AdaBoostStumps::write wrote it, after a "key" line. */
  void
  booster (const std::string& key, int dimension, crf::AdaBoostStumps& booster)
  {
    keyLine (key, 0);
    const int first_line = line_number_ + 1;
    std::string block;
    for (int k = 0; k < 3; ++k) {
      std::string line;
      ++line_number_;
      if (!std::getline (is_, line))
        fail ("unexpected end of file inside '" + key + "'");
      block += line + '\n';
      if (k == 2)
        appendStumpLines (key, line, block);
    }
    std::istringstream stream (block);
    try {
      booster.read (stream);
    }
    catch (const std::runtime_error& error) {
      throw std::runtime_error (name_ + ": '" + key + "' block starting at line " + std::to_string (first_line) +
                                ": " + error.what ());
    }
    if (booster.getDimension () != dimension)
      fail ("'" + key + "' has dimension " + std::to_string (booster.getDimension ()) + ", expected " +
            std::to_string (dimension));
  }

private:
  /** Whether the next meaningful line starts with \a key; the line is kept for the next read. */
  bool
  nextLineIs (const std::string& key)
  {
    pending_ = nextLine ("'" + key + "' or what follows it");
    return pending_.front () == key;
  }

  /** Reads the stump lines announced by "stumps N" into block. */
  void
  appendStumpLines (const std::string& key, const std::string& count_line, std::string& block)
  {
    std::istringstream fields (count_line);
    std::string word;
    long long count = -1;
    if (!(fields >> word >> count) || word != "stumps" || count < 0 || count > 100000)
      fail ("'" + key + "': expected 'stumps <count>' (count in [0, 100000])");
    for (long long t = 0; t < count; ++t) {
      std::string line;
      ++line_number_;
      if (!std::getline (is_, line))
        fail ("unexpected end of file inside '" + key + "' (stump " + std::to_string (t) + " of " +
              std::to_string (count) + ")");
      block += line + '\n';
    }
  }

  std::istream& is_;
  std::string name_;
  int line_number_ = 0;
  std::vector<std::string> pending_;  // a line read ahead by nextLineIs
};


}  // namespace detail
}  // namespace matching
}  // namespace pcl_crf
