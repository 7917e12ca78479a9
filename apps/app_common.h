#pragma once
// Small helpers shared by the pcl_crf_* tools.

#include <pcl_crf/core/decimal_text.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pcl_crf {
namespace apps {

/** \brief Whether \a arg is written like an option ("-q", "--method"), not a path or value. */
inline bool
looksLikeOption (const std::string& arg)
{
  return arg.size () > 1 && arg[0] == '-';
}

/** The arguments that are neither options nor values of options, in order.
 *  \a value_options lists the options that take a value ("--method", ...). */
inline std::vector<std::string>
positionalArguments (int argc, char** argv, const std::set<std::string>& value_options)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    if (looksLikeOption (argv[i])) {
      if (value_options.count (argv[i]))
        ++i;
      continue;
    }
    positional.emplace_back (argv[i]);
  }
  return positional;
}

/** \brief Checks a tool's command line: every argument written like an option must be one
 *  of \a value_options, followed by its value (an argument that is not itself one of the
 *  tool's options, so "--yaw-rate -0.1" works), or one of \a switches (-h and --help
 *  always are), each at most once. PCL's parse_argument silently skips an unknown option or a
 *  missing value, and reads only the first of a repeated option.
 *  \return false after a print_error naming the option and pointing to -h. */
inline bool
checkOptions (int argc, char** argv, const std::set<std::string>& value_options,
              std::set<std::string> switches)
{
  switches.insert ({"-h", "--help"});
  auto known = [&] (const std::string& arg) { return value_options.count (arg) > 0 || switches.count (arg) > 0; };
  std::set<std::string> given;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (known (arg) && !given.insert (arg).second) {  // parse_argument would read the first one only
      pcl::console::print_error ("Option %s is given twice (see %s -h).\n", arg.c_str (), argv[0]);
      return false;
    }
    if (value_options.count (arg)) {
      if (i + 1 >= argc || known (argv[i + 1])) {
        pcl::console::print_error ("Option %s needs a value (see %s -h).\n", arg.c_str (), argv[0]);
        return false;
      }
      if (argv[i + 1][0] == '\0') {  // "$UNSET_VARIABLE": every option would silently do nothing
        pcl::console::print_error ("Option %s is given an empty value (see %s -h).\n", arg.c_str (), argv[0]);
        return false;
      }
      ++i;
    }
    else if (looksLikeOption (arg) && !switches.count (arg)) {
      pcl::console::print_error ("Unknown option '%s' (see %s -h for the options).\n", arg.c_str (), argv[0]);
      return false;
    }
  }
  return true;
}

/** Parses "--name VALUE" as a number when present. Returns false (after a
 *  print_error naming the option) when the value is missing or not a number. */
inline bool
numberOption (int argc, char** argv, const char* name, double& value)
{
  const int index = pcl::console::find_argument (argc, argv, name);
  if (index < 0)
    return true;
  if (index + 1 >= argc) {
    pcl::console::print_error ("%s needs a value (see -h).\n", name);
    return false;
  }
  const std::optional<double> parsed = pcl_crf::parseDecimal (argv[index + 1]);
  if (!parsed) {
    pcl::console::print_error ("%s needs a decimal number, not '%s'.\n", name, argv[index + 1]);
    return false;
  }
  value = *parsed;
  return true;
}

/** Same as numberOption for a whole number >= \a minimum. */
inline bool
countOption (int argc, char** argv, const char* name, long& value, long minimum)
{
  double parsed = static_cast<double> (value);
  if (!numberOption (argc, argv, name, parsed))
    return false;
  if (parsed != std::floor (parsed) || parsed < static_cast<double> (minimum) || parsed > 1e12) {
    pcl::console::print_error ("%s needs a whole number >= %ld, not '%g'.\n", name, minimum, parsed);
    return false;
  }
  value = static_cast<long> (parsed);
  return true;
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
