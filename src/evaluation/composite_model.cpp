#include <pcl_crf/evaluation/composite_model.h>

#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace pcl_crf {
namespace {

constexpr const char* kMagic = "pcl_crf_composite_model";

std::string
partNames (const std::vector<std::string>& names)
{
  std::string text;
  for (const std::string& name : names)
    text += (text.empty () ? "" : " ") + name;
  return text;
}

/** Reads the file line by line; errors "<where>: line <n>: <problem>". */
class LineReader
{
public:
  LineReader (std::istream& is, std::string where) : is_ (is), where_ (std::move (where)) {}

  [[noreturn]] void
  fail (const std::string& what) const
  {
    throw std::runtime_error (where_ + ": line " + std::to_string (line_) + ": " + what);
  }

  /** The next line that is neither blank nor a '#' comment, trimmed; "" at the end of the file. */
  std::string
  meaningful ()
  {
    for (std::string line; next (line);)
      if (line = trim (line); !line.empty () && line[0] != '#')
        return line;
    ++line_;
    return "";
  }

  /** The next meaningful line, which must be exactly \a expected. */
  void
  expect (const std::string& expected, const std::string& problem)
  {
    const std::string line = meaningful ();
    if (line.empty ())
      fail ("unexpected end of file, missing '" + expected + "' (the file is truncated)");
    if (line != expected)
      fail (problem + ": expected '" + expected + "', found '" + line + "'");
  }

  /** The lines up to "end_part NAME", as a text whose line numbers are the file's. */
  std::string
  section (const std::string& name)
  {
    std::string text (static_cast<std::size_t> (line_), '\n'), line;
    const std::string end = "end_part " + name;
    while (next (line)) {
      if (trim (line) == end)
        return text;
      text += line + '\n';
    }
    fail ("unexpected end of file inside part '" + name + "', missing '" + end + "' (the file is truncated)");
  }

private:
  static std::string
  trim (const std::string& line)
  {
    const auto first = line.find_first_not_of (" \t\r");
    return first == std::string::npos ? "" : line.substr (first, line.find_last_not_of (" \t\r") - first + 1);
  }

  bool
  next (std::string& line)
  {
    if (!std::getline (is_, line))
      return false;
    ++line_;
    return true;
  }

  std::istream& is_;
  std::string where_;
  int line_ = 0;
};

}  // namespace

void
writeCompositeModel (std::ostream& os, const std::string& method, const std::vector<const EvaluationMethod*>& parts)
{
  std::vector<std::string> names;
  std::ostringstream body;
  for (const EvaluationMethod* part : parts) {
    names.push_back (part->name ());
    std::ostringstream text;
    part->writeModel (text);
    const std::string model = text.str ();
    body << "part " << part->name () << '\n'
         << model << (model.empty () || model.back () != '\n' ? "\n" : "") << "end_part " << part->name () << '\n';
  }
  os << kMagic << ' ' << kCompositeModelVersion << '\n'
     << "# the model of a method made of parts: each part's own model between 'part NAME' and 'end_part NAME'\n"
     << "method " << method << '\n'
     << "parts " << partNames (names) << '\n'
     << body.str ();
}

void
readCompositeModel (std::istream& is, const std::string& where, const std::string& method,
                    const std::vector<EvaluationMethod*>& parts)
{
  LineReader reader (is, where);
  const std::string header = reader.meaningful ();
  std::istringstream words (header);
  std::string magic, version;
  words >> magic >> version;
  if (magic != kMagic)
    reader.fail ("not a composite model (expected the header '" + std::string (kMagic) + " " +
                 std::to_string (kCompositeModelVersion) + "'; a model of '" + method + "' holds all its parts)");
  if (version != std::to_string (kCompositeModelVersion))
    reader.fail ("unsupported composite model version '" + version + "', expected " +
                 std::to_string (kCompositeModelVersion));
  std::string trailing;
  if (words >> trailing)
    reader.fail ("unexpected text '" + trailing + "' after the version");
  reader.expect ("method " + method, "a model of another method");
  std::vector<std::string> names;
  for (const EvaluationMethod* part : parts)
    names.push_back (part->name ());
  reader.expect ("parts " + partNames (names), "other parts than " + method + "'s");
  for (EvaluationMethod* part : parts) {
    reader.expect ("part " + part->name (), "missing or misplaced part");
    std::istringstream text (reader.section (part->name ()));
    part->readModel (text, where + " (part " + part->name () + ")");
  }
  const std::string extra = reader.meaningful ();
  if (!extra.empty ())
    reader.fail ("unexpected '" + extra + "' after the last part");
}

}  // namespace pcl_crf
