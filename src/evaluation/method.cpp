#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/io/readable_file.h>

#include <fstream>
#include <sstream>

namespace pcl_crf {

void
EvaluationMethod::saveModel (const std::string& path) const
{
  std::ostringstream text;  // all of it first: a failing writeModel leaves no file behind
  writeModel (text);
  std::ofstream file (path);
  if (!file)
    throw std::runtime_error (name () + ": cannot open '" + path + "' for writing");
  file << text.str ();
  if (!file.flush ())
    throw std::runtime_error (name () + ": failed writing '" + path + "'");
}

void
EvaluationMethod::loadModel (const std::string& path)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw std::runtime_error (name () + ": cannot read the model file '" + path + "': " + problem);
  std::ifstream file (path);
  readModel (file, path);
}

}  // namespace pcl_crf
