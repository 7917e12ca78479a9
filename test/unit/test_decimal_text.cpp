#include <pcl_crf/core/decimal_text.h>
#include <pcl_crf/evaluation/evaluate.h>
#include <pcl_crf/evaluation/method.h>
#include <pcl_crf/evaluation/prediction_io.h>
#include <pcl_crf/evaluation/report.h>
#include <pcl_crf/io/dataset_io.h>

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <locale>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kSourceDir = PCL_CRF_SOURCE_DIR;

std::string
fileText (const fs::path& path)
{
  std::ifstream in (path);
  std::stringstream text;
  text << in.rdbuf ();
  return text.str ();
}

}  // namespace

TEST (DecimalText, ReadsDecimalNumbers)
{
  EXPECT_EQ (pcl_crf::parseDecimal ("0.25"), 0.25);
  EXPECT_EQ (pcl_crf::parseDecimal ("-1e-3"), -0.001);
  EXPECT_EQ (pcl_crf::parseDecimal ("+2"), 2.0);
  EXPECT_EQ (pcl_crf::parseDecimal (".5"), 0.5);
  EXPECT_EQ (pcl_crf::parseDecimal ("5."), 5.0);
  EXPECT_EQ (pcl_crf::parseDecimal ("1E5"), 1e5);
  EXPECT_EQ (pcl_crf::parseDecimal ("-1.5707963267948966"), -1.5707963267948966);
  EXPECT_EQ (pcl_crf::parseDecimal ("1e-310"), 1e-310);  // subnormal, still in range
  // Too small for a double: 0, as strtod rounds it (from_chars calls it out of range).
  EXPECT_EQ (pcl_crf::parseDecimal ("1e-400"), 0.0);
  EXPECT_TRUE (std::signbit (*pcl_crf::parseDecimal ("-1e-400")));
  EXPECT_EQ (pcl_crf::parseDecimal ("1e-99999"), 0.0);
  EXPECT_EQ (pcl_crf::parseDecimalFloat ("1e-46"), 0.0f);
  EXPECT_EQ (pcl_crf::parseDecimalFloat ("1e-40"), 1e-40f);
}

TEST (DecimalText, RefusesWhatIsNotAFiniteDecimalNumber)
{
  for (const char* text : {"", "+", "-", "0x10", "0X1p3", "1,5", "nan", "-inf", "infinity", "1e999", "-1e99999", "1e40000",
                           "1.5x", " 1", "1 ", "+-1", "++1", "--1", "e5", "1e", "five"})
    EXPECT_FALSE (pcl_crf::parseDecimal (text).has_value ()) << "'" << text << "'";
}

TEST (DecimalText, WritesAsPrintfDoesInTheCLocale)
{
  EXPECT_EQ (pcl_crf::formatGeneral (0.0025, 17), "0.0025000000000000001");
  EXPECT_EQ (pcl_crf::formatGeneral (1e-9, 17), "1.0000000000000001e-09");
  EXPECT_EQ (pcl_crf::formatGeneral (0.25, 17), "0.25");
  EXPECT_EQ (pcl_crf::formatGeneral (1e9, 6), "1e+09");
  EXPECT_EQ (pcl_crf::formatFixed (0.86654, 4), "0.8665");
  EXPECT_EQ (pcl_crf::formatFixed (1575811858.2734, 3), "1575811858.273");
  EXPECT_EQ (pcl_crf::formatScientific (0.000123, 3), "1.230e-04");
  EXPECT_EQ (pcl_crf::formatShortest (0.1), "0.1");
  EXPECT_EQ (pcl_crf::formatShortest (-1.0), "-1");
}

TEST (DecimalText, SeventeenDigitsAndTheShortestTextReadBackExactly)
{
  std::mt19937_64 rng (44);
  std::uniform_real_distribution<double> exponent (-300.0, 300.0), mantissa (-1.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    const double value = mantissa (rng) * std::pow (10.0, exponent (rng));
    ASSERT_EQ (pcl_crf::parseDecimal (pcl_crf::formatGeneral (value, 17)), value) << value;
    ASSERT_EQ (pcl_crf::parseDecimal (pcl_crf::formatShortest (value)), value) << value;
  }
  const double largest = std::numeric_limits<double>::max ();
  EXPECT_EQ (pcl_crf::parseDecimal (pcl_crf::formatFixed (largest, 4)), largest);
}

/** Runs a test in a program whose C and C++ locales are German (decimal comma, digit
 *  grouping with points), as a host program's setlocale (LC_ALL, "") would set them
 *  under LANG=de_DE.UTF-8. Skips when the machine has no such locale (scripts/setup.sh
 *  --test generates it). */
class GermanLocale : public ::testing::Test
{
protected:
  static constexpr const char* kGerman = "de_DE.UTF-8";

  /** Switches both locales; false when the machine lacks the locale. */
  bool
  switchToGerman ()
  {
    try {
      saved_cpp_ = std::locale::global (std::locale (kGerman));  // sets the C locale as well
      switched_ = true;
    }
    catch (const std::runtime_error&) {
      return false;
    }
    return std::string (std::setlocale (LC_NUMERIC, nullptr)) == kGerman;
  }

  void
  TearDown () override
  {
    if (switched_)
      std::locale::global (saved_cpp_);
    std::setlocale (LC_ALL, "C");
  }

  fs::path
  scratch (const std::string& name) const
  {
    const fs::path dir = fs::temp_directory_path () / ("pcl_crf_locale_" + name);
    fs::remove_all (dir);
    return dir;
  }

private:
  std::locale saved_cpp_;
  bool switched_ = false;
};

