#include <pcl_crf/core/repeated_points.h>
#include <pcl_crf/matching/scan_matching.h>
#include <pcl_crf/matching/lifted_matches.h>
#include <pcl_crf/matching/matching_chain.h>
#include <pcl_crf/matching/robust_rigid_fit.h>

#include <algorithm>
#include <stdexcept>

namespace pcl_crf {
namespace matching {

namespace {

std::vector<int>
labelsToMatches (const Candidates& candidates, const std::vector<int>& labels)
{
  std::vector<int> matches (labels.size (), kNoMatch);
  for (int i = 0; i < candidates.size (); ++i)
    if (labels[i] < candidates.count (i))
      matches[i] = candidates.target (i, labels[i]);
  return matches;
}

/** p(y_i = MAP label) of every node. */
Eigen::VectorXd
mapProbabilities (const crf::MarginalResult& marginals, const std::vector<int>& labels)
{
  Eigen::VectorXd p (static_cast<Eigen::Index> (labels.size ()));
  for (std::size_t i = 0; i < labels.size (); ++i)
    p (i) = marginals.node_marginals[i] (labels[i]);
  return p;
}

/** 1 − p(y_i = outlier) of every node (the outlier state is the last). */
Eigen::VectorXd
inlierProbabilities (const crf::MarginalResult& marginals)
{
  Eigen::VectorXd p (static_cast<Eigen::Index> (marginals.node_marginals.size ()));
  for (std::size_t i = 0; i < marginals.node_marginals.size (); ++i)
    p (i) = 1.0 - marginals.node_marginals[i] (marginals.node_marginals[i].size () - 1);
  return p;
}

void
checkModel (const CrfMatchingModel& model)
{
  if (!model.isTrained ())
    throw std::invalid_argument ("[pcl_crf::matching::matchScans] the model is not trained (train or load one first)");
  validateParameters (model.parameters);
}

/** The model's, the source scan's and the guess's checks, before any thinning (so
 *  that a NaN is named as such, not as a bearing). */
void
checkInputs (const CrfMatchingModel& model, const Eigen::Matrix2Xd& source, const MotionGuess& guess)
{
  checkModel (model);
  const std::string points_problem = scanPointsProblem (source, "source");
  if (!points_problem.empty ())
    throw std::invalid_argument ("[pcl_crf::matching::matchScans] " + points_problem);
  const std::string problem = motionGuessProblem (guess);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::matching::matchScans] " + problem);
}

/** The candidates and marginals of a full source point: those of its anchor, as full
 *  target indices, the MAP candidate replaced by the lifted \a match (a candidate
 *  that then repeats it gives it its probability and is dropped). */
void
appendLiftedStates (const MatchResult& coarse, const ThinnedScan& target, int anchor, int match,
                    Candidates& candidates, std::vector<Eigen::VectorXd>& marginals)
{
  const int count = coarse.candidates.count (anchor);
  const Eigen::VectorXd& p = coarse.marginals[anchor];
  const int map_state = match == kNoMatch ? -1 : coarse.candidates.find (anchor, coarse.matches[anchor]);
  std::vector<double> probabilities;
  int map_position = -1;
  double merged = 0.0;
  for (int c = 0; c < count; ++c) {
    const int full = c == map_state ? match : target.kept[coarse.candidates.target (anchor, c)];
    if (c != map_state && full == match) {
      merged += p (c);
      continue;
    }
    if (c == map_state)
      map_position = static_cast<int> (probabilities.size ());
    candidates.targets.push_back (full);
    probabilities.push_back (p (c));
  }
  if (map_position >= 0)
    probabilities[map_position] += merged;
  probabilities.push_back (p (count));  // the outlier state
  candidates.offsets.push_back (static_cast<int> (candidates.targets.size ()));
  marginals.push_back (Eigen::Map<const Eigen::VectorXd> (probabilities.data (),
                                                          static_cast<Eigen::Index> (probabilities.size ())));
}

/** liftMatches () onto the first copies of the target points alone (a later copy inside
 *  a kept point's span would stand for the point it repeats there), as full indices. */
std::vector<int>
liftToFirstCopies (const Eigen::Matrix2Xd& source, const MatchingTarget& target, const ThinnedPair& thinned,
                   const std::vector<int>& coarse_matches, const std::vector<int>& groups, const Rigid2d& motion)
{
  if (!repeatsAPoint (target.first_copy))
    return liftMatches (source, target.points, thinned, coarse_matches, groups, {motion});
  const std::vector<int> distinct = firstCopies (target.first_copy);
  const std::vector<int> column = firstCopyColumns (target.first_copy);  // a first copy's column in distinct
  ThinnedPair on_distinct = thinned;
  for (int& k : on_distinct.target.kept)
    k = column[static_cast<std::size_t> (k)];
  std::vector<int> matches =
      liftMatches (source, target.points (Eigen::all, distinct), on_distinct, coarse_matches, groups, {motion});
  for (int& j : matches)
    if (j != kNoMatch)
      j = distinct[static_cast<std::size_t> (j)];
  return matches;
}

/** A result on the thinned scans lifted to the full ones (see matchScans). */
MatchResult
liftMatchResult (const MatchResult& coarse, const Eigen::Matrix2Xd& source, const MatchingTarget& target,
                 const ThinnedPair& thinned)
{
  std::vector<int> groups (coarse.matches.size (), -1);
  for (std::size_t k = 0; k < groups.size (); ++k)
    groups[k] = coarse.matches[k] == kNoMatch ? -1 : 0;
  MatchResult result;
  result.matches = liftToFirstCopies (source, target, thinned, coarse.matches, groups, coarse.T_target_source);
  result.map_probability.resize (source.cols ());
  for (int i = 0; i < static_cast<int> (source.cols ()); ++i) {
    const int anchor = thinned.anchors[i];
    appendLiftedStates (coarse, target.thinned, anchor, result.matches[i], result.candidates, result.marginals);
    result.map_probability (i) = coarse.map_probability (anchor);
  }
  result.T_target_source = coarse.T_target_source;
  result.passes = coarse.passes;
  result.inlier_count = static_cast<int> (
      std::count_if (result.matches.begin (), result.matches.end (), [] (int j) { return j != kNoMatch; }));
  return result;
}

/** \a target's thinned scan over its first copies (firstOfEqualPoints), indexing the full scan. */
ThinnedScan
thinFirstCopies (const Eigen::Matrix2Xd& target, const std::vector<int>& first_copy, double model_spacing)
{
  if (!repeatsAPoint (first_copy))
    return thinToSpacing (target, model_spacing);
  const std::vector<int> distinct = firstCopies (first_copy);
  ThinnedScan thinned = thinToSpacing (target (Eigen::all, distinct), model_spacing);
  for (int& k : thinned.kept)
    k = distinct[static_cast<std::size_t> (k)];
  return thinned;
}

/** \a coarse, a result over the kept target points, with its target indices those of the
 *  full scan (nothing was thinned but copies). */
MatchResult
indexFullTarget (MatchResult coarse, const std::vector<int>& kept)
{
  for (int& j : coarse.matches)
    if (j != kNoMatch)
      j = kept[static_cast<std::size_t> (j)];
  for (int& j : coarse.candidates.targets)
    j = kept[static_cast<std::size_t> (j)];
  return coarse;
}

/** \a distinct, the result over the first copies of the source points, given to every
 *  point: a copy takes its first copy's match, states, marginals and probability. */
MatchResult
liftToSourceCopies (const MatchResult& distinct, const std::vector<int>& source_first)
{
  const std::vector<int> node_of = firstCopyColumns (source_first);  // a point's first copy's node in distinct
  MatchResult result;
  result.map_probability.resize (static_cast<Eigen::Index> (source_first.size ()));
  for (std::size_t i = 0; i < source_first.size (); ++i) {
    const int node = node_of[i];
    result.matches.push_back (distinct.matches[node]);
    const auto first = distinct.candidates.targets.begin () + distinct.candidates.offsets[node];
    result.candidates.targets.insert (result.candidates.targets.end (), first,
                                      first + distinct.candidates.count (node));
    result.candidates.offsets.push_back (static_cast<int> (result.candidates.targets.size ()));
    result.marginals.push_back (distinct.marginals[node]);
    result.map_probability (static_cast<Eigen::Index> (i)) = distinct.map_probability (node);
  }
  result.T_target_source = distinct.T_target_source;
  result.passes = distinct.passes;
  result.inlier_count = static_cast<int> (
      std::count_if (result.matches.begin (), result.matches.end (), [] (int j) { return j != kNoMatch; }));
  return result;
}

}  // namespace

PassResult
runPass (const ScanShape& source, const PreparedTarget& target, const MotionGuess& guess, const Rigid2d& T_current,
         const StageModel& stage, const MatchingParameters& parameters, const ShapeNeighbours* earlier)
{
  PassResult pass;
  pass.geometry = preparePass (source, target, guess.T_target_source, T_current,
                               limitToInterval (parameters, guess.interval).candidates, earlier);
  pass.scores = scorePass (stage, source, target.scan, pass.geometry);
  crf::PackedChainPotentials chain;
  matchingChainPotentials (source, target.scan, pass.geometry, pass.scores, stage.crf_weights,
                           parameters.residual_scale, chain);
  crf::ChainInference inference;
  crf::maxAndSumProduct (chain, inference, pass.map, pass.marginals);  // Viterbi and forward–backward
  pass.matches = labelsToMatches (pass.geometry.candidates, pass.map.labels);
  pass.T_estimate = robustRigidFit (source.points, target.scan.points, target.normals, pass.geometry.candidates,
                                    pass.matches, inlierProbabilities (pass.marginals), T_current, guess, parameters.fit);
  return pass;
}

MatchResult
matchScans (const Eigen::Matrix2Xd& source, const PreparedTarget& target, const MotionGuess& guess,
            const CrfMatchingModel& model)
{
  checkInputs (model, source, guess);
  MatchResult result;
  result.T_target_source = guess.T_target_source;
  if (source.cols () == 0)
    return result;
  const ScanShape source_scan = describeScan (source);
  const int passes = model.parameters.passes;
  PassResult pass;
  for (int k = 0; k < passes; ++k) {
    const StageModel& stage = model.stages[std::min<std::size_t> (k, model.stages.size () - 1)];
    pass = runPass (source_scan, target, guess, result.T_target_source, stage, model.parameters,
                    &pass.geometry.shape_neighbours);  // the last pass's, if any
    result.T_target_source = pass.T_estimate;
  }
  result.passes = passes;
  result.matches = std::move (pass.matches);
  result.candidates = std::move (pass.geometry.candidates);
  result.map_probability = mapProbabilities (pass.marginals, pass.map.labels);
  result.marginals = std::move (pass.marginals.node_marginals);
  result.inlier_count = static_cast<int> (
      std::count_if (result.matches.begin (), result.matches.end (), [] (int j) { return j != kNoMatch; }));
  return result;
}

MatchingTarget
prepareMatchingTarget (const Eigen::Matrix2Xd& target, const MatchingParameters& parameters)
{
  const std::string problem = scanPointsProblem (target, "target");
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::matching::prepareMatchingTarget] " + problem);
  MatchingTarget prepared;
  prepared.points = target;
  prepared.first_copy = firstOfEqualPoints (target);
  prepared.thinned = thinFirstCopies (target, prepared.first_copy, parameters.training_beam_spacing);
  prepared.prepared = prepareTarget (prepared.thinned.points, parameters.candidates);
  return prepared;
}

