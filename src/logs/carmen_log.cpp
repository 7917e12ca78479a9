#include <pcl_crf/logs/carmen_log.h>
#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/io/readable_file.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>

namespace pcl_crf {
namespace {

/** Poses a log writes as text agree to this [m, rad] when they are one pose. */
constexpr double kSamePoseTolerance = 1e-6;

/** Reads whitespace-separated words and numbers from one log line. */
class LineCursor
{
public:
  explicit LineCursor (const std::string& line) : position_ (line.c_str ()) {}

  /** The next word as a finite decimal number (parseDecimal ()); false, with \a value
   *  untouched, at the end of the line or when the word is not one. */
  bool
  nextNumber (double& value)
  {
    std::string word;
    if (!nextWord (word))
      return false;
    const std::optional<double> number = parseDecimal (word);
    if (number)
      value = *number;
    return number.has_value ();
  }

  bool
  nextWord (std::string& word)
  {
    skipSpace ();
    const char* begin = position_;
    while (*position_ != '\0' && !std::isspace (static_cast<unsigned char> (*position_)))
      ++position_;
    word.assign (begin, position_);
    return !word.empty ();
  }

private:
  void
  skipSpace ()
  {
    while (*position_ != '\0' && std::isspace (static_cast<unsigned char> (*position_)))
      ++position_;
  }

  const char* position_;
};

/** One laser record as logged, before the odometry rule is applied. */
struct RawScan
{
  LaserScanRecord record;
  Rigid2d odometry_fields = Rigid2d::Identity ();
  /** last ODOM pose seen between the previous laser record and this one. */
  std::optional<Rigid2d> last_odom_before;
  /** first ODOM pose seen between this laser record and the next one. */
  std::optional<Rigid2d> first_odom_after;
};

/** true when the laser records' poses are corrected (reference) poses, as in the Radish
 *  "-corrected" logs: every record's odometry fields equal its pose, and the ODOM stream
 *  is re-anchored at the records (the first ODOM line after every record that has one
 *  equals its pose, and at least one record has one). A raw log's pose and odometry
 *  fields are both the robot's odometry, so they are equal too; its ODOM stream is the
 *  odometry itself, which has moved on from a record's pose by the next ODOM line
 *  unless the robot stands still. */
bool
hasCorrectedPoses (const std::vector<RawScan>& scans)
{
  bool anchored = false;
  for (const auto& scan : scans) {
    if (!samePose (scan.odometry_fields, scan.record.pose, kSamePoseTolerance))
      return false;
    if (scan.first_odom_after && !samePose (*scan.first_odom_after, scan.record.pose, kSamePoseTolerance))
      return false;
    anchored = anchored || scan.first_odom_after.has_value ();
  }
  return anchored;
}

class CarmenParser
{
public:
  CarmenParser (const std::string& name, const CarmenReadOptions& options) : name_ (name), options_ (options) {}

  /** Parses one line; returns false once max_scans laser records were read. */
  bool
  parseLine (const std::string& line, std::size_t line_number)
  {
    line_number_ = line_number;
    LineCursor cursor (line);
    std::string type;
    if (!cursor.nextWord (type) || type[0] == '#')
      return true;
    if (type == "ODOM")
      parseOdom (cursor);
    else if (type == "FLASER")
      parseFlaser (cursor);
    else if (type == "ROBOTLASER1")
      parseRobotLaser (cursor);
    return options_.max_scans == 0 || scans_.size () < options_.max_scans;
  }

  LaserLog
  finish ()
  {
    if (scans_.empty ())
      throw LogError (name_ + ": no FLASER or ROBOTLASER1 record (is this a CARMEN log?)");
    LaserLog log;
    log.path = name_;
    const bool corrected = hasCorrectedPoses (scans_);
    log.has_reference_poses = corrected;
    for (std::size_t j = 0; j < scans_.size (); ++j) {
      LaserScanRecord record = scans_[j].record;
      record.has_pose = corrected;
      if (j > 0) {
        if (corrected && scans_[j].last_odom_before) {
          record.odometry_step = scans_[j - 1].record.pose.inverse () * *scans_[j].last_odom_before;
          record.has_odometry_step = true;
        }
        else if (!corrected) {
          record.odometry_step = scans_[j - 1].odometry_fields.inverse () * scans_[j].odometry_fields;
          record.has_odometry_step = true;
        }
      }
      log.has_odometry = log.has_odometry || record.has_odometry_step;
      log.scans.push_back (std::move (record));
    }
    return log;
  }

private:
  [[noreturn]] void
  fail (const std::string& what) const
  {
    throw LogError (name_ + ":" + std::to_string (line_number_) + ": " + what);
  }

