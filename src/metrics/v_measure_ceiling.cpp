#include <pcl_crf/metrics/v_measure.h>
#include <pcl_crf/metrics/v_measure_ceiling.h>

#include <map>
#include <stdexcept>
#include <string>

namespace pcl_crf {

namespace {

[[noreturn]] void
fail (const char* function, const std::string& what)
{
  throw std::invalid_argument (std::string ("[pcl_crf::") + function + "] " + what);
}

}  // namespace

std::vector<int>
labelsWithoutSmallObjects (const std::vector<int>& objects, int min_points, int background)
{
  if (min_points < 1)
    fail ("labelsWithoutSmallObjects", "min_points must be at least 1, got " + std::to_string (min_points));
  std::map<int, int> size;
  for (int object : objects)
    ++size[object];
  std::vector<int> labels = objects;
  for (int& label : labels)
    if (size[label] < min_points)
      label = background;
  return labels;
}

std::vector<VMeasureCeiling>
vMeasureCeilings (const std::vector<ScanPair>& pairs, const std::vector<int>& min_points, double threshold)
{
  if (pairs.empty ())
    fail ("vMeasureCeilings", "no pairs to score");
  for (const ScanPair& pair : pairs)
    if (pair.source.cols () == 0 || pair.source_object.size () != static_cast<std::size_t> (pair.source.cols ()))
      fail ("vMeasureCeilings", "pair '" + pair.name + "' has " + std::to_string (pair.source.cols ()) +
                                    " source points and " + std::to_string (pair.source_object.size ()) +
                                    " object labels; give one label per point");
  std::vector<VMeasureCeiling> ceilings;
  for (int m : min_points) {
    VMeasureCeiling ceiling;
    ceiling.min_points = m;
    for (const ScanPair& pair : pairs) {
      const double v =
          computeVMeasure (pair.source_object, labelsWithoutSmallObjects (pair.source_object, m, pair.staticObjectId ())).v;
      ceiling.mean_v += v;
      ceiling.pairs_reaching += v >= threshold ? 1 : 0;
    }
    ceiling.mean_v /= static_cast<double> (pairs.size ());
    ceilings.push_back (ceiling);
  }
  return ceilings;
}

}  // namespace pcl_crf