MatchResult
matchScans (const Eigen::Matrix2Xd& source, const MatchingTarget& target, const MotionGuess& guess,
            const CrfMatchingModel& model)
{
  checkInputs (model, source, guess);
  const std::vector<int> source_first = firstOfEqualPoints (source);
  if (repeatsAPoint (source_first))  // the first copies alone, lifted to the others
    return liftToSourceCopies (matchScans (source (Eigen::all, firstCopies (source_first)), target, guess, model),
                               source_first);
  ThinnedPair thinned;
  thinned.source = thinToSpacing (source, model.parameters.training_beam_spacing);
  thinned.target = target.thinned;
  if (!thinned.isThinned (source, target.points))
    return matchScans (source, target.prepared, guess, model);
  if (!thinned.source.isThinned (source.cols ()) && target.thinned.factor == 1)  // only target copies dropped
    return indexFullTarget (matchScans (source, target.prepared, guess, model), target.thinned.kept);
  thinned.anchors = thinnedAnchors (source, thinned.source);
  const MatchResult coarse = matchScans (thinned.source.points, target.prepared, guess, model);
  return liftMatchResult (coarse, source, target, thinned);
}

MatchResult
matchScans (const Eigen::Matrix2Xd& source, const Eigen::Matrix2Xd& target, const MotionGuess& guess,
            const CrfMatchingModel& model)
{
  checkModel (model);
  return matchScans (source, prepareMatchingTarget (target, model.parameters), guess, model);
}

}  // namespace matching
}  // namespace pcl_crf
