#pragma once

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/metrics/summary.h>

#include <functional>
#include <string>
#include <vector>

namespace pcl_crf {

/** \brief A method's predictions and scores over a set of scan pairs. */
struct MethodEvaluation
{
  std::string method;
  std::vector<std::string> pair_names;
  std::vector<Prediction> predictions;
  std::vector<PairScores> scores;
  std::vector<MetricSummary> summary;
};

/** \brief Called after every pair: pairs done, pairs in all, the pair's name. */
using EvaluationProgress = std::function<void (std::size_t, std::size_t, const std::string&)>;

/** \brief Runs \a method on every pair, times each predict() call (wall clock,
 *  stored in Prediction::seconds and PairScores::seconds) and scores it.
 *  The method must already be trained if it learns.
 *  \throws std::invalid_argument when a prediction does not fit its pair.
 */
MethodEvaluation
evaluateMethod (EvaluationMethod& method, const std::vector<ScanPair>& pairs,
                const ScoreOptions& options = {}, const EvaluationProgress& progress = {});

}  // namespace pcl_crf