TEST_F (GermanLocale, TheShippedModelsLoadAndPredictAsInTheCLocale)
{
  // strtod stopped "0.25" at its point: no shipped model or dataset loaded.
  const std::vector<pcl_crf::ScanPair> pairs = pcl_crf::loadDataset (kSourceDir + "/data/default/test");
  auto joint = pcl_crf::createEvaluationMethod ("joint");
  joint->loadModel (kSourceDir + "/data/models/joint.model");
  const pcl_crf::Prediction reference = joint->predict (pairs.front ());

  if (!switchToGerman ())
    GTEST_SKIP () << kGerman << " is not installed (localedef -i de_DE -f UTF-8 de_DE.UTF-8)";
  ASSERT_NE (std::string (std::localeconv ()->decimal_point), ".");  // the test means something

  const std::vector<pcl_crf::ScanPair> german_pairs = pcl_crf::loadDataset (kSourceDir + "/data/default/test");
  ASSERT_EQ (german_pairs.size (), pairs.size ());
  EXPECT_EQ (german_pairs.front ().sensor.angle_min, pairs.front ().sensor.angle_min);
  EXPECT_TRUE (german_pairs.back ().source.isApprox (pairs.back ().source, 0.0));
  for (const fs::path& model : fs::directory_iterator (kSourceDir + "/data/models")) {
    auto method = pcl_crf::createEvaluationMethod (model.stem ().string ());
    EXPECT_NO_THROW (method->loadModel (model.string ())) << model;
  }
  auto german_joint = pcl_crf::createEvaluationMethod ("joint");
  german_joint->loadModel (kSourceDir + "/data/models/joint.model");
  const pcl_crf::Prediction prediction = german_joint->predict (german_pairs.front ());
  EXPECT_EQ (prediction.source_cluster, reference.source_cluster);
  EXPECT_EQ (prediction.source_match, reference.source_match);
  EXPECT_TRUE (prediction.T_source_target.isApprox (reference.T_source_target, 0.0));
}

TEST_F (GermanLocale, FilesWrittenReadTheSameAsInTheCLocale)
{
  pcl_crf::ScanPair pair = pcl_crf::loadDataset (kSourceDir + "/data/default/test").front ();
  const int world = pair.staticObjectId ();  // renamed to a count a German std::locale::global groups as "1.234"
  pair.objects[pair.objectIndex (world)].id = 1234;
  for (std::vector<int>* labels : {&pair.source_object, &pair.target_object})
    for (int& id : *labels)
      id = id == world ? 1234 : id;
  const fs::path c_dir = scratch ("c"), german_dir = scratch ("de");
  pcl_crf::saveScanPair (pair, c_dir.string ());
  pcl_crf::Prediction prediction;
  prediction.T_source_target = pair.odometry.T_source_target;
  prediction.cluster_motions = {pair.objects.front ().T_target_source};
  prediction.static_cluster = 0;
  prediction.source_cluster.assign (pair.source.cols (), 0);
  prediction.seconds = 0.00123;
  pcl_crf::savePrediction (pair, prediction, "joint", (c_dir / "prediction").string ());

  if (!switchToGerman ())
    GTEST_SKIP () << kGerman << " is not installed (localedef -i de_DE -f UTF-8 de_DE.UTF-8)";
  pcl_crf::saveScanPair (pair, german_dir.string ());
  pcl_crf::savePrediction (pair, prediction, "joint", (german_dir / "prediction").string ());
  for (const char* file : {"pair.txt", "source.pcd", "target.pcd"})
    EXPECT_EQ (fileText (german_dir / file), fileText (c_dir / file)) << file;
  EXPECT_NE (fileText (german_dir / "pair.txt").find ("object 1234 static"), std::string::npos);
  for (const char* file : {"prediction.txt", "prediction.pcd"})
    EXPECT_EQ (fileText (german_dir / "prediction" / file), fileText (c_dir / "prediction" / file)) << file;
  const pcl_crf::Prediction read = pcl_crf::loadPrediction ((german_dir / "prediction").string ());
  EXPECT_TRUE (read.cluster_motions.front ().isApprox (prediction.cluster_motions.front (), 1e-15));
  EXPECT_DOUBLE_EQ (read.seconds, 0.00123);
  const pcl_crf::ScanPair read_pair = pcl_crf::loadScanPair (german_dir.string ());
  EXPECT_EQ (read_pair.staticObjectId (), 1234);
  EXPECT_TRUE (read_pair.odometry.covariance.isApprox (pair.odometry.covariance, 0.0));
  fs::remove_all (c_dir);
  fs::remove_all (german_dir);
}

TEST_F (GermanLocale, ReportsUseThePointAndNoDigitGrouping)
{
  pcl_crf::MethodEvaluation evaluation;
  evaluation.method = "joint";
  evaluation.summary = {{"association accuracy", "fraction", 0.86654, 0.125, 1234}};
  if (!switchToGerman ())
    GTEST_SKIP () << kGerman << " is not installed (localedef -i de_DE -f UTF-8 de_DE.UTF-8)";
  std::ostringstream csv, table;
  csv.imbue (std::locale ());  // the German global locale, as std::cout would have after imbue
  table.imbue (std::locale ());
  pcl_crf::writeEvaluationCsv (csv, {evaluation});
  pcl_crf::printEvaluationTable (table, {evaluation});
  EXPECT_EQ (csv.str (), "method,metric,unit,mean,std,count\njoint,association accuracy,fraction,0.86654,0.125,1234\n");
  EXPECT_NE (table.str ().find ("0.8665"), std::string::npos) << table.str ();
  EXPECT_EQ (table.str ().find (','), std::string::npos) << table.str ();
}