  double
  number (LineCursor& cursor, const char* record, const char* field)
  {
    double value = 0.0;
    if (!cursor.nextNumber (value))
      fail (std::string (record) + " record: " + field + " is missing or not a finite number");
    return value;
  }

  Rigid2d
  pose (LineCursor& cursor, const char* record, const char* field)
  {
    const double x = number (cursor, record, field);
    const double y = number (cursor, record, field);
    const double theta = number (cursor, record, field);
    if (std::max (std::abs (x), std::abs (y)) > kMaxCoordinate)
      fail (std::string (record) + " record: " + field + " lies beyond 1e18 m");
    return makeRigid2d (x, y, theta);
  }

  /** The end of a laser record after its timestamp: the host name and the logger's
   *  timestamp (both absent in some converted logs), then nothing. A number where the
   *  host should be, or a field after them, means the record holds more readings than
   *  its count says: they were read as its pose and timestamp. */
  void
  recordEnd (LineCursor& cursor, const char* record, int count)
  {
    std::string host;
    if (!cursor.nextWord (host))
      return;
    const std::string more = std::string (record) + " record: more fields than its " + std::to_string (count) +
                             " readings, pose, odometry and timestamp";
    if (parseDecimal (host))
      fail (more + " (the host name is a number: does the record hold more readings than its count says?)");
    number (cursor, record, "the logger timestamp");
    std::string extra;
    if (cursor.nextWord (extra))
      fail (more + ", host name and logger timestamp: '" + extra + "'");
  }

  int
  readingCount (LineCursor& cursor, const char* record)
  {
    const double n = number (cursor, record, "the number of readings");
    if (n < 2 || n > 100000 || n != std::floor (n))
      fail (std::string (record) + " record: the number of readings must be an integer in [2, 100000], not " +
            std::to_string (n));
    return static_cast<int> (n);
  }

  void
  parseOdom (LineCursor& cursor)
  {
    pending_odom_ = pose (cursor, "ODOM", "the pose x y theta");
    if (!scans_.empty () && !scans_.back ().first_odom_after)
      scans_.back ().first_odom_after = pending_odom_;
  }

  /** Adds a laser record's scan. Its valid readings lie in [min_range, max_range] of the
   *  options and short of \a no_return_from, the record's own maximum range (+inf when
   *  it has none): a sensor writes its maximum range for a beam without a return. */
  void
  addScan (const SensorInfo& sensor, const std::vector<double>& ranges, double no_return_from, const Rigid2d& pose,
           const Rigid2d& odometry_fields, double stamp)
  {
    RawScan scan;
    scan.record.sensor = sensor;
    scan.record.points.resize (2, static_cast<Eigen::Index> (ranges.size ()));
    Eigen::Index n = 0;
    for (std::size_t i = 0; i < ranges.size (); ++i) {
      const double r = ranges[i];
      if (!(r >= options_.min_range && r <= options_.max_range && r < no_return_from))
        continue;
      const double angle = sensor.angle_min + static_cast<double> (i) * sensor.angle_increment;
      scan.record.points.col (n++) << r * std::cos (angle), r * std::sin (angle);
      scan.record.beams.push_back (static_cast<int> (i));
    }
    scan.record.points.conservativeResize (2, n);
    scan.record.pose = pose;
    scan.record.stamp = stamp;
    scan.odometry_fields = odometry_fields;
    scan.last_odom_before = pending_odom_;
    pending_odom_.reset ();
    scans_.push_back (std::move (scan));
  }

  // FLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
  void
  parseFlaser (LineCursor& cursor)
  {
    const int n = readingCount (cursor, "FLASER");
    std::vector<double> ranges (n);
    for (auto& r : ranges)
      r = number (cursor, "FLASER", "a range reading");
    SensorInfo sensor;
    sensor.beam_count = n;
    sensor.angle_min = options_.angle_min;
    sensor.angle_increment = options_.field_of_view / (n - 1);
    sensor.range_max = options_.max_range;
    const Rigid2d laser_pose = pose (cursor, "FLASER", "the pose x y theta");
    const Rigid2d odometry_fields = pose (cursor, "FLASER", "the odometry x y theta");
    const double stamp = number (cursor, "FLASER", "the timestamp");
    recordEnd (cursor, "FLASER", n);
    addScan (sensor, ranges, std::numeric_limits<double>::infinity (), laser_pose, odometry_fields, stamp);
  }

