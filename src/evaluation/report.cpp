#include <pcl_crf/evaluation/report.h>
#include <pcl_crf/core/decimal_text.h>

#include <cmath>
#include <iomanip>
#include <locale>
#include <sstream>

namespace pcl_crf {
namespace {

std::string
formatNumber (double value)
{
  if (std::isnan (value))
    return "";
  const double magnitude = std::abs (value);
  if (magnitude != 0.0 && (magnitude < 1e-3 || magnitude >= 1e5))
    return formatScientific (value, 3);
  return formatFixed (value, 4);
}

std::string
jsonNumber (double value)
{
  if (!std::isfinite (value))
    return "null";
  return formatGeneral (value, 9);
}

std::string
jsonString (const std::string& text)
{
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\')
      quoted += '\\';
    if (static_cast<unsigned char> (c) < 0x20)
      continue;
    quoted += c;
  }
  return quoted + "\"";
}

std::string
cell (const MetricSummary& row)
{
  if (row.count == 0)
    return "-";
  return formatNumber (row.mean) + " ± " + formatNumber (row.stddev);
}

void
printTable (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  if (evaluations.empty ())
    return;
  const std::size_t name_width = 44, cell_width = 26;
  out << std::left << std::setw (name_width) << "metric [unit]";
  for (const auto& evaluation : evaluations)
    out << std::setw (cell_width) << evaluation.method;
  out << "\n" << std::string (name_width + cell_width * evaluations.size (), '-') << "\n";
  const auto& rows = evaluations.front ().summary;
  for (std::size_t r = 0; r < rows.size (); ++r) {
    bool any = false;
    for (const auto& evaluation : evaluations)
      any = any || evaluation.summary[r].count > 0;
    if (!any)
      continue;
    out << std::setw (name_width) << (rows[r].name + " [" + rows[r].unit + "]");
    for (const auto& evaluation : evaluations) {
      // "±" is two bytes in UTF-8: pad by hand so columns stay aligned.
      const std::string text = cell (evaluation.summary[r]);
      const std::size_t shown = text.size () - (text.find ("±") != std::string::npos ? 1 : 0);
      out << text << std::string (shown < cell_width ? cell_width - shown : 1, ' ');
    }
    out << "\n";
  }
  out << "pairs:";
  for (const auto& evaluation : evaluations)
    out << " " << evaluation.method << "=" << evaluation.scores.size ();
  out << "\n";
}

void
printCsv (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  out << "method,metric,unit,mean,std,count\n";
  for (const auto& evaluation : evaluations)
    for (const auto& row : evaluation.summary)
      out << evaluation.method << "," << row.name << "," << row.unit << "," << jsonNumber (row.mean)
          << "," << jsonNumber (row.stddev) << "," << row.count << "\n";
}

void
printJson (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  out << "{\"methods\": [";
  for (std::size_t m = 0; m < evaluations.size (); ++m) {
    const auto& evaluation = evaluations[m];
    out << (m ? ", " : "") << "{\"method\": " << jsonString (evaluation.method)
        << ", \"pairs\": " << evaluation.scores.size () << ", \"metrics\": {";
    for (std::size_t r = 0; r < evaluation.summary.size (); ++r) {
      const auto& row = evaluation.summary[r];
      out << (r ? ", " : "") << jsonString (row.name) << ": {\"mean\": " << jsonNumber (row.mean)
          << ", \"std\": " << jsonNumber (row.stddev) << ", \"count\": " << row.count
          << ", \"unit\": " << jsonString (row.unit) << "}";
    }
    out << "}, \"per_pair\": [";
    for (std::size_t k = 0; k < evaluation.scores.size (); ++k) {
      out << (k ? ", " : "") << "{\"pair\": " << jsonString (evaluation.pair_names[k]);
      for (const auto& field : metricFields ())
        out << ", " << jsonString (field.name) << ": " << jsonNumber (evaluation.scores[k].*field.value);
      out << "}";
    }
    out << "]}";
  }
  out << "]}\n";
}

/** Writes through \a write into a buffer in the classic locale, then to \a out: numbers
 *  and counts without a host program's decimal comma or digit grouping ("1.234" for
 *  1234 under a German std::locale::global). */
template <typename Write>
void
writeInClassicLocale (std::ostream& out, Write write)
{
  std::ostringstream text;
  text.imbue (std::locale::classic ());
  write (text);
  out << text.str ();
}

}  // namespace

void
printEvaluationTable (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  writeInClassicLocale (out, [&evaluations] (std::ostream& text) { printTable (text, evaluations); });
}

void
writeEvaluationCsv (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  writeInClassicLocale (out, [&evaluations] (std::ostream& text) { printCsv (text, evaluations); });
}

void
writeEvaluationJson (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  writeInClassicLocale (out, [&evaluations] (std::ostream& text) { printJson (text, evaluations); });
}

}  // namespace pcl_crf
