#include <pcl_crf/evaluation/method.h>

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
  std::ifstream file (path);
  if (!file)
    throw std::runtime_error (name () + ": cannot open the model file '" + path + "'");
  readModel (file, path);
}

}  // namespace pcl_crf