  // ROBOTLASER1 laser_type start_angle fov resolution max_range accuracy remission_mode
  //   n r1..rn m e1..em laser_x laser_y laser_theta robot_x robot_y robot_theta
  //   tv rv forward_safety side_safety turn_axis timestamp host logger_timestamp
  void
  parseRobotLaser (LineCursor& cursor)
  {
    const char* record = "ROBOTLASER1";
    number (cursor, record, "the laser type");
    SensorInfo sensor;
    sensor.angle_min = number (cursor, record, "the start angle");
    number (cursor, record, "the field of view");
    sensor.angle_increment = number (cursor, record, "the angular resolution");
    const double logged_max = number (cursor, record, "the maximum range");
    number (cursor, record, "the accuracy");
    number (cursor, record, "the remission mode");
    const int n = readingCount (cursor, record);
    constexpr double kOneTurn = 2.0 * 3.14159265358979323846 * (1.0 + 1e-9);
    if (!(sensor.angle_increment > 0.0))
      fail ("ROBOTLASER1 record: the angular resolution must be positive");
    if (!(sensor.angle_increment * (n - 1) <= kOneTurn) || !(std::abs (sensor.angle_min) <= kOneTurn))
      fail ("ROBOTLASER1 record: " + std::to_string (n) + " beams " + formatGeneral (sensor.angle_increment, 6) +
            " rad apart from the start angle " + formatGeneral (sensor.angle_min, 6) +
            " rad: the beams must span at most one turn from a start within one turn");
    std::vector<double> ranges (n);
    for (auto& r : ranges)
      r = number (cursor, record, "a range reading");
    const double remissions = number (cursor, record, "the number of remissions");
    if (remissions < 0 || remissions > 100000 || remissions != std::floor (remissions))
      fail ("ROBOTLASER1 record: the number of remissions must be a non-negative integer");
    for (int i = 0; i < static_cast<int> (remissions); ++i)
      number (cursor, record, "a remission value");
    sensor.beam_count = n;
    // Its own maximum range marks beams without a return; a missing one (0) marks none.
    const double no_return_from = logged_max > 0.0 ? logged_max : std::numeric_limits<double>::infinity ();
    sensor.range_max = std::min (options_.max_range, no_return_from);
    const Rigid2d laser_pose = pose (cursor, record, "the laser pose x y theta");
    const Rigid2d robot_pose = pose (cursor, record, "the robot pose x y theta");
    for (int i = 0; i < 5; ++i)
      number (cursor, record, "a velocity or safety field");
    const double stamp = number (cursor, record, "the timestamp");
    recordEnd (cursor, record, n);
    addScan (sensor, ranges, no_return_from, laser_pose, robot_pose, stamp);
  }

  std::string name_;
  CarmenReadOptions options_;
  std::size_t line_number_ = 0;
  std::optional<Rigid2d> pending_odom_;
  std::vector<RawScan> scans_;
};

bool
isGzipFile (const std::string& path)
{
  std::ifstream file (path, std::ios::binary);
  unsigned char magic[2] = {0, 0};
  file.read (reinterpret_cast<char*> (magic), 2);
  return file.gcount () == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
}

void
checkOptions (const CarmenReadOptions& options, const std::string& name)
{
  if (!(options.min_range >= 0.0) || !(options.max_range > options.min_range))
    throw LogError (name + ": the valid range interval [min_range, max_range] must satisfy 0 <= min < max");
  if (!(options.field_of_view > 0.0) || !std::isfinite (options.angle_min))
    throw LogError (name + ": the field of view must be positive and the start angle finite");
}

}  // namespace

LaserLog
readCarmenLog (std::istream& in, const std::string& name, const CarmenReadOptions& options)
{
  checkOptions (options, name);
  CarmenParser parser (name, options);
  std::string line;
  std::size_t line_number = 0;
  try {
    while (std::getline (in, line))
      if (!parser.parseLine (line, ++line_number))
        break;
  }
  catch (const boost::iostreams::gzip_error& error) {
    throw LogError (name + ":" + std::to_string (line_number + 1) + ": corrupt gzip data (" + error.what () + ")");
  }
  if (in.bad ())
    throw LogError (name + ":" + std::to_string (line_number + 1) +
                    ": read error (a truncated or corrupt gzip file?)");
  return parser.finish ();
}

LaserLog
readCarmenLog (const std::string& path, const CarmenReadOptions& options)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw LogError (path + ": cannot read the CARMEN log: " + problem);
  std::ifstream file (path, std::ios::binary);
  if (!isGzipFile (path))
    return readCarmenLog (file, path, options);
  boost::iostreams::filtering_istream in;
  in.push (boost::iostreams::gzip_decompressor ());
  in.push (file);
  return readCarmenLog (in, path, options);
}

}  // namespace pcl_crf
