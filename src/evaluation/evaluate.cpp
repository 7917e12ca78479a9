#include <pcl_crf/evaluation/evaluate.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace pcl_crf {

MethodEvaluation
evaluateMethod (EvaluationMethod& method, const std::vector<ScanPair>& pairs,
                const ScoreOptions& options, const EvaluationProgress& progress)
{
  MethodEvaluation evaluation;
  evaluation.method = method.name ();
  for (std::size_t k = 0; k < pairs.size (); ++k) {
    const auto start = std::chrono::steady_clock::now ();
    Prediction prediction = method.predict (pairs[k]);
    prediction.seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    PairScores scores = scorePair (pairs[k], prediction, options);
    scores.seconds = prediction.seconds;
    evaluation.pair_names.push_back (pairs[k].name);
    evaluation.predictions.push_back (std::move (prediction));
    evaluation.scores.push_back (scores);
    if (progress)
      progress (k + 1, pairs.size (), pairs[k].name);
  }
  evaluation.summary = summarize (evaluation.scores);
  return evaluation;
}

MethodEvaluation
evaluateLeaveOneOut (const MethodMaker& make_method, const std::vector<ScanPair>& pairs, std::size_t held_out,
                     const ScoreOptions& options, const FoldProgress& progress)
{
  if (pairs.size () < 2)
    throw std::invalid_argument ("leave-one-out needs at least 2 pairs (one to hold out, one to train on), got " +
                                 std::to_string (pairs.size ()));
  const std::size_t folds = held_out == 0 ? pairs.size () : std::min (held_out, pairs.size ());
  std::unique_ptr<EvaluationMethod> method = make_method ();
  const bool learned = method->isLearned ();
  MethodEvaluation evaluation;
  evaluation.method = method->name ();
  for (std::size_t k = 0; k < folds; ++k) {
    FoldStatus status{k + 1, folds, pairs[k].name, learned ? pairs.size () - 1 : 0, false};
    if (progress)
      progress (status);
    if (learned) {
      std::vector<ScanPair> training;
      training.reserve (pairs.size () - 1);
      for (std::size_t j = 0; j < pairs.size (); ++j)
        if (j != k)
          training.push_back (pairs[j]);
      if (k > 0)
        method = make_method ();
      method->train (training);
    }
    MethodEvaluation fold = evaluateMethod (*method, {pairs[k]}, options);
    evaluation.pair_names.push_back (fold.pair_names.front ());
    evaluation.predictions.push_back (std::move (fold.predictions.front ()));
    evaluation.scores.push_back (fold.scores.front ());
    status.finished = true;
    if (progress)
      progress (status);
  }
  evaluation.summary = summarize (evaluation.scores);
  return evaluation;
}

}  // namespace pcl_crf
