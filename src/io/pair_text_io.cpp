#include "pair_text_io.h"

#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/io/readable_file.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <locale>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

namespace pcl_crf {
namespace detail {
namespace {

constexpr const char* kMagic = "pcl_crf_pair";
constexpr int kVersion = 1;

struct LineReader
{
  std::string path;
  int line_number = 0;

  [[noreturn]] void
  fail (const std::string& what) const
  {
    throw DatasetError (path + ":" + std::to_string (line_number) + ": " + what);
  }

  double
  number (std::istringstream& in, const char* what) const
  {
    std::string token;
    if (!(in >> token))
      fail (std::string ("missing ") + what);
    const std::optional<double> value = parseDecimal (token);
    if (!value)
      fail (std::string ("'") + token + "' is not a finite decimal number (" + what + ")");
    return *value;
  }

  /** A whole number in [lowest, most] (the line's documented range, within int's). */
  int
  integer (std::istringstream& in, const char* what, int lowest = std::numeric_limits<int>::lowest (),
           int most = std::numeric_limits<int>::max ()) const
  {
    const double value = number (in, what);
    if (value != std::floor (value) || value < lowest || value > most)
      fail (std::string (what) + " must be a whole number in [" + std::to_string (lowest) + ", " +
            std::to_string (most) + "], not " + formatGeneral (value, 17));
    return static_cast<int> (value);
  }

  void
  expectEnd (std::istringstream& in) const
  {
    std::string extra;
    if (in >> extra)
      fail ("unexpected trailing value '" + extra + "'");
  }
};

void
readHeader (LineReader& reader, std::istringstream& in)
{
  if (reader.integer (in, "format version") != kVersion)
    reader.fail ("unsupported format version (this reader knows version " +
                 std::to_string (kVersion) + ")");
}

void
readObject (LineReader& reader, std::istringstream& in, ScanPair& pair)
{
  ObjectTruth object;
  object.id = reader.integer (in, "object id", 0);
  std::string motion_kind;
  in >> motion_kind;
  if (motion_kind != "static" && motion_kind != "moving")
    reader.fail ("object motion kind must be 'static' or 'moving', got '" + motion_kind + "'");
  object.is_static = motion_kind == "static";
  const double x = reader.number (in, "object x");
  const double y = reader.number (in, "object y");
  const double theta = reader.number (in, "object theta");
  object.T_target_source = makeRigid2d (x, y, theta);
  if (!(in >> object.kind))
    reader.fail ("missing object kind (e.g. world, car, pedestrian)");
  reader.expectEnd (in);
  pair.objects.push_back (object);
}

}  // namespace

void
readPairText (const std::string& path, ScanPair& pair)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw DatasetError (path + ": cannot read (" + problem + "; missing pair.txt?)");
  std::ifstream file (path);
  LineReader reader{path};
  std::set<std::string> seen;  // the keys given at most once (every key but object)
  const auto once = [&reader, &seen] (const std::string& key) {
    if (!seen.insert (key).second)
      reader.fail ("'" + key + "' given twice");
  };
  std::string line;
  while (std::getline (file, line)) {
    ++reader.line_number;
    std::istringstream in (line);
    std::string key;
    if (!(in >> key) || key[0] == '#')
      continue;
    if (seen.count (kMagic) == 0 && key != kMagic)
      reader.fail (std::string ("the first line must be '") + kMagic + " " + std::to_string (kVersion) + "'");
    if (key != "object")
      once (key);
    if (key == kMagic)
      readHeader (reader, in);
    else if (key == "sensor") {
      pair.sensor.beam_count = reader.integer (in, "beam count", 1, kMaxBeamCount);
      pair.sensor.angle_min = reader.number (in, "angle_min");
      pair.sensor.angle_increment = reader.number (in, "angle_increment");
      pair.sensor.range_max = reader.number (in, "range_max");
    }
    else if (key == "odometry") {
      const double x = reader.number (in, "odometry x");
      const double y = reader.number (in, "odometry y");
      const double theta = reader.number (in, "odometry theta");
      pair.odometry.T_source_target = makeRigid2d (x, y, theta);
    }
    else if (key == "odometry_covariance") {
      for (int k = 0; k < 9; ++k)
        pair.odometry.covariance (k / 3, k % 3) = reader.number (in, "odometry covariance entry");
    }
    else if (key == "interval") {
      pair.odometry.interval = reader.number (in, "interval");
      if (!(pair.odometry.interval > 0.0))
        reader.fail ("the interval between the scans must be > 0 s (leave the line out when unknown)");
    }
    else if (key == "object")
      readObject (reader, in, pair);
    else
      reader.fail ("unknown key '" + key + "'");
    reader.expectEnd (in);
  }
  const auto failInFile = [&path] (const std::string& what) { throw DatasetError (path + ": " + what); };
  if (seen.count (kMagic) == 0)
    failInFile ("empty file or missing header line");
  for (const char* key : {"sensor", "odometry", "odometry_covariance"})
    if (seen.count (key) == 0)
      failInFile (std::string ("missing '") + key + "' line");
}

void
writePairText (const ScanPair& pair, const std::string& path)
{
  std::ofstream file (path);
  if (!file)
    throw DatasetError (path + ": cannot write");
  file.imbue (std::locale::classic ());  // ids without a host program's digit grouping
  const auto exact = [] (double value) { return formatGeneral (value, 17); };
  const auto xyt = [&exact] (const Rigid2d& T) {
    const Eigen::Vector3d v = toXYTheta (T);
    return exact (v.x ()) + " " + exact (v.y ()) + " " + exact (v.z ());
  };
  file << kMagic << " " << kVersion << "\n";
  file << "sensor " << pair.sensor.beam_count << " " << exact (pair.sensor.angle_min) << " "
       << exact (pair.sensor.angle_increment) << " " << exact (pair.sensor.range_max) << "\n";
  file << "odometry " << xyt (pair.odometry.T_source_target) << "\n";
  file << "odometry_covariance";
  for (int k = 0; k < 9; ++k)
    file << " " << exact (pair.odometry.covariance (k / 3, k % 3));
  file << "\n";
  if (pair.odometry.interval > 0.0)
    file << "interval " << exact (pair.odometry.interval) << "\n";
  for (const auto& object : pair.objects)
    file << "object " << object.id << (object.is_static ? " static " : " moving ")
         << xyt (object.T_target_source) << " " << (object.kind.empty () ? "object" : object.kind)
         << "\n";
  if (!file)
    throw DatasetError (path + ": write failed");
}

}  // namespace detail
}  // namespace pcl_crf
