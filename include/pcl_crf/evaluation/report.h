#pragma once

#include <pcl_crf/evaluation/evaluate.h>

#include <ostream>
#include <vector>

namespace pcl_crf {

/** \brief A table in the papers' style: one row per metric, one column per
 *  method, each cell "mean ± std" (blank where the metric does not apply). */
void
printEvaluationTable (std::ostream& out, const std::vector<MethodEvaluation>& evaluations);

/** \brief CSV, one line per (method, metric): method,metric,unit,mean,std,count. */
void
writeEvaluationCsv (std::ostream& out, const std::vector<MethodEvaluation>& evaluations);

/** \brief JSON: {"methods": [{"method": ..., "pairs": N, "metrics": {name:
 *  {"mean", "std", "count", "unit"}}, "per_pair": [{"pair": ..., name: value}]}]};
 *  NaN is written as null. */
void
writeEvaluationJson (std::ostream& out, const std::vector<MethodEvaluation>& evaluations);

}  // namespace pcl_crf
