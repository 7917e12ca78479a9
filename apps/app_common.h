#pragma once
// Small helpers shared by the pcl_crf_* tools.

#include <cstring>
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

}  // namespace apps
}  // namespace pcl_crf
