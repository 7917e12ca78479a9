#pragma once
// Runs a pcl_crf_* tool from the build tree (ctest sets PCL_CRF_APPS_DIR).

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pcl_crf {
namespace test {

struct ToolRun
{
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

/** The folder of the built tools, or "" when the tests run outside ctest. */
inline std::string
appsDir ()
{
  const char* dir = std::getenv ("PCL_CRF_APPS_DIR");
  return dir ? dir : "";
}

/** Runs "<apps dir>/<tool> <arguments>" through the shell. */
inline ToolRun
runTool (const std::string& tool, const std::string& arguments)
{
  ToolRun run;
  const std::string command = appsDir () + "/" + tool + " " + arguments + " 2>&1";
  FILE* pipe = popen (command.c_str (), "r");
  if (!pipe)
    return run;
  std::array<char, 4096> buffer;
  while (std::fgets (buffer.data (), buffer.size (), pipe))
    run.output += buffer.data ();
  const int status = pclose (pipe);
  run.exit_code = WIFEXITED (status) ? WEXITSTATUS (status) : -1;
  return run;
}

}  // namespace test
}  // namespace pcl_crf

#define PCL_CRF_SKIP_WITHOUT_APPS()                                                      \
  if (pcl_crf::test::appsDir ().empty ())                                                \
  GTEST_SKIP () << "PCL_CRF_APPS_DIR is not set (run through ctest)"
