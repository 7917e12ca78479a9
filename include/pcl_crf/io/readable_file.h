#pragma once

#include <string>

namespace pcl_crf {

/** \brief Why \a path cannot be read as a file, or "" when it can: it does not exist, is
 *  a directory (which std::ifstream opens, and whose reads then fail unexplained), or
 *  cannot be opened (the system's reason).
 *  \code
 *  const std::string problem = pcl_crf::unreadableFileProblem (path);
 *  if (!problem.empty ()) throw std::runtime_error (path + ": " + problem);
 *  \endcode */
std::string
unreadableFileProblem (const std::string& path);

}  // namespace pcl_crf
