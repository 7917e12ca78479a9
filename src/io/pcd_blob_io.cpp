#include "pcd_blob_io.h"

#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/io/readable_file.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

namespace pcl_crf {
namespace detail {
namespace {

/** \brief A field's layout as the PCD header spells it, e.g. "TYPE F SIZE 4 COUNT 1". */
std::string
describeLayout (int datatype, std::uint32_t count)
{
  const int size = pcl::getFieldSize (datatype);
  if (size == 0)
    return "a TYPE/SIZE pair PCL does not know";
  return "TYPE " + std::string (1, pcl::getFieldType (datatype)) + " SIZE " + std::to_string (size) + " COUNT " +
         std::to_string (count);
}

/** \brief A field pcl_crf can read: COUNT 1, of a numeric type PCL knows. */
bool
isReadable (const pcl::PCLPointField& field)
{
  return field.count == 1 && pcl::getFieldSize (field.datatype) != 0;
}

/** \brief The lines of a PCD header: keyword -> the words after it. */
using PcdHeaderLines = std::map<std::string, std::vector<std::string>>;

/** \brief The lines of the PCD header of \a path, read once: every keyword's first line
 *  up to DATA (or up to a blank line). */
PcdHeaderLines
headerLines (const std::string& path)
{
  PcdHeaderLines lines;
  std::ifstream in (path);
  std::string line, word;
  while (std::getline (in, line)) {
    std::istringstream words (line);
    if (!(words >> word))
      break;
    const std::string keyword = word;
    std::vector<std::string> rest;
    while (words >> word)
      rest.push_back (word);
    lines.emplace (keyword, std::move (rest));
    if (keyword == "DATA")
      break;
  }
  return lines;
}

/** \brief The words after \a keyword in \a lines (empty when the header has no such line). */
std::vector<std::string>
wordsAfter (const PcdHeaderLines& lines, const std::string& keyword)
{
  const auto found = lines.find (keyword);
  return found == lines.end () ? std::vector<std::string> () : found->second;
}

/** \brief Why \a name is not among the fields PCL read: PCL drops a field declared
 *  with COUNT 0 (with a warning of its own), so say so rather than call it missing. */
std::string
missingFieldMessage (const std::string& path, const std::string& name)
{
  const PcdHeaderLines lines = headerLines (path);
  const std::vector<std::string> names = wordsAfter (lines, "FIELDS");
  const std::vector<std::string> counts = wordsAfter (lines, "COUNT");
  for (std::size_t i = 0; i < names.size () && i < counts.size (); ++i)
    if (names[i] == name)
      return path + ": field '" + name + "' has COUNT " + counts[i] + ", must be 1";
  return path + ": missing field '" + name + "'";
}

/** \brief Checks that \a blob's header declares \a field, readable (isReadable).
 *  \return the field's index in \a blob. */
int
checkField (const pcl::PCLPointCloud2& blob, const PcdField& field, const std::string& path)
{
  const int index = pcl::getFieldIndex (blob, field.name);
  if (index < 0)
    throw DatasetError (missingFieldMessage (path, field.name));
  const pcl::PCLPointField& found = blob.fields[index];
  if (!isReadable (found))
    throw DatasetError (path + ": field '" + field.name + "' must be " + describeLayout (field.datatype, 1) +
                        " (or another TYPE and SIZE of COUNT 1), found " +
                        describeLayout (found.datatype, found.count));
  return index;
}

template <typename T> double
valueAt (const std::uint8_t* at)
{
  T value;
  std::memcpy (&value, at, sizeof (T));
  return static_cast<double> (value);
}

/** \brief The number stored at \a at as \a datatype (any PCD TYPE and SIZE). */
double
valueAt (const std::uint8_t* at, std::uint8_t datatype)
{
  switch (datatype) {
    case pcl::PCLPointField::INT8: return valueAt<std::int8_t> (at);
    case pcl::PCLPointField::UINT8: return valueAt<std::uint8_t> (at);
    case pcl::PCLPointField::INT16: return valueAt<std::int16_t> (at);
    case pcl::PCLPointField::UINT16: return valueAt<std::uint16_t> (at);
    case pcl::PCLPointField::INT32: return valueAt<std::int32_t> (at);
    case pcl::PCLPointField::UINT32: return valueAt<std::uint32_t> (at);
    case pcl::PCLPointField::INT64: return valueAt<std::int64_t> (at);
    case pcl::PCLPointField::UINT64: return valueAt<std::uint64_t> (at);
    case pcl::PCLPointField::FLOAT32: return valueAt<float> (at);
    case pcl::PCLPointField::FLOAT64: return valueAt<double> (at);
    default: return valueAt<std::uint8_t> (at);  // BOOL, the one type left that PCL gives a size
  }
}

template <typename T> void
storeAs (double value, std::uint8_t* at)
{
  const T stored = static_cast<T> (value);
  std::memcpy (at, &stored, sizeof (T));
}

/** \brief Stores \a value as the field \a field expects: a float, or a whole number
 *  in the range of its integer type (\throws DatasetError naming the point otherwise). */
void
storeValue (double value, const PcdField& field, std::size_t point, const std::string& path, std::uint8_t* at)
{
  if (field.datatype == pcl::PCLPointField::FLOAT32) {
    storeAs<float> (value, at);  // a NaN or an overflow is reported with the coordinates
    return;
  }
  const bool is_signed = field.datatype == pcl::PCLPointField::INT32;
  const double lowest = is_signed ? std::numeric_limits<std::int32_t>::lowest () : 0.0;
  const double highest = is_signed ? std::numeric_limits<std::int32_t>::max () : std::numeric_limits<std::uint32_t>::max ();
  if (!(value >= lowest && value <= highest) || value != std::floor (value)) {
    std::ostringstream what;
    what << std::setprecision (17) << path << ": point " << point << " has " << field.name << " " << value
         << ", not a whole number in [" << lowest << ", " << highest << "] (" << describeLayout (field.datatype, 1)
         << ")";
    throw DatasetError (what.str ());
  }
  if (is_signed)
    storeAs<std::int32_t> (value, at);
  else
    storeAs<std::uint32_t> (value, at);
}

/** \brief A copy of \a blob holding only \a fields, each converted to its expected
 *  datatype (a PCD writer may store x as float64 or a label as int32). */
pcl::PCLPointCloud2
convertFields (const pcl::PCLPointCloud2& blob, const std::vector<PcdField>& fields, const std::string& path)
{
  pcl::PCLPointCloud2 converted;
  converted.header = blob.header;
  converted.width = blob.width;
  converted.height = blob.height;
  converted.is_bigendian = blob.is_bigendian;
  converted.is_dense = blob.is_dense;
  for (const PcdField& field : fields) {
    pcl::PCLPointField out;
    out.name = field.name;
    out.offset = converted.point_step;
    out.datatype = field.datatype;
    out.count = 1;
    converted.fields.push_back (out);
    converted.point_step += static_cast<std::uint32_t> (pcl::getFieldSize (field.datatype));
  }
  const std::size_t points = static_cast<std::size_t> (blob.width) * blob.height;
  converted.row_step = converted.point_step * converted.width;
  converted.data.resize (points * converted.point_step);
  for (std::size_t k = 0; k < fields.size (); ++k) {
    const pcl::PCLPointField& in = blob.fields[pcl::getFieldIndex (blob, fields[k].name)];
    for (std::size_t i = 0; i < points; ++i) {
      const double value = valueAt (&blob.data[i * blob.point_step + in.offset], in.datatype);
      storeValue (value, fields[k], i, path, &converted.data[i * converted.point_step + converted.fields[k].offset]);
    }
  }
  return converted;
}

/** \brief The most bytes one byte of LZF data (binary_compressed) unpacks to: a
 *  back-reference of 3 bytes unpacks to at most 264. */
constexpr double kLzfMostUnpackedPerByte = 88.0;

/** \brief The PCD header's DATA encodings, as PCDReader::readHeader () numbers them. */
enum PcdEncoding : int
{
  kAscii = 0,
  kBinary = 1,
  kBinaryCompressed = 2
};

/** \brief How many points the ASCII body of \a path after byte \a data_index holds: its
 *  lines with a value on them (PCL's reader skips blank lines and comments). */
std::size_t
asciiPointCount (const std::string& path, std::size_t data_index)
{
  std::ifstream in (path, std::ios::binary);
  in.seekg (static_cast<std::streamoff> (data_index));
  std::size_t count = 0;
  std::string line;
  while (std::getline (in, line)) {
    const auto first = line.find_first_not_of (" \t\r");
    count += first != std::string::npos && line[first] != '#' ? 1 : 0;
  }
  return count;
}

/** \brief The largest point count a PCD header declares (\a lines), in POINTS or as WIDTH
 *  x HEIGHT (0 for words that are not counts: PCL's reader names those). */
double
declaredPointCount (const PcdHeaderLines& lines)
{
  const auto count = [&lines] (const char* keyword) {
    const std::vector<std::string> words = wordsAfter (lines, keyword);
    const std::optional<double> value = words.size () == 1 ? parseDecimal (words[0]) : std::nullopt;
    return value && *value > 0.0 ? *value : 0.0;
  };
  return std::max (count ("POINTS"), count ("WIDTH") * count ("HEIGHT"));
}

/** \brief Checks, before PCL's reader allocates the cloud the header of \a path (its
 *  \a lines) declares, that a file of its size can hold that many points (each takes a
 *  byte at the least, a binary_compressed byte unpacks to at most kLzfMostUnpackedPerByte).
 *  \throws DatasetError naming the file and both counts */
void
checkDeclaredPointCount (const std::string& path, const PcdHeaderLines& lines)
{
  const double file_size = static_cast<double> (std::filesystem::file_size (path));
  const double declared = declaredPointCount (lines);
  if (declared > kLzfMostUnpackedPerByte * file_size) {
    std::ostringstream what;
    what << path << ": the header declares " << std::setprecision (15) << declared << " points, more than a file of "
         << file_size << " bytes can hold";
    throw DatasetError (what.str ());
  }
}

/** \brief The most values of one field a point may hold (COUNT), and the most bytes a
 *  point may take: far above any scan's fields, far below what would make PCL's reader
 *  allocate gigabytes from a header of a few bytes. */
constexpr double kMaxPcdCount = 1e4;
constexpr double kMaxPcdPointBytes = 1e5;

/** \brief \a word as a count of at most \a most: decimal digits only, as PCL's reader
 *  reads it into an integer ("1e7" or "10…0e-1989" would be read as the digits before the
 *  e, overflowing), or nothing. */
std::optional<double>
headerCount (const std::string& word, double most)
{
  constexpr std::size_t kMostDigits = 10;
  if (word.empty () || word.size () > kMostDigits ||
      !std::all_of (word.begin (), word.end (), [] (char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  const std::optional<double> value = parseDecimal (word);
  if (!value || *value > most)
    return std::nullopt;
  return value;
}

/** \brief \a word for a message: its first 40 characters, "..." after them. */
std::string
shortWord (const std::string& word)
{
  constexpr std::size_t kShown = 40;
  return word.size () <= kShown ? word : word.substr (0, kShown) + "...";
}

/** \brief Checks the header of \a path before PCL's reader sees it: PCL's readHeader ()
 *  reads negative or huge WIDTH, HEIGHT, POINTS, SIZE and COUNT words into unsigned
 *  integers and allocates from them (a segmentation fault, std::bad_alloc or 1.2 GB from
 *  a 168-byte file), and a bare DATA line throws std::out_of_range. Every FIELDS entry
 *  needs a SIZE, TYPE and (when there is a COUNT line) COUNT; SIZE is 1, 2, 4 or 8 and
 *  TYPE I, U or F (F of size 4 or 8); COUNT is a whole number up to kMaxPcdCount and a
 *  point takes at most kMaxPcdPointBytes; WIDTH, HEIGHT and POINTS are whole numbers
 *  below 2^31; DATA is ascii, binary or binary_compressed; the file can hold the points
 *  declared (checkDeclaredPointCount ()).
 *  \throws DatasetError naming the file, the line and the word */
void
checkHeader (const std::string& path)
{
  const PcdHeaderLines lines = headerLines (path);
  const auto fail = [&path] (const std::string& what) { throw DatasetError (path + ": PCD header: " + what); };
  const std::vector<std::string> names = wordsAfter (lines, "FIELDS"), sizes = wordsAfter (lines, "SIZE"),
                                 types = wordsAfter (lines, "TYPE"), counts = wordsAfter (lines, "COUNT");
  if (names.empty () || sizes.empty () || types.empty ())
    throw DatasetError (path + ": not a PCD file (unreadable header, or no FIELDS/SIZE/TYPE)");
  if (sizes.size () != names.size () || types.size () != names.size () ||
      (lines.count ("COUNT") && counts.size () != names.size ()))
    fail ("FIELDS names " + std::to_string (names.size ()) + " fields, SIZE gives " + std::to_string (sizes.size ()) +
          " sizes, TYPE " + std::to_string (types.size ()) + " types" +
          (lines.count ("COUNT") ? ", COUNT " + std::to_string (counts.size ()) + " counts" : std::string ()));
  double point_bytes = 0.0;
  for (std::size_t k = 0; k < names.size (); ++k) {
    const std::optional<double> size = headerCount (sizes[k], 8);
    const std::string& type = types[k];
    if (!size || (*size != 1 && *size != 2 && *size != 4 && *size != 8) ||
        (type != "I" && type != "U" && type != "F") || (type == "F" && *size != 4 && *size != 8))
      fail ("field '" + shortWord (names[k]) + "' has SIZE " + shortWord (sizes[k]) + " and TYPE " + shortWord (type) +
            " (SIZE 1, 2, 4 or 8 and TYPE I, U or F; F of SIZE 4 or 8)");
    const std::optional<double> count = counts.empty () ? 1.0 : headerCount (counts[k], kMaxPcdCount);
    if (!count)
      fail ("field '" + shortWord (names[k]) + "' has COUNT " + shortWord (counts[k]) + " (a whole number from 0 to 10000)");
    point_bytes += *size * *count;
  }
  if (point_bytes > kMaxPcdPointBytes)
    fail ("a point takes " + formatGeneral (point_bytes, 17) + " bytes (at most 100000)");
  constexpr double kMostPoints = 2147483647.0;
  std::map<std::string, double> extent;  // WIDTH, HEIGHT and (when given) POINTS
  for (const char* keyword : {"WIDTH", "HEIGHT", "POINTS"}) {
    const std::vector<std::string> words = wordsAfter (lines, keyword);
    if (!lines.count (keyword) && std::string (keyword) == "POINTS")
      continue;  // optional (PCD v0.6)
    const std::optional<double> value = words.size () == 1 ? headerCount (words[0], kMostPoints) : std::nullopt;
    if (!value)
      fail (std::string (keyword) + " must be one whole number from 0 to 2147483647, not '" +
            (words.empty () ? std::string () : shortWord (words[0])) + (words.size () > 1 ? " ..." : "") + "'");
    extent[keyword] = *value;
  }
  if (extent.count ("POINTS") && extent["POINTS"] != extent["WIDTH"] * extent["HEIGHT"])
    fail ("POINTS " + formatGeneral (extent["POINTS"], 17) + " is not WIDTH x HEIGHT = " +
          formatGeneral (extent["WIDTH"], 17) + " x " + formatGeneral (extent["HEIGHT"], 17));
  const std::vector<std::string> data = wordsAfter (lines, "DATA");
  if (data.size () != 1 || (data[0] != "ascii" && data[0] != "binary" && data[0] != "binary_compressed"))
    fail ("the DATA line must name one of ascii, binary, binary_compressed");
  checkDeclaredPointCount (path, lines);  // PCL's readHeader () allocates the declared cloud
}

/** \brief The two sizes a binary_compressed body starts with. */
struct CompressedSizes
{
  std::uint32_t compressed = 0;
  std::uint32_t uncompressed = 0;
};

CompressedSizes
compressedSizes (const std::string& path, std::size_t data_index)
{
  std::ifstream in (path, std::ios::binary);
  in.seekg (static_cast<std::streamoff> (data_index));
  CompressedSizes sizes;
  in.read (reinterpret_cast<char*> (&sizes.compressed), sizeof (sizes.compressed));
  in.read (reinterpret_cast<char*> (&sizes.uncompressed), sizeof (sizes.uncompressed));
  return sizes;
}

/** \brief Checks that the body of \a path holds the points its header declares, before
 *  PCL reads it. PCL's reader trusts the header: it reads past the end of a short binary
 *  body, crashes on a compressed one whose sizes disagree with it, first allocates
 *  whatever a corrupt POINTS asks for, and drops data beyond POINTS without a word.
 *  \throws DatasetError naming the file, the count declared and the count found */
void
checkBodySize (const std::string& path, const pcl::PCLPointCloud2& header, int encoding, std::size_t data_index)
{
  const std::size_t points = static_cast<std::size_t> (header.width) * header.height;
  const std::size_t step = header.point_step;
  const std::size_t file_size = std::filesystem::file_size (path);
  const std::size_t body = file_size > data_index ? file_size - data_index : 0;
  const std::string declared = path + ": the header declares " + std::to_string (points) + " points (WIDTH x HEIGHT, POINTS)";
  if (encoding == kAscii) {
    const std::size_t found = asciiPointCount (path, data_index);
    if (found != points)
      throw DatasetError (declared + ", the ascii data hold " + std::to_string (found));
    return;
  }
  if (encoding == kBinary) {
    if (body < points * step || body / step > points)
      throw DatasetError (declared + " of " + std::to_string (step) + " bytes, the binary data hold " +
                          std::to_string (body) + " bytes");
    return;
  }
  if (encoding != kBinaryCompressed)
    throw DatasetError (path + ": unknown DATA encoding (ascii, binary or binary_compressed)");
  const CompressedSizes sizes = body >= 8 ? compressedSizes (path, data_index) : CompressedSizes{};
  if (body < 8 || body - 8 < sizes.compressed)
    throw DatasetError (path + ": the binary_compressed data are truncated (" + std::to_string (body) +
                        " bytes after the header, " + std::to_string (sizes.compressed) + " compressed bytes declared)");
  if (sizes.uncompressed != points * step)
    throw DatasetError (declared + " of " + std::to_string (step) + " bytes, the binary_compressed data unpack to " +
                        std::to_string (sizes.uncompressed) + " bytes");
  // A body that claims to unpack to more than LZF can is corrupt, however the header agrees with it.
  if (sizes.uncompressed > kLzfMostUnpackedPerByte * static_cast<double> (sizes.compressed))
    throw DatasetError (path + ": " + std::to_string (sizes.compressed) + " compressed bytes cannot unpack to the " +
                        std::to_string (sizes.uncompressed) + " bytes declared (corrupt binary_compressed data)");
}

/** \brief The words of \a line, split at spaces, tabs and carriage returns. */
void
splitWords (const std::string& line, std::vector<std::string_view>& words)
{
  words.clear ();
  const std::string_view text (line);
  std::size_t begin = text.find_first_not_of (" \t\r");
  while (begin != std::string_view::npos) {
    const std::size_t end = std::min (text.find_first_of (" \t\r", begin), text.size ());
    words.push_back (text.substr (begin, end - begin));
    begin = text.find_first_not_of (" \t\r", end);
  }
}

template <typename T> bool
storeWhole (double value, std::uint8_t* at)
{
  // max () + 1 is a power of two, exact as a double (max () itself is not, for 64 bits).
  if (value != std::floor (value) || value < static_cast<double> (std::numeric_limits<T>::lowest ()) ||
      !(value < static_cast<double> (std::numeric_limits<T>::max ()) + 1.0))
    return false;
  storeAs<T> (value, at);
  return true;
}

/** \brief Stores the ascii value \a word at \a at as \a datatype: "nan" (any case) is
 *  NaN, as PCL reads it, and only in a float field; a number is read with
 *  parseDecimal (); an integer field takes whole numbers in its type's range.
 *  \return false when \a word is none of these */
bool
storeAsciiValue (std::string_view word, std::uint8_t datatype, std::uint8_t* at)
{
  const bool nan = word.size () == 3 && std::tolower (word[0]) == 'n' && std::tolower (word[1]) == 'a' &&
                   std::tolower (word[2]) == 'n';
  if (datatype == pcl::PCLPointField::FLOAT32) {
    const std::optional<float> value = nan ? std::numeric_limits<float>::quiet_NaN () : parseDecimalFloat (word);
    if (value)
      storeAs<float> (*value, at);
    return value.has_value ();
  }
  const std::optional<double> value = nan ? std::numeric_limits<double>::quiet_NaN () : parseDecimal (word);
  if (datatype == pcl::PCLPointField::FLOAT64 && value) {
    storeAs<double> (*value, at);
    return true;
  }
  if (!value || nan)
    return false;
  switch (datatype) {
    case pcl::PCLPointField::INT8: return storeWhole<std::int8_t> (*value, at);
    case pcl::PCLPointField::UINT8: return storeWhole<std::uint8_t> (*value, at);
    case pcl::PCLPointField::INT16: return storeWhole<std::int16_t> (*value, at);
    case pcl::PCLPointField::UINT16: return storeWhole<std::uint16_t> (*value, at);
    case pcl::PCLPointField::INT32: return storeWhole<std::int32_t> (*value, at);
    case pcl::PCLPointField::UINT32: return storeWhole<std::uint32_t> (*value, at);
    case pcl::PCLPointField::INT64: return storeWhole<std::int64_t> (*value, at);
    case pcl::PCLPointField::UINT64: return storeWhole<std::uint64_t> (*value, at);
    default: return storeWhole<std::uint8_t> (*value, at);  // BOOL, the one type left that PCL gives a size
  }
}

/** \brief [lowest, max] of integer type \a T, as text. */
template <typename T>
std::string
wholeRange ()
{
  return "[" + std::to_string (+std::numeric_limits<T>::lowest ()) + ", " + std::to_string (+std::numeric_limits<T>::max ()) +
         "]";
}

/** \brief The range of integer \a datatype as text; empty for a float type. */
std::string
wholeRange (std::uint8_t datatype)
{
  switch (datatype) {
    case pcl::PCLPointField::INT8: return wholeRange<std::int8_t> ();
    case pcl::PCLPointField::UINT8: return wholeRange<std::uint8_t> ();
    case pcl::PCLPointField::INT16: return wholeRange<std::int16_t> ();
    case pcl::PCLPointField::UINT16: return wholeRange<std::uint16_t> ();
    case pcl::PCLPointField::INT32: return wholeRange<std::int32_t> ();
    case pcl::PCLPointField::UINT32: return wholeRange<std::uint32_t> ();
    case pcl::PCLPointField::INT64: return wholeRange<std::int64_t> ();
    case pcl::PCLPointField::UINT64: return wholeRange<std::uint64_t> ();
    default: return {};
  }
}

/** \brief What is wrong with the ascii value \a word that storeAsciiValue () refused
 *  for \a field: no decimal number, or a number outside the integer type's range. */
std::string
asciiValueProblem (std::string_view word, const pcl::PCLPointField& field)
{
  const std::string layout = describeLayout (field.datatype, field.count);
  const std::string range = wholeRange (field.datatype);
  if (range.empty () || !parseDecimal (word))
    return "not a decimal number of its " + layout;
  return "not a whole number in " + range + " (its " + layout + ")";
}

/** \brief Reads the ascii body of \a path (after byte \a data_index) into \a blob, whose
 *  header is read, the same whatever the program's locale (storeAsciiValue ()). PCL's
 *  reader parses with a stream in the global C++ locale: after a host program's
 *  std::locale::global (std::locale ("de_DE.UTF-8")) it read "-9.2848825" as -9. Blank
 *  and '#' lines are skipped, as PCL skips them (checkBodySize () counted the others).
 *  \throws DatasetError naming the point and the value that is not a number of its field */
void
readAsciiBody (const std::string& path, std::size_t data_index, pcl::PCLPointCloud2& blob)
{
  std::size_t values_per_point = 0;
  for (const pcl::PCLPointField& field : blob.fields)
    values_per_point += field.count;
  const std::size_t points = static_cast<std::size_t> (blob.width) * blob.height;
  blob.data.assign (points * blob.point_step, 0);
  blob.is_dense = true;
  std::ifstream in (path, std::ios::binary);
  in.seekg (static_cast<std::streamoff> (data_index));
  std::string line;
  std::vector<std::string_view> words;
  for (std::size_t point = 0; point < points && std::getline (in, line);) {
    splitWords (line, words);
    if (words.empty () || words.front ().front () == '#')
      continue;
    if (words.size () != values_per_point)
      throw DatasetError (path + ": point " + std::to_string (point) + " has " + std::to_string (words.size ()) +
                          " values, the header's fields take " + std::to_string (values_per_point));
    std::size_t word = 0;
    for (const pcl::PCLPointField& field : blob.fields)
      for (std::uint32_t k = 0; k < field.count; ++k, ++word) {
        std::uint8_t* at = &blob.data[point * blob.point_step + field.offset + k * pcl::getFieldSize (field.datatype)];
        if (!storeAsciiValue (words[word], field.datatype, at))
          throw DatasetError (path + ": point " + std::to_string (point) + " has " + field.name + " '" +
                              std::string (words[word]) + "', " + asciiValueProblem (words[word], field));
        blob.is_dense = blob.is_dense && !std::isnan (valueAt (at, field.datatype));
      }
    ++point;
  }
}

}  // namespace

pcl::PCLPointCloud2
readPcdBlob (const std::string& path, const std::vector<PcdField>& fields)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw DatasetError (path + ": " + (problem == "no such file" ? "file not found" : problem));
  checkHeader (path);  // before PCL's readHeader () reads and allocates from it
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_index = 0;
  if (reader.readHeader (path, blob, origin, orientation, version, data_type, data_index) != 0 ||
      blob.fields.empty () || blob.point_step == 0)
    throw DatasetError (path + ": not a PCD file (unreadable header, or no FIELDS/SIZE/TYPE)");
  if (static_cast<std::size_t> (blob.width) * blob.height == 0)
    throw DatasetError (path + ": PCD header declares no points");
  checkBodySize (path, blob, data_type, data_index);
  bool exact = true;
  for (const auto& field : fields)
    exact = blob.fields[checkField (blob, field, path)].datatype == field.datatype && exact;
  if (data_type == kAscii)
    readAsciiBody (path, data_index, blob);
  else if (reader.read (path, blob) != 0)
    throw DatasetError (path + ": not a readable PCD file (truncated or corrupt data)");
  if (exact)
    return blob;
  std::vector<PcdField> kept = fields;  // z too, when the file has it (the point types hold one)
  const int z = pcl::getFieldIndex (blob, "z");
  if (z >= 0 && isReadable (blob.fields[z]))
    kept.push_back ({"z", pcl::PCLPointField::FLOAT32});
  return convertFields (blob, kept, path);
}

}  // namespace detail
}  // namespace pcl_crf
