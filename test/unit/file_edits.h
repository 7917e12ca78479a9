#pragma once
// Test helper: edits a written file in place, as a corrupt or hand-made file would read.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pcl_crf {
namespace test {

/** \brief Replaces the first \a from in \a file by \a to (a test failure when absent). */
inline void
replaceInFile (const std::filesystem::path& file, const std::string& from, const std::string& to)
{
  std::ifstream in (file);
  std::stringstream buffer;
  buffer << in.rdbuf ();
  std::string text = buffer.str ();
  const auto at = text.find (from);
  ASSERT_NE (at, std::string::npos) << from << " not in " << file;
  text.replace (at, from.size (), to);
  std::ofstream (file) << text;
}

}  // namespace test
}  // namespace pcl_crf
