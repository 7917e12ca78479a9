#include <pcl_crf/evaluation/no_return_points.h>
#include <pcl_crf/core/beam_order.h>
#include <pcl_crf/core/repeated_points.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace pcl_crf {

namespace {

/** The columns \a kept of \a points, in that order. */
Eigen::Matrix2Xd
columns (const Eigen::Matrix2Xd& points, const std::vector<int>& kept)
{
  Eigen::Matrix2Xd out (2, static_cast<Eigen::Index> (kept.size ()));
  for (std::size_t k = 0; k < kept.size (); ++k)
    out.col (static_cast<Eigen::Index> (k)) = points.col (kept[k]);
  return out;
}

/** The indices of the points of \a scan that are returns (isReturn ()), in beam order
 *  (beamOrder (): increasing unless the scan was in no beam order or listed clockwise),
 *  each position once: a return at the coordinates of one before it in that order is
 *  left out, so that a scan listed either way round keeps the same copy. */
std::vector<int>
returnsOf (const Eigen::Matrix2Xd& scan, double range_max)
{
  std::vector<int> returns;
  returns.reserve (static_cast<std::size_t> (scan.cols ()));
  for (Eigen::Index i = 0; i < scan.cols (); ++i)
    if (isReturn (scan.col (i).norm (), range_max))
      returns.push_back (static_cast<int> (i));
  const bool every_point = static_cast<Eigen::Index> (returns.size ()) == scan.cols ();  // then 0, 1, ...
  const std::vector<int> order = every_point ? beamOrder (scan) : beamOrder (columns (scan, returns));
  const std::vector<int> copies_of = firstOfEqualPoints (scan);  // one entry per set of equal points
  std::vector<bool> seen (static_cast<std::size_t> (scan.cols ()), false);
  std::vector<int> kept;
  kept.reserve (returns.size ());
  for (const int k : order) {
    const int i = returns[static_cast<std::size_t> (k)];
    const auto copies = static_cast<std::size_t> (copies_of[static_cast<std::size_t> (i)]);
    if (!seen[copies]) {
      seen[copies] = true;
      kept.push_back (i);
    }
  }
  return kept;
}

/** Whether the returns of either scan of \a pair (returnsOf ()) leave out a point or
 *  reorder them. */
bool
changesAScan (const ScanPair& pair)
{
  PairReturns returns;  // the indices alone: no copy of the pair
  returns.source_size = static_cast<int> (pair.source.cols ());
  returns.target_size = static_cast<int> (pair.target.cols ());
  returns.source_index = returnsOf (pair.source, pair.sensor.range_max);
  returns.target_index = returnsOf (pair.target, pair.sensor.range_max);
  return !returns.keepsEveryPoint ();
}

/** The entries \a kept of \a values (empty stays empty: no ground truth). */
std::vector<int>
entries (const std::vector<int>& values, const std::vector<int>& kept)
{
  if (values.empty ())
    return {};
  std::vector<int> out;
  out.reserve (kept.size ());
  for (int i : kept)
    out.push_back (values[static_cast<std::size_t> (i)]);
  return out;
}

/** Per original point: its index among \a kept, or −1 when it was left out. */
std::vector<int>
newIndices (const std::vector<int>& kept, int size)
{
  std::vector<int> index (static_cast<std::size_t> (size), -1);
  for (std::size_t k = 0; k < kept.size (); ++k)
    index[static_cast<std::size_t> (kept[k])] = static_cast<int> (k);
  return index;
}

class NoReturnPointsLeftOut : public EvaluationMethod
{
public:
  explicit NoReturnPointsLeftOut (std::unique_ptr<EvaluationMethod> method) : method_ (std::move (method))
  {
    if (!method_)
      throw std::invalid_argument ("[pcl_crf::ignoringNoReturnPoints] no method given");
  }

  std::string
  name () const override { return method_->name (); }

  bool
  isLearned () const override { return method_->isLearned (); }

  void
  train (const std::vector<ScanPair>& training_pairs) override
  {
    if (std::none_of (training_pairs.begin (), training_pairs.end (), changesAScan)) {
      method_->train (training_pairs);  // the usual case: no copy
      return;
    }
    std::vector<ScanPair> returns;  // a pair with a scan of no return teaches nothing: left out
    returns.reserve (training_pairs.size ());
    for (const ScanPair& pair : training_pairs) {
      if (!changesAScan (pair)) {
        returns.push_back (pair);
        continue;
      }
      PairReturns kept = keepReturns (pair);
      if (holdsAReturnInEachScan (kept))
        returns.push_back (std::move (kept.pair));
    }
    if (returns.empty ())
      throw std::invalid_argument ("every training pair has a scan without a return (every point at the sensor (0, 0) "
                                   "or at or beyond the sensor's maximum range): nothing to learn from");
    method_->train (returns);
  }

  void
  writeModel (std::ostream& os) const override { method_->writeModel (os); }

  void
  readModel (std::istream& is, const std::string& where) override { method_->readModel (is, where); }

  void
  saveModel (const std::string& path) const override { method_->saveModel (path); }

  void
  loadModel (const std::string& path) override { method_->loadModel (path); }

