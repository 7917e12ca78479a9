#include <pcl_crf/logs/read_laser_log.h>
#include <pcl_crf/io/readable_file.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace pcl_crf {

LaserLogFormat
detectLaserLogFormat (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw LogError (path + ": cannot read the log: " + problem);
  std::ifstream file (path, std::ios::binary);
  char magic[13] = {};
  file.read (magic, sizeof (magic));
  return std::string (magic, static_cast<std::size_t> (file.gcount ())) == "#ROSBAG V2.0\n" ? LaserLogFormat::Rosbag
                                                                                         : LaserLogFormat::Carmen;
}

LaserLog
readLaserLog (const std::string& path, const LaserLogReadOptions& options)
{
  return detectLaserLogFormat (path) == LaserLogFormat::Rosbag ? readRosbagLog (path, options.rosbag)
                                                               : readCarmenLog (path, options.carmen);
}

}  // namespace pcl_crf
