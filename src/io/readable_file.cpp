#include <pcl_crf/io/readable_file.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace pcl_crf {

std::string
unreadableFileProblem (const std::string& path)
{
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status (path, error);
  if (status.type () == std::filesystem::file_type::not_found)
    return "no such file";
  if (status.type () == std::filesystem::file_type::directory)
    return "is a directory, not a file";
  std::ifstream file (path, std::ios::binary);
  if (!file)
    return std::string ("cannot open (") + std::strerror (errno) + ")";
  return "";
}

}  // namespace pcl_crf