  Prediction
  predict (const ScanPair& pair) override
  {
    const std::string problem = odometryProblem (pair.odometry);
    if (!problem.empty ())
      throw std::invalid_argument ("pair '" + pair.name + "': " + problem);
    if (!changesAScan (pair))
      return method_->predict (pair);  // the usual case: no copy of the pair
    const PairReturns returns = keepReturns (pair);
    if (!holdsAReturnInEachScan (returns))  // nothing to estimate from
      return predictFromOdometry (pair);
    return liftToAllPoints (method_->predict (returns.pair), returns);
  }

private:
  static bool
  holdsAReturnInEachScan (const PairReturns& returns)
  {
    return !returns.source_index.empty () && !returns.target_index.empty ();
  }

  std::unique_ptr<EvaluationMethod> method_;
};

}  // namespace

bool
isReturn (double range, double range_max)
{
  // A point stored at the maximum range in single precision (PCD's float x and y) may
  // come back up to a few ulp nearer; 1e-5 of the range is far above that and far
  // below any laser's resolution (0.3 mm at 30 m).
  constexpr double kRelativeRounding = 1e-5;
  if (!(range > 0.0))  // the sensor's own position: a driver's 0 for a beam without a return
    return false;
  return !(range_max > 0.0 && std::isfinite (range_max)) || range < range_max * (1.0 - kRelativeRounding);
}

PairReturns
keepReturns (const ScanPair& pair)
{
  PairReturns returns;
  returns.source_size = static_cast<int> (pair.source.cols ());
  returns.target_size = static_cast<int> (pair.target.cols ());
  returns.source_index = returnsOf (pair.source, pair.sensor.range_max);
  returns.target_index = returnsOf (pair.target, pair.sensor.range_max);
  returns.pair = pair;
  if (returns.keepsEveryPoint ())
    return returns;
  ScanPair& reduced = returns.pair;
  reduced.source = columns (pair.source, returns.source_index);
  reduced.target = columns (pair.target, returns.target_index);
  reduced.source_object = entries (pair.source_object, returns.source_index);
  reduced.target_object = entries (pair.target_object, returns.target_index);
  reduced.source_match = entries (pair.source_match, returns.source_index);
  const std::vector<int> target_position = newIndices (returns.target_index, returns.target_size);
  for (int& j : reduced.source_match)
    j = j >= 0 && j < returns.target_size ? target_position[static_cast<std::size_t> (j)] : kNoMatch;
  return returns;
}

Prediction
liftToAllPoints (const Prediction& reduced, const PairReturns& returns)
{
  const auto kept = returns.source_index.size ();
  const auto fail = [] (const std::string& what) {
    throw std::invalid_argument ("[pcl_crf::liftToAllPoints] " + what);
  };
  if ((!reduced.source_match.empty () && reduced.source_match.size () != kept) ||
      (!reduced.source_cluster.empty () && reduced.source_cluster.size () != kept))
    fail ("the prediction does not have one entry per kept source point (" + std::to_string (kept) + ")");
  Prediction all = reduced;
  if (!reduced.source_match.empty ()) {
    all.source_match.assign (static_cast<std::size_t> (returns.source_size), kNoMatch);
    for (std::size_t k = 0; k < kept; ++k) {
      const int j = reduced.source_match[k];
      if (j != kNoMatch && (j < 0 || j >= static_cast<int> (returns.target_index.size ())))
        fail ("source point " + std::to_string (k) + " is matched to target point " + std::to_string (j) + " of " +
              std::to_string (returns.target_index.size ()));
      all.source_match[static_cast<std::size_t> (returns.source_index[k])] =
          j == kNoMatch ? kNoMatch : returns.target_index[static_cast<std::size_t> (j)];
    }
  }
  if (!reduced.source_cluster.empty ()) {
    // A beam without a return saw the background up to the laser's range: the static
    // world (an outlier when the method names none), never a match.
    const int background = reduced.static_cluster >= 0 ? reduced.static_cluster : kOutlierCluster;
    all.source_cluster.assign (static_cast<std::size_t> (returns.source_size), background);
    for (std::size_t k = 0; k < kept; ++k)
      all.source_cluster[static_cast<std::size_t> (returns.source_index[k])] = reduced.source_cluster[k];
  }
  return all;
}

Prediction
predictFromOdometry (const ScanPair& pair)
{
  const std::string problem = odometryProblem (pair.odometry);
  if (!problem.empty ())
    throw std::invalid_argument ("[pcl_crf::predictFromOdometry] pair '" + pair.name + "': " + problem);
  Prediction prediction;
  prediction.source_cluster.assign (static_cast<std::size_t> (pair.source.cols ()), 0);
  prediction.cluster_motions = {pair.odometry.T_source_target.inverse ()};
  prediction.static_cluster = 0;
  prediction.T_source_target = pair.odometry.T_source_target;
  return prediction;
}

std::unique_ptr<EvaluationMethod>
ignoringNoReturnPoints (std::unique_ptr<EvaluationMethod> method)
{
  return std::make_unique<NoReturnPointsLeftOut> (std::move (method));
}

}  // namespace pcl_crf
