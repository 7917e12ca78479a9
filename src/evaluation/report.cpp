#include <pcl_crf/evaluation/report.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace pcl_crf {
namespace {

std::string
formatNumber (double value)
{
  if (std::isnan (value))
    return "";
  char buffer[64];
  const double magnitude = std::abs (value);
  if (magnitude != 0.0 && (magnitude < 1e-3 || magnitude >= 1e5))
    std::snprintf (buffer, sizeof (buffer), "%.3e", value);
  else
    std::snprintf (buffer, sizeof (buffer), "%.4f", value);
  return buffer;
}

std::string
jsonNumber (double value)
{
  if (!std::isfinite (value))
    return "null";
  char buffer[64];
  std::snprintf (buffer, sizeof (buffer), "%.9g", value);
  return buffer;
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

}  // namespace

void
printEvaluationTable (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
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
writeEvaluationCsv (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
{
  out << "method,metric,unit,mean,std,count\n";
  for (const auto& evaluation : evaluations)
    for (const auto& row : evaluation.summary)
      out << evaluation.method << "," << row.name << "," << row.unit << "," << jsonNumber (row.mean)
          << "," << jsonNumber (row.stddev) << "," << row.count << "\n";
}

void
writeEvaluationJson (std::ostream& out, const std::vector<MethodEvaluation>& evaluations)
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

}  // namespace pcl_crf
