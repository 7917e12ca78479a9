// pcl_crf_eval: runs methods over a labelled dataset and prints the papers' tables.

#include <pcl_crf/evaluation/evaluate.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/evaluation/report.h>
#include <pcl_crf/io/dataset_io.h>
#include <pcl_crf/metrics/v_measure_ceiling.h>

#include "app_common.h"

#include <pcl/common/time.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <unistd.h>

using namespace pcl::console;

namespace {

struct EvalArguments
{
  std::string dataset;
  std::vector<std::string> methods{"icp"};
  std::string train_dir;
  std::string model_dir;
  std::string format = "table";
  std::string output;
  std::string save_predictions;
  double tolerance = 0.1;
  int max_pairs = 0;
  int clusters = 0;
  bool leave_one_out = false;
  bool v_ceiling = false;
  bool quiet = false;
};

void
printHelp (const char* program)
{
  std::string methods;
  for (const auto& name : pcl_crf::availableEvaluationMethods ())
    methods += (methods.empty () ? "" : ", ") + name;
  print_info ("Scores methods on a labelled scan-pair dataset (see data/README.md).\n\n"
              "Usage: %s DATASET_DIR [options]\n\n", program);
  print_info ("  --method NAMES        comma-separated methods (default: icp); known: %s\n", methods.c_str ());
  print_info ("  --train DIR           training dataset for learned methods (default: none)\n");
  print_info ("  --models DIR          load learned methods from DIR/<method>.model (pcl_crf_train writes them;\n"
              "                        data/models holds the defaults trained on data/default/train,\n"
              "                        installed in <prefix>/share/pcl_crf/models)\n");
  print_info ("  --clusters K          clusters for K-Means-like baselines (default: method's own)\n");
  print_info ("  --format F            table | csv | json (default: table); json also holds every pair's\n"
              "                        scores (\"per_pair\")\n");
  print_info ("  --output FILE         write the csv/json/table there instead of stdout\n");
  print_info ("  --save-predictions D  write every pair's prediction to D/<method>/<pair>/\n");
  print_info ("  --tolerance M         association tolerance [m] (default: 0.1)\n");
  print_info ("  --leave-one-out       for each pair: train every learned method on all the other pairs of\n"
              "                        DATASET_DIR, then score it on that pair (no --train / --models)\n");
  print_info ("  --max-pairs N         evaluate the first N pairs only; with --leave-one-out, hold out the\n"
              "                        first N in turn, still training on all others (default: all)\n");
  print_info ("  --v-ceiling           no method runs: prints the mean V-measure of oracles that cluster every\n"
              "                        object of at least N source points exactly and leave smaller ones in\n"
              "                        the static world (N = 1, 2, 3, 5, 9, 20), the V the dataset allows a\n"
              "                        method that cannot see movers below N points\n");
  print_info ("  -q                    no progress line\n");
  print_info ("  -h                    this help\n");
}

bool
parseArguments (int argc, char** argv, EvalArguments& args)
{
  const std::set<std::string> value_options{"--method", "--output", "--save-predictions", "--train", "--models",
                                            "--format", "--tolerance", "--max-pairs", "--clusters"};
  if (!pcl_crf::apps::checkOptions (argc, argv, value_options, {"--leave-one-out", "--v-ceiling", "-q"}))
    return false;
  const auto positional = pcl_crf::apps::positionalArguments (argc, argv, value_options);
  if (positional.size () > 1)
    return print_error ("Expected one dataset folder, got %zu arguments (see -h).\n", positional.size ()), false;
  if (!positional.empty ())
    args.dataset = positional.front ();
  std::string methods;
  if (parse_argument (argc, argv, "--method", methods) >= 0)
    args.methods = pcl_crf::apps::splitCommas (methods);
  parse_argument (argc, argv, "--train", args.train_dir);
  parse_argument (argc, argv, "--models", args.model_dir);
  parse_argument (argc, argv, "--format", args.format);
  parse_argument (argc, argv, "--output", args.output);
  parse_argument (argc, argv, "--save-predictions", args.save_predictions);
  long max_pairs = 0, clusters = 0;
  if (!pcl_crf::apps::numberOption (argc, argv, "--tolerance", args.tolerance) ||
      !pcl_crf::apps::countOption (argc, argv, "--max-pairs", max_pairs, 0) ||
      !pcl_crf::apps::countOption (argc, argv, "--clusters", clusters, 0))
    return false;
  constexpr long kLargeCount = 1000000000L;  // more pairs or clusters than any dataset has points
  args.max_pairs = static_cast<int> (std::min (max_pairs, kLargeCount));
  args.clusters = static_cast<int> (std::min (clusters, kLargeCount));
  args.leave_one_out = find_switch (argc, argv, "--leave-one-out");
  args.v_ceiling = find_switch (argc, argv, "--v-ceiling");
  args.quiet = find_switch (argc, argv, "-q");
  if (args.dataset.empty ())
    return print_error ("No dataset folder given (see -h).\n"), false;
  if (args.methods.empty ())
    return print_error ("--method needs at least one method name.\n"), false;
  std::set<std::string> named;
  for (const std::string& method : args.methods)
    if (!named.insert (method).second)
      return print_error ("--method names '%s' twice.\n", method.c_str ()), false;
  if (args.format != "table" && args.format != "csv" && args.format != "json")
    return print_error ("--format must be table, csv or json, not '%s'.\n", args.format.c_str ()), false;
  if (!(args.tolerance >= 0.0))
    return print_error ("--tolerance must be a non-negative distance in metres.\n"), false;
  if (args.leave_one_out && (!args.train_dir.empty () || !args.model_dir.empty ()))
    return print_error ("--leave-one-out trains every learned method on the dataset's other pairs: "
                        "drop --train / --models.\n"), false;
  return true;
}

pcl_crf::EvaluationProgress
progressLine (bool quiet, const std::string& method)
{
  if (quiet)
    return {};
  const bool terminal = isatty (STDERR_FILENO);
  return [terminal, method] (std::size_t done, std::size_t total, const std::string& name) {
    if (terminal)
      std::cerr << "\r[" << method << "] " << done << "/" << total << " " << name << "        " << std::flush;
    else if (done == total || done % 10 == 0)
      std::cerr << "[" << method << "] " << done << "/" << total << " pairs\n";
    if (terminal && done == total)
      std::cerr << "\n";
  };
}

pcl_crf::FoldProgress
foldProgressLine (bool quiet, const std::string& method)
{
  if (quiet)
    return {};
  const bool terminal = isatty (STDERR_FILENO);
  return [terminal, method] (const pcl_crf::FoldStatus& fold) {
    std::ostringstream line;
    line << "[" << method << "] fold " << fold.fold << "/" << fold.folds << " " << fold.held_out;
    if (fold.training_pairs > 0)
      line << (fold.finished ? ": scored" : ": training on " + std::to_string (fold.training_pairs) + " pairs");
    if (terminal)
      std::cerr << "\r" << line.str () << "        " << (fold.finished && fold.fold == fold.folds ? "\n" : "")
                << std::flush;
    else if (fold.training_pairs > 0 ? !fold.finished
                                     : fold.finished && (fold.fold % 10 == 0 || fold.fold == fold.folds))
      std::cerr << line.str () << "\n";
  };
}

std::unique_ptr<pcl_crf::EvaluationMethod>
prepareMethod (const std::string& name, const EvalArguments& args)
{
  pcl_crf::MethodSettings settings;
  settings.cluster_count = args.clusters;
  auto method = pcl_crf::createEvaluationMethod (name, settings);
  const std::string model_file = (std::filesystem::path (args.model_dir) / (name + ".model")).string ();
  if (!method->isLearned ())
    return method;
  if (!args.train_dir.empty ()) {
    pcl::console::TicToc timer;
    timer.tic ();
    method->train (pcl_crf::loadDataset (args.train_dir));
    if (!args.quiet)
      print_info ("[%s] trained on %s in %g s\n", name.c_str (), args.train_dir.c_str (), timer.toc () / 1000.0);
  }
  else if (!args.model_dir.empty ())
    method->loadModel (model_file);
  else
    throw std::invalid_argument ("method '" + name + "' learns its weights: give --train DIR or --models DIR");
  return method;
}

void
savePredictions (const EvalArguments& args, const std::vector<pcl_crf::ScanPair>& pairs,
                 const pcl_crf::MethodEvaluation& evaluation)
{
  for (std::size_t k = 0; k < pairs.size (); ++k)
    pcl_crf::savePrediction (pairs[k], evaluation.predictions[k], evaluation.method,
                             (std::filesystem::path (args.save_predictions) / evaluation.method / pairs[k].name).string ());
}

/** Where the report goes: --output FILE (opened into \a file), else stdout. */
std::ostream&
reportStream (const EvalArguments& args, std::ofstream& file)
{
  if (args.output.empty ())
    return std::cout;
  file.open (args.output);
  if (!file)
    throw std::runtime_error ("cannot write " + args.output);
  return file;
}

void
writeReport (const EvalArguments& args, const std::vector<pcl_crf::MethodEvaluation>& evaluations)
{
  std::ofstream file;
  std::ostream& out = reportStream (args, file);
  if (args.format == "csv")
    pcl_crf::writeEvaluationCsv (out, evaluations);
  else if (args.format == "json")
    pcl_crf::writeEvaluationJson (out, evaluations);
  else
    pcl_crf::printEvaluationTable (out, evaluations);
}

/** The table of --v-ceiling: V of the small-object oracles over \a pairs. */
void
writeVMeasureCeilings (const EvalArguments& args, const std::vector<pcl_crf::ScanPair>& pairs)
{
  constexpr double kReached = 0.95;
  const auto ceilings = pcl_crf::vMeasureCeilings (pairs, {1, 2, 3, 5, 9, 20}, kReached);
  std::ofstream file;
  std::ostream& out = reportStream (args, file);
  out << "oracle: every object of >= N source points clustered exactly, smaller ones in the static world\n"
      << "N     mean V   pairs with V >= " << kReached << " (of " << pairs.size () << ")\n";
  char line[64];
  for (const auto& ceiling : ceilings) {
    std::snprintf (line, sizeof (line), "%-5d %6.3f   %d\n", ceiling.min_points, ceiling.mean_v, ceiling.pairs_reaching);
    out << line;
  }
}

/** Every method trained and scored leave-one-out over the dataset. */
std::vector<pcl_crf::MethodEvaluation>
runLeaveOneOut (const EvalArguments& args, const std::vector<pcl_crf::ScanPair>& pairs,
                const pcl_crf::ScoreOptions& options)
{
  pcl_crf::MethodSettings settings;
  settings.cluster_count = args.clusters;
  const std::size_t folds = args.max_pairs > 0 ? std::min<std::size_t> (args.max_pairs, pairs.size ()) : pairs.size ();
  if (!args.quiet && pairs.size () >= 2)  // fewer: evaluateLeaveOneOut says why not
    print_info ("Leave-one-out: %zu folds, each learned method trained on %zu pairs per fold\n", folds,
                pairs.size () - 1);
  std::vector<pcl_crf::MethodEvaluation> evaluations;
  for (const auto& name : args.methods) {
    pcl::console::TicToc timer;
    timer.tic ();
    evaluations.push_back (pcl_crf::evaluateLeaveOneOut (
        [&] { return pcl_crf::createEvaluationMethod (name, settings); }, pairs, folds, options,
        foldProgressLine (args.quiet, name)));
    if (!args.quiet)
      print_info ("[%s] %zu folds in %g s\n", name.c_str (), folds, timer.toc () / 1000.0);
    if (!args.save_predictions.empty ())
      savePredictions (args, {pairs.begin (), pairs.begin () + static_cast<std::ptrdiff_t> (folds)},
                       evaluations.back ());
  }
  return evaluations;
}

int
run (const EvalArguments& args)
{
  pcl::console::TicToc timer;
  timer.tic ();
  std::vector<pcl_crf::ScanPair> pairs = pcl_crf::loadDataset (args.dataset);
  if (!args.quiet)
    print_info ("Loaded %zu pairs from %s in %g ms\n", pairs.size (), args.dataset.c_str (), timer.toc ());
  pcl_crf::ScoreOptions options;
  options.match_tolerance = args.tolerance;
  if (args.leave_one_out && !args.v_ceiling) {  // trains on every pair, holds out the first max_pairs
    writeReport (args, runLeaveOneOut (args, pairs, options));
    return 0;
  }
  if (args.max_pairs > 0 && pairs.size () > static_cast<std::size_t> (args.max_pairs))
    pairs.resize (args.max_pairs);
  if (args.v_ceiling) {
    writeVMeasureCeilings (args, pairs);
    return 0;
  }
  std::vector<pcl_crf::MethodEvaluation> evaluations;
  for (const auto& name : args.methods) {
    auto method = prepareMethod (name, args);
    evaluations.push_back (pcl_crf::evaluateMethod (*method, pairs, options, progressLine (args.quiet, name)));
    if (!args.save_predictions.empty ())
      savePredictions (args, pairs, evaluations.back ());
  }
  writeReport (args, evaluations);
  return 0;
}

}  // namespace

int
main (int argc, char** argv)
{
  if (const int code = pcl_crf::apps::helpExitCode (argc, argv, printHelp); code >= 0)
    return code;
  EvalArguments args;
  if (!parseArguments (argc, argv, args))
    return 1;
  return pcl_crf::apps::exitCodeOf ([&] { return run (args); });
}
