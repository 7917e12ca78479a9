#pragma once
// Small helpers shared by the pcl_crf_* tools.

#include <pcl/console/parse.h>
#include <pcl/console/print.h>

#include <cstring>
#include <exception>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pcl_crf {
namespace apps {

/** The arguments that are neither options nor values of options, in order.
 *  \a value_options lists the options that take a value ("--method", ...). */
inline std::vector<std::string>
positionalArguments (int argc, char** argv, const std::set<std::string>& value_options)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-' && std::strlen (argv[i]) > 1) {
      if (value_options.count (argv[i]))
        ++i;
      continue;
    }
    positional.emplace_back (argv[i]);
  }
  return positional;
}

/** Splits "a,b,c" into {"a", "b", "c"}, dropping empty parts. */
inline std::vector<std::string>
splitCommas (const std::string& text)
{
  std::vector<std::string> parts;
  std::stringstream in (text);
  std::string part;
  while (std::getline (in, part, ','))
    if (!part.empty ())
      parts.push_back (part);
  return parts;
}

/** A bare call or -h / --help: prints the usage and gives the exit code (1 for
 *  a bare call, 0 when help was asked for); otherwise -1, meaning "go on". */
inline int
helpExitCode (int argc, char** argv, void (*print_help) (const char*))
{
  if (argc >= 2 && !pcl::console::find_switch (argc, argv, "-h") &&
      !pcl::console::find_switch (argc, argv, "--help"))
    return -1;
  print_help (argv[0]);
  return argc < 2 ? 1 : 0;
}

/** Runs a tool's work and gives its exit code; an exception is printed as an
 *  error and gives 1. */
template <typename Work> int
exitCodeOf (Work&& work)
{
  try {
    return work ();
  }
  catch (const std::exception& error) {
    pcl::console::print_error ("%s\n", error.what ());
    return 1;
  }
}

}  // namespace apps
}  // namespace pcl_crf
