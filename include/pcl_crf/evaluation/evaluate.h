#pragma once

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/metrics/pair_scores.h>
#include <pcl_crf/metrics/summary.h>

#include <functional>
#include <memory>
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

/** \brief Where a leave-one-out evaluation is: fold (1-based) of folds, the held-out
 *  pair, how many pairs the method is trained on, and whether the fold is starting
 *  (before training) or finished (the pair scored). */
struct FoldStatus
{
  std::size_t fold = 0;
  std::size_t folds = 0;
  std::string held_out;
  std::size_t training_pairs = 0;
  bool finished = false;
};

/** \brief Called at the start and at the end of every leave-one-out fold. */
using FoldProgress = std::function<void (const FoldStatus&)>;

/** \brief Builds a fresh, untrained method (one per fold). */
using MethodMaker = std::function<std::unique_ptr<EvaluationMethod> ()>;

/** \brief Leave-one-out (the joint paper's protocol): for each of the first
 *  \a held_out pairs k, a fresh method is trained on every other pair of \a pairs,
 *  then predicts and scores pair k. A method that learns nothing is built once and
 *  predicts each held-out pair (training_pairs = 0 in the progress).
 *
 *  \code
 *  const auto pairs = pcl_crf::loadDataset ("data/default/train");
 *  const pcl_crf::MethodEvaluation evaluation = pcl_crf::evaluateLeaveOneOut (
 *      [] { return pcl_crf::createEvaluationMethod ("crf-m"); }, pairs);
 *  \endcode
 *  \param[in] make_method builds the method
 *  \param[in] pairs every pair (training and held out)
 *  \param[in] held_out how many pairs (the first ones) are held out in turn; 0: all
 *  \param[in] options scoring options
 *  \param[in] progress called at the start and end of every fold
 *  \return the held-out pairs' predictions and scores, summarised over them
 *  \throws std::invalid_argument when \a pairs has fewer than 2 pairs
 */
MethodEvaluation
evaluateLeaveOneOut (const MethodMaker& make_method, const std::vector<ScanPair>& pairs, std::size_t held_out = 0,
                     const ScoreOptions& options = {}, const FoldProgress& progress = {});

}  // namespace pcl_crf
