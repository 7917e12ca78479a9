// pcl_crf_train: learns a method's weights from a labelled dataset and writes its model file.

#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/io/dataset_io.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include "app_common.h"

#include <algorithm>

using namespace pcl::console;

namespace {

void
printHelp (const char* program)
{
  std::string learned;
  for (const auto& name : pcl_crf::availableEvaluationMethods ())
    if (pcl_crf::createEvaluationMethod (name)->isLearned ())
      learned += (learned.empty () ? "" : ", ") + name;
  print_info ("Learns a method's weights (maximum pseudo-likelihood with L-BFGS, AdaBoost stumps)\n"
              "from a labelled scan-pair dataset and writes a versioned text model file.\n\n"
              "Usage: %s TRAIN_DIR --method NAME -o MODEL_FILE\n\n", program);
  print_info ("  --method NAME   the method to train; learned methods: %s\n", learned.c_str ());
  print_info ("  -o FILE         the model file to write (pcl_crf_eval --models DIR reads DIR/NAME.model)\n");
  print_info ("  -h              this help\n");
}

}  // namespace

int
main (int argc, char** argv)
{
  if (const int code = pcl_crf::apps::helpExitCode (argc, argv, printHelp); code >= 0)
    return code;
  const std::set<std::string> value_options{"--method", "-o"};
  if (!pcl_crf::apps::checkOptions (argc, argv, value_options, {}))
    return 1;
  const auto positional = pcl_crf::apps::positionalArguments (argc, argv, value_options);
  std::string method_name, output;
  parse_argument (argc, argv, "--method", method_name);
  parse_argument (argc, argv, "-o", output);
  if (positional.size () != 1)
    return print_error ("Expected exactly one training dataset folder (see -h).\n"), 1;
  if (method_name.empty () || output.empty ())
    return print_error ("Both --method NAME and -o MODEL_FILE are required (see -h).\n"), 1;
  return pcl_crf::apps::exitCodeOf ([&] {
    auto method = pcl_crf::createEvaluationMethod (method_name);
    if (!method->isLearned ())
      return print_error ("Method '%s' learns nothing: there is no model to train.\n", method_name.c_str ()), 1;
    TicToc timer;
    timer.tic ();
    const auto pairs = pcl_crf::loadDataset (positional.front ());
    print_highlight ("Training %s on %zu pairs of %s\n", method_name.c_str (), pairs.size (), positional.front ().c_str ());
    const bool some_mover = std::any_of (pairs.begin (), pairs.end (), [] (const pcl_crf::ScanPair& pair) {
      const int world = pair.staticObjectId ();
      return std::any_of (pair.source_object.begin (), pair.source_object.end (), [world] (int id) { return id != world; });
    });
    if (!some_mover && method_name != "crf-matching")
      print_warn ("No training pair has a point on a moving object: %s learns its clusters from the static world "
                  "alone.\n", method_name.c_str ());
    method->train (pairs);
    method->saveModel (output);
    print_info ("Wrote "), print_value ("%s", output.c_str ()), print_info (" in %g s\n", timer.toc () / 1000.0);
    return 0;
  });
}
