# Prints a Markdown table of the headline scores in a pcl_crf_eval CSV (--format csv):
# association accuracy, motion-detection accuracy, V, ego and moving-object error.
# Variables (awk -v):
#   header=1   print the header and separator rows first
#   label=TEXT add a first column holding TEXT on every row (e.g. the condition)
BEGIN { FS = "," }
NR == 1 { next }
$2 == "association_accuracy" || $2 == "cluster_accuracy" || $2 == "v_measure" ||
$2 == "ego_translation_error" || $2 == "moving_translation_error" {
  if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
  value[$1, $2] = $4
}
END {
  first = label == "" ? "" : "| condition "
  if (header) {
    printf "%s| method | association accuracy | motion-detection accuracy | V | ego motion [m] | moving objects [m] |\n", first
    printf "%s|---|---|---|---|---|---|\n", label == "" ? "" : "|---"
  }
  for (k = 1; k <= n; ++k) {
    m = order[k]
    printf "%s| %s | %s | %s | %s | %s | %s |\n", label == "" ? "" : "| " label " ", m,
           fmt(value[m, "association_accuracy"]), fmt(value[m, "cluster_accuracy"]), fmt(value[m, "v_measure"]),
           fmt(value[m, "ego_translation_error"]), fmt(value[m, "moving_translation_error"])
  }
}
# "-" where the CSV has no value: a metric over no object (null; awk would print 0.000)
function fmt(v) { return v == "" || v == "null" || tolower (v) == "nan" ? "-" : sprintf("%.3f", v) }
