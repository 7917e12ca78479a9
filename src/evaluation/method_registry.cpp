#include <pcl_crf/evaluation/clustering_methods.h>
#include <pcl_crf/evaluation/joint_methods.h>
#include <pcl_crf/evaluation/matching_methods.h>
#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/evaluation/no_return_points.h>
#include <pcl_crf/evaluation/pipeline_methods.h>

#include <functional>
#include <stdexcept>
#include <utility>

namespace pcl_crf {
namespace {

using MethodFactory = std::function<std::unique_ptr<EvaluationMethod> (const MethodSettings&)>;

const std::vector<std::pair<std::string, MethodFactory>>&
registry ()
{
  static const std::vector<std::pair<std::string, MethodFactory>> methods = {
      {"icp", [] (const MethodSettings&) { return makeIcpMethod (); }},
      {"crf-matching", [] (const MethodSettings&) { return makeCrfMatchingMethod (); }},
      {"kmeans", [] (const MethodSettings& settings) { return makeKMeansMethod (settings.cluster_count); }},
      {"cbd", [] (const MethodSettings&) { return makeConsistencyMethod (); }},
      {"crf-t", [] (const MethodSettings&) { return makeCrfClusteringTrueAssociationsMethod (); }},
      {"icp+kmeans", [] (const MethodSettings& settings) { return makeIcpKMeansMethod (settings.cluster_count); }},
      {"crf-matching+kmeans",
       [] (const MethodSettings& settings) { return makeCrfMatchingKMeansMethod (settings.cluster_count); }},
      {"crf-m", [] (const MethodSettings&) { return makeCrfMMethod (); }},
      {"joint", [] (const MethodSettings&) { return makeJointMethod (); }},
  };
  return methods;
}

}  // namespace

std::vector<std::string>
availableEvaluationMethods ()
{
  std::vector<std::string> names;
  for (const auto& entry : registry ())
    names.push_back (entry.first);
  return names;
}

std::unique_ptr<EvaluationMethod>
createEvaluationMethod (const std::string& name, const MethodSettings& settings)
{
  for (const auto& entry : registry ())
    if (entry.first == name)
      return ignoringNoReturnPoints (entry.second (settings));
  std::string known;
  for (const auto& entry : registry ())
    known += (known.empty () ? "" : ", ") + entry.first;
  throw std::invalid_argument ("unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace pcl_crf
