#include <pcl_crf/evaluation/evaluate.h>

#include <chrono>

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

}  // namespace pcl_crf
