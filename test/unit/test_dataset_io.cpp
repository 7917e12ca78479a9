#include <pcl_crf/io/dataset_io.h>

#include "file_edits.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using pcl_crf::test::replaceInFile;
using pcl_crf::DatasetError;
using pcl_crf::ScanPair;

namespace {

ScanPair
makeSmallPair ()
{
  ScanPair pair;
  pair.name = "pair_0000";
  pair.sensor = {5, -M_PI / 2, M_PI / 4, 30.0};
  pair.source.resize (2, 4);
  pair.source << 1.0, 2.0, 3.0, 4.0,
                 0.5, 0.25, -0.5, 1.5;
  pair.target.resize (2, 3);
  pair.target << 1.1, 2.1, 3.1,
                 0.5, 0.25, -0.5;
  pair.source_object = {0, 0, 3, 3};
  pair.target_object = {0, 0, 3};
  pair.source_match = {0, 1, 2, pcl_crf::kNoMatch};
  pair.objects.push_back ({0, true, pcl_crf::makeRigid2d (-0.1, 0.0, 0.0), "world"});
  pair.objects.push_back ({3, false, pcl_crf::makeRigid2d (0.5, 0.1, 0.05), "car"});
  pair.odometry.T_source_target = pcl_crf::makeRigid2d (0.1, 0.001, 0.002);
  pair.odometry.covariance = Eigen::Vector3d (1e-4, 2e-4, 3e-5).asDiagonal ();
  return pair;
}

/** The small pair's target scan (x y z label, 3 points) as a PCD of \a encoding
 *  ("binary" or "binary_compressed") whose header declares \a declared points, with
 *  the first \a stored points in its body. The compressed body is LZF of literal runs
 *  only (valid LZF, as any reader unpacks it), fields one after another as PCL stores
 *  them; \a unpacked_size overrides the size it says it unpacks to (< 0: the true one). */
std::string
targetPcd (const std::string& encoding, int declared, int stored, long long unpacked_size = -1)
{
  const ScanPair pair = makeSmallPair ();
  std::string fields[4];  // x, y, z, label of every stored point
  for (int i = 0; i < stored; ++i) {
    const float x = static_cast<float> (pair.target (0, i)), y = static_cast<float> (pair.target (1, i)), z = 0.0f;
    const auto label = static_cast<std::uint32_t> (pair.target_object[i]);
    fields[0].append (reinterpret_cast<const char*> (&x), 4);
    fields[1].append (reinterpret_cast<const char*> (&y), 4);
    fields[2].append (reinterpret_cast<const char*> (&z), 4);
    fields[3].append (reinterpret_cast<const char*> (&label), 4);
  }
  std::string body;
  if (encoding == "binary") {
    for (int i = 0; i < stored; ++i)
      for (const std::string& field : fields)
        body += field.substr (4 * i, 4);
  }
  else {
    const std::string unpacked = fields[0] + fields[1] + fields[2] + fields[3];
    std::string packed;
    for (std::size_t at = 0; at < unpacked.size (); at += 32) {
      const std::string run = unpacked.substr (at, 32);
      packed += static_cast<char> (run.size () - 1);
      packed += run;
    }
    const auto packed_size = static_cast<std::uint32_t> (packed.size ());
    const auto unpacked_bytes = static_cast<std::uint32_t> (unpacked_size < 0 ? unpacked.size () : unpacked_size);
    body.append (reinterpret_cast<const char*> (&packed_size), 4);
    body.append (reinterpret_cast<const char*> (&unpacked_bytes), 4);
    body += packed;
  }
  const std::string count = std::to_string (declared);
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z label\nSIZE 4 4 4 4\n"
         "TYPE F F F U\nCOUNT 1 1 1 1\nWIDTH " + count + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + count +
         "\nDATA " + encoding + "\n" + body;
}

class DatasetIo : public ::testing::Test
{
protected:
  void
  SetUp () override
  {
    dir_ = fs::temp_directory_path () /
           ("pcl_crf_io_" + std::string (::testing::UnitTest::GetInstance ()->current_test_info ()->name ()));
    fs::remove_all (dir_);
  }
  void
  TearDown () override
  {
    fs::remove_all (dir_);
  }

  std::string
  writeSmallPair ()
  {
    pcl_crf::saveScanPair (makeSmallPair (), (dir_ / "pair_0000").string ());
    return (dir_ / "pair_0000").string ();
  }


  void
  expectLoadError (const std::string& pair_dir, const std::string& fragment)
  {
    try {
      pcl_crf::loadScanPair (pair_dir);
      FAIL () << "expected a DatasetError containing '" << fragment << "'";
    }
    catch (const DatasetError& error) {
      EXPECT_NE (std::string (error.what ()).find (fragment), std::string::npos) << error.what ();
    }
  }

  fs::path dir_;
};

TEST_F (DatasetIo, RoundTripKeepsEveryField)
{
  const ScanPair original = makeSmallPair ();
  const ScanPair loaded = pcl_crf::loadScanPair (writeSmallPair ());
  EXPECT_EQ (loaded.name, "pair_0000");
  EXPECT_EQ (loaded.sensor.beam_count, 5);
  EXPECT_DOUBLE_EQ (loaded.sensor.angle_min, original.sensor.angle_min);
  EXPECT_DOUBLE_EQ (loaded.sensor.angle_increment, original.sensor.angle_increment);
  EXPECT_DOUBLE_EQ (loaded.sensor.range_max, 30.0);
  EXPECT_TRUE (loaded.source.isApprox (original.source, 1e-7));
  EXPECT_TRUE (loaded.target.isApprox (original.target, 1e-7));
  EXPECT_EQ (loaded.source_object, original.source_object);
  EXPECT_EQ (loaded.target_object, original.target_object);
  EXPECT_EQ (loaded.source_match, original.source_match);
  ASSERT_EQ (loaded.objects.size (), 2u);
  EXPECT_EQ (loaded.objects[1].id, 3);
  EXPECT_FALSE (loaded.objects[1].is_static);
  EXPECT_EQ (loaded.objects[1].kind, "car");
  EXPECT_TRUE (loaded.objects[1].T_target_source.isApprox (original.objects[1].T_target_source, 1e-15));
  EXPECT_TRUE (loaded.odometry.T_source_target.isApprox (original.odometry.T_source_target, 1e-15));
  EXPECT_TRUE (loaded.odometry.covariance.isApprox (original.odometry.covariance, 1e-15));
}

TEST_F (DatasetIo, WritingTwiceGivesIdenticalBytes)
{
  const std::string first = writeSmallPair ();
  std::ifstream a (fs::path (first) / "source.pcd");
  std::stringstream sa;
  sa << a.rdbuf ();
  pcl_crf::saveScanPair (makeSmallPair (), (dir_ / "again").string ());
  std::ifstream b (dir_ / "again" / "source.pcd");
  std::stringstream sb;
  sb << b.rdbuf ();
  EXPECT_EQ (sa.str (), sb.str ());
}

TEST_F (DatasetIo, DatasetListsPairsInSortedOrder)
{
  ScanPair pair = makeSmallPair ();
  pair.name = "b";
  ScanPair other = makeSmallPair ();
  other.name = "a";
  pcl_crf::saveDataset ({pair, other}, dir_.string ());
  const auto pairs = pcl_crf::loadDataset (dir_.string ());
  ASSERT_EQ (pairs.size (), 2u);
  EXPECT_EQ (pairs[0].name, "a");
  EXPECT_EQ (pairs[1].name, "b");
}

TEST_F (DatasetIo, MissingDatasetFolderIsAnError)
{
  EXPECT_THROW (pcl_crf::loadDataset ((dir_ / "nowhere").string ()), DatasetError);
  fs::create_directories (dir_);
  EXPECT_THROW (pcl_crf::loadDataset (dir_.string ()), DatasetError);
}

TEST_F (DatasetIo, MissingFilesAreNamed)
{
  const std::string pair_dir = writeSmallPair ();
  fs::remove (fs::path (pair_dir) / "target.pcd");
  expectLoadError (pair_dir, "target.pcd: file not found");
  fs::remove (fs::path (pair_dir) / "pair.txt");
  expectLoadError (pair_dir, "pair.txt");
}

TEST_F (DatasetIo, CorruptPcdIsAnError)
{
  const std::string pair_dir = writeSmallPair ();
  std::ofstream (fs::path (pair_dir) / "source.pcd") << "this is not a point cloud\n";
  expectLoadError (pair_dir, "source.pcd");
}

TEST_F (DatasetIo, TruncatedPcdIsAnError)
{
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "target.pcd", "POINTS 3", "POINTS 30");
  replaceInFile (fs::path (pair_dir) / "target.pcd", "WIDTH 3", "WIDTH 30");
  expectLoadError (pair_dir, "target.pcd");
}

TEST_F (DatasetIo, AsciiRowsBeyondTheDeclaredPointsAreAnError)
{
  // PCL's reader takes the first POINTS rows and drops the rest without a word.
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "target.pcd", "POINTS 3", "POINTS 2");
  replaceInFile (fs::path (pair_dir) / "target.pcd", "WIDTH 3", "WIDTH 2");
  expectLoadError (pair_dir, "target.pcd: the header declares 2 points (WIDTH x HEIGHT, POINTS), the ascii data hold 3");
}

TEST_F (DatasetIo, AsciiValuesAreDecimalNumbersOfTheirField)
{
  // pcl_crf reads ascii bodies itself: PCL's reader parses in the global C++ locale (under
  // a German one "-9.28" read as -9) and took "3x" as 3, "0x1" as 0 and "3,5" as 3.
  const std::string pair_dir = writeSmallPair ();
  const ScanPair expected = pcl_crf::loadScanPair (pair_dir);
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  const std::string row = "3.0999999 -0.5 0 3";
  for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
           {"3.0999999 -0.5 0 3x", "point 2 has label '3x', not a decimal number of its TYPE U SIZE 4 COUNT 1"},
           {"3.0999999 -0.5 0 3.5", "point 2 has label '3.5', not a whole number in [0, 4294967295] (its TYPE U SIZE 4"},
           {"3.0999999 -0.5 0 -1", "point 2 has label '-1', not a whole number in [0, 4294967295] (its TYPE U SIZE 4"},
           {"3.0999999 -0.5 0 nan", "point 2 has label 'nan'"},
           {"0x1 -0.5 0 3", "point 2 has x '0x1', not a decimal number of its TYPE F SIZE 4"},
           {"3,0999999 -0.5 0 3", "point 2 has x '3,0999999'"},
           {"3.0999999 -0.5 0", "point 2 has 3 values, the header's fields take 4"}}) {
    replaceInFile (target, row, bad);
    expectLoadError (pair_dir, "target.pcd: " + message);
    replaceInFile (target, bad, row);
  }
  // Blank lines, '#' lines and tabs in the body, as PCL's reader takes them.
  replaceInFile (target, row, "\n# a comment\n3.0999999\t-0.5 0  3\r");
  const ScanPair spaced = pcl_crf::loadScanPair (pair_dir);
  EXPECT_EQ (spaced.target, expected.target);
  EXPECT_EQ (spaced.target_object, expected.target_object);
}

TEST_F (DatasetIo, APointCountNoFileOfItsSizeHoldsIsAnErrorBeforeAllocating)
{
  // PCL's readHeader () allocates the declared cloud: 4e9 points failed with a bare
  // std::bad_alloc, 4e8 took 7.8 GB before the data were found short.
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "target.pcd", "POINTS 3", "POINTS 400000000");
  replaceInFile (fs::path (pair_dir) / "target.pcd", "WIDTH 3", "WIDTH 400000000");
  expectLoadError (pair_dir, "target.pcd: the header declares 400000000 points, more than a file of");
}

TEST_F (DatasetIo, APcdHeaderIsCheckedBeforePclReadsIt)
{
  // Found by fuzzing the reader: PCL's readHeader () reads these words into unsigned
  // integers and allocates from them, or indexes a missing DATA word.
  const std::string pair_dir = writeSmallPair ();
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      // WIDTH x HEIGHT wrapped to 0 in 32 bits: a segmentation fault in pcl::fromPCLPointCloud2
      {"WIDTH 3\nHEIGHT 1", "WIDTH -2147483648\nHEIGHT -2147483648",
       "WIDTH must be one whole number from 0 to 2147483647, not '-2147483648'"},
      {"POINTS 3", "POINTS -1", "POINTS must be one whole number from 0 to 2147483647, not '-1'"},  // std::length_error
      // PCL's reader refused it as an unreadable header, naming nothing
      {"POINTS 3", "POINTS 2", "POINTS 2 is not WIDTH x HEIGHT = 3 x 1"},
      // a negative SIZE corrupted the heap; overlapping fields read y as 0
      {"SIZE 4 4 4 4", "SIZE 4 4 -4 4", "field 'z' has SIZE -4 and TYPE F"},
      {"SIZE 4 4 4 4", "SIZE 4 4 4 3", "field 'label' has SIZE 3 and TYPE U"},
      {"TYPE F F F U", "TYPE F F F X", "field 'label' has SIZE 4 and TYPE X"},
      {"COUNT 1 1 1 1", "COUNT 1 1 -326 1", "field 'z' has COUNT -326"},  // std::bad_alloc
      {"COUNT 1 1 1 1", "COUNT 1 1 150000000 1", "field 'z' has COUNT 150000000"},  // 1.2 GB, 6 s
      {"COUNT 1 1 1 1", "COUNT 1 1 1", "FIELDS names 4 fields, SIZE gives 4 sizes, TYPE 4 types, COUNT 3 counts"},
      {"DATA ascii", "DATA", "the DATA line must name one of ascii, binary, binary_compressed"},  // std::out_of_range
  };
  for (const auto& [from, to, message] : cases) {
    replaceInFile (target, from, to);
    expectLoadError (pair_dir, "target.pcd: PCD header: " + message);
    replaceInFile (target, to, from);
  }
  // A label stored as uint64 beyond its range wrapped to 0.
  replaceInFile (target, "SIZE 4 4 4 4", "SIZE 4 4 4 8");
  replaceInFile (target, "3.0999999 -0.5 0 3", "3.0999999 -0.5 0 18446744073709551615");
  expectLoadError (pair_dir, "target.pcd: point 2 has label '18446744073709551615', not a whole number in [0, "
                            "18446744073709551615] (its TYPE U SIZE 8");
  replaceInFile (target, "3.0999999 -0.5 0 18446744073709551615", "3.0999999 -0.5 0 3");
  EXPECT_EQ (pcl_crf::loadScanPair (pair_dir).target_object.back (), 3);  // the same label as uint64 reads
}

TEST_F (DatasetIo, BinaryBodiesAreReadWhenTheyHoldTheDeclaredPoints)
{
  const std::string pair_dir = writeSmallPair ();
  const ScanPair expected = pcl_crf::loadScanPair (pair_dir);
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  for (const std::string encoding : {"binary", "binary_compressed"}) {
    std::ofstream (target, std::ios::binary) << targetPcd (encoding, 3, 3);
    const ScanPair read = pcl_crf::loadScanPair (pair_dir);
    EXPECT_EQ (read.target, expected.target) << encoding;
    EXPECT_EQ (read.target_object, expected.target_object) << encoding;
  }
}

TEST_F (DatasetIo, ABinaryBodyOfAnotherSizeIsAnError)
{
  // PCL read past the end of a short body, and dropped a longer one's extra points.
  const std::string pair_dir = writeSmallPair ();
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  std::ofstream (target, std::ios::binary) << targetPcd ("binary", 3, 2);
  expectLoadError (pair_dir, "target.pcd: the header declares 3 points (WIDTH x HEIGHT, POINTS) of 16 bytes, the "
                             "binary data hold 32 bytes");
  std::ofstream (target, std::ios::binary) << targetPcd ("binary", 2, 3);
  expectLoadError (pair_dir, "target.pcd: the header declares 2 points (WIDTH x HEIGHT, POINTS) of 16 bytes, the "
                             "binary data hold 48 bytes");
}

TEST_F (DatasetIo, ACompressedBodyThatDisagreesWithItsHeaderIsAnError)
{
  // PCL warned "Data corruption?" and then crashed (SIGSEGV) on these.
  const std::string pair_dir = writeSmallPair ();
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  std::ofstream (target, std::ios::binary) << targetPcd ("binary_compressed", 3, 3, 0);
  expectLoadError (pair_dir, "target.pcd: the header declares 3 points (WIDTH x HEIGHT, POINTS) of 16 bytes, the "
                             "binary_compressed data unpack to 0 bytes");
  std::ofstream (target, std::ios::binary) << targetPcd ("binary_compressed", 30, 3);
  expectLoadError (pair_dir, "the binary_compressed data unpack to 48 bytes");
  std::string truncated = targetPcd ("binary_compressed", 3, 3);
  truncated.resize (truncated.size () - 5);
  std::ofstream (target, std::ios::binary) << truncated;
  expectLoadError (pair_dir, "target.pcd: the binary_compressed data are truncated");
  // Sizes that agree with the header, but no LZF stream that short unpacks that far.
  std::ofstream (target, std::ios::binary) << targetPcd ("binary_compressed", 1000, 3, 16000);
  expectLoadError (pair_dir, "compressed bytes cannot unpack to the 16000 bytes declared");
}

TEST_F (DatasetIo, MissingMatchFieldIsNamed)
{
  const std::string pair_dir = writeSmallPair ();
  fs::copy_file (fs::path (pair_dir) / "target.pcd", fs::path (pair_dir) / "source.pcd",
                 fs::copy_options::overwrite_existing);
  expectLoadError (pair_dir, "missing field 'match'");
}

TEST_F (DatasetIo, FieldOfAnotherCountIsNamed)
{
  // PCL's conversion leaves a field it cannot map at 0 without a word.
  const std::string pair_dir = writeSmallPair ();
  const fs::path source = fs::path (pair_dir) / "source.pcd";
  replaceInFile (source, "COUNT 1 1 1 1 1", "COUNT 1 2 1 1 1");
  expectLoadError (pair_dir, "source.pcd: field 'y' must be TYPE F SIZE 4 COUNT 1 (or another TYPE and SIZE of COUNT 1), "
                             "found TYPE F SIZE 4 COUNT 2");
  // PCL's reader drops a field of COUNT 0 from its header: the field is there, not missing.
  replaceInFile (source, "COUNT 1 2 1 1 1", "COUNT 1 0 1 1 1");
  expectLoadError (pair_dir, "source.pcd: field 'y' has COUNT 0, must be 1");
}

TEST_F (DatasetIo, FieldsOfAnotherTypeOrSizeAreConverted)
{
  // A PCD writer may store x and y as float64 or the labels as int32 or float; the
  // reader converts them (PCL's conversion used to give zeros, pcl_crf then refused them).
  const std::string pair_dir = writeSmallPair ();
  const ScanPair expected = pcl_crf::loadScanPair (pair_dir);
  const fs::path source = fs::path (pair_dir) / "source.pcd";
  const fs::path target = fs::path (pair_dir) / "target.pcd";
  replaceInFile (source, "SIZE 4 4 4 4 4", "SIZE 8 8 4 4 2");
  replaceInFile (source, "TYPE F F F U I", "TYPE F F F I I");
  replaceInFile (target, "TYPE F F F U", "TYPE F F F F");
  const ScanPair converted = pcl_crf::loadScanPair (pair_dir);
  EXPECT_EQ (converted.source, expected.source.cast<float> ().cast<double> ());
  EXPECT_EQ (converted.target, expected.target.cast<float> ().cast<double> ());
  EXPECT_EQ (converted.source_object, expected.source_object);
  EXPECT_EQ (converted.source_match, expected.source_match);
  EXPECT_EQ (converted.target_object, expected.target_object);
  // A label that is not a whole number, or a negative one, is named with its point.
  replaceInFile (target, "3.0999999 -0.5 0 3", "3.0999999 -0.5 0 3.5");
  expectLoadError (pair_dir, "target.pcd: point 2 has label 3.5, not a whole number in [0, 4294967295]");
  replaceInFile (target, "3.0999999 -0.5 0 3.5", "3.0999999 -0.5 0 -3");
  expectLoadError (pair_dir, "target.pcd: point 2 has label -3, not a whole number in [0, 4294967295]");
}

TEST_F (DatasetIo, MatchOutOfRangeIsAnError)
{
  ScanPair pair = makeSmallPair ();
  pair.source_match[1] = 7;
  EXPECT_THROW (pcl_crf::saveScanPair (pair, (dir_ / "bad").string ()), DatasetError);
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "source.pcd", "4 1.5 0 3 -1", "4 1.5 0 3 9");
  expectLoadError (pair_dir, "out of range");
}

TEST_F (DatasetIo, NanCoordinateIsAnError)
{
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "target.pcd", "2.0999999 0.25", "nan 0.25");
  expectLoadError (pair_dir, "NaN");
  ScanPair pair = makeSmallPair ();
  pair.source (0, 2) = std::numeric_limits<double>::infinity ();
  EXPECT_THROW (pcl_crf::saveScanPair (pair, (dir_ / "bad").string ()), DatasetError);
}

TEST_F (DatasetIo, CoordinatesAndMotionsBeyond1e18MetresAreErrors)
{
  // Finite, but their squares overflow PCL's floats: the evaluation printed inf errors.
  const auto message = [] (const ScanPair& pair) -> std::string {
    try {
      pcl_crf::validateScanPair (pair, "x");
    }
    catch (const DatasetError& error) {
      return error.what ();
    }
    return "";
  };
  EXPECT_EQ (message (makeSmallPair ()), "");
  ScanPair pair = makeSmallPair ();
  pair.objects[0].T_target_source.translation ().x () = 1e300;
  EXPECT_NE (message (pair).find ("object " + std::to_string (pair.objects[0].id) + " moves beyond 1e18 m"),
             std::string::npos);
  pair = makeSmallPair ();
  pair.target (1, 2) = -2e18;
  EXPECT_NE (message (pair).find ("target point 2 has a coordinate beyond 1e18 m"), std::string::npos);
  pair = makeSmallPair ();
  pair.odometry.T_source_target.translation ().y () = 1e19;
  EXPECT_NE (message (pair).find ("odometry translation beyond 1e18 m"), std::string::npos);
}

TEST_F (DatasetIo, InconsistentSizesAreErrors)
{
  ScanPair pair = makeSmallPair ();
  pair.source_object.pop_back ();
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
  pair = makeSmallPair ();
  pair.source_match.push_back (0);
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
  pair = makeSmallPair ();
  pair.sensor.beam_count = 2;
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
}

TEST_F (DatasetIo, AbsurdBeamCountIsAnError)
{
  // A corrupt beam count made the cbd method allocate gigabytes.
  ScanPair pair = makeSmallPair ();
  pair.sensor.beam_count = pcl_crf::kMaxBeamCount;
  EXPECT_NO_THROW (pcl_crf::validateScanPair (pair, "x"));
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "pair.txt", "sensor 5 ", "sensor 1000000000 ");
  expectLoadError (pair_dir, "pair.txt:2: beam count must be a whole number in [1, 100000], not 1000000000");
}

TEST_F (DatasetIo, EmptyScanIsAnError)
{
  ScanPair pair = makeSmallPair ();
  pair.target.resize (2, 0);
  pair.target_object.clear ();
  pair.source_match.assign (4, pcl_crf::kNoMatch);
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
}

TEST_F (DatasetIo, UndeclaredObjectIdIsAnError)
{
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "pair.txt", "object 3 moving", "object 4 moving");
  expectLoadError (pair_dir, "object id 3 that no object line declares");
}

TEST_F (DatasetIo, PairTextErrorsNameTheLine)
{
  // Each edit of pair.txt, the error it raises (naming the line, and a number's
  // documented range), then the edit undone.
  const std::string pair_dir = writeSmallPair ();
  const fs::path text = fs::path (pair_dir) / "pair.txt";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"sensor 5", "sensor five", "pair.txt:2: 'five' is not a finite decimal number"},
      {"sensor 5 ", "sensor 5.5 ", "pair.txt:2: beam count must be a whole number in [1, 100000], not 5.5"},
      {"pcl_crf_pair 1", "pcl_crf_pair 9", "unsupported format version"},
      {"odometry_covariance", "odometry_variance", "unknown key 'odometry_variance'"},
      {"object 0 static", "object 0 moving", "exactly one object must be the static world"},
      {"object 3 moving", "object -3 moving", "pair.txt:6: object id must be a whole number in [0, 2147483647], not -3"},
      // a missing line has no line number (the odometry line, not its covariance's)
      {"odometry ", "# odometry ", "pair.txt: missing 'odometry' line"}};
  for (const auto& [from, to, message] : cases) {
    replaceInFile (text, from, to);
    expectLoadError (pair_dir, message);
    replaceInFile (text, to, from);
  }
  EXPECT_NO_THROW (pcl_crf::loadScanPair (pair_dir));
}

TEST_F (DatasetIo, AKeyGivenTwiceIsAnError)
{
  // The last of two odometry lines used to win without a word (a 139 m ego error).
  const std::string pair_dir = writeSmallPair ();
  const fs::path text = fs::path (pair_dir) / "pair.txt";
  for (const std::string key : {"sensor", "odometry", "odometry_covariance", "pcl_crf_pair"}) {
    const std::string original = [&text] {
      std::ifstream in (text);
      std::stringstream buffer;
      buffer << in.rdbuf ();
      return buffer.str ();
    }();
    const std::string lines = "\n" + original;  // every line, the first one too, after a newline
    const auto begin = lines.find ("\n" + key + " ") + 1;
    const std::string line = lines.substr (begin, lines.find ('\n', begin) - begin + 1);
    std::ofstream (text) << original << line;
    expectLoadError (pair_dir, "'" + key + "' given twice");
    std::ofstream (text) << original;
  }
  EXPECT_NO_THROW (pcl_crf::loadScanPair (pair_dir));
}

TEST_F (DatasetIo, NumbersInPairTextAreFiniteDecimals)
{
  // strtod read "0x10" as 16; a decimal comma is what a German locale would have written.
  const std::string pair_dir = writeSmallPair ();
  const fs::path text = fs::path (pair_dir) / "pair.txt";
  const std::string odometry = "odometry 0.10000000000000001";
  for (const std::string bad : {"nan", "0x10", "0,10000000000000001", "-inf"}) {
    replaceInFile (text, odometry, "odometry " + bad);
    expectLoadError (pair_dir, "pair.txt:3: '" + bad + "' is not a finite decimal number");
    replaceInFile (text, "odometry " + bad, odometry);
  }
  replaceInFile (text, odometry, "odometry +0.10000000000000001");
  EXPECT_NEAR (pcl_crf::loadScanPair (pair_dir).odometry.T_source_target.translation ().x (), 0.1, 1e-15);
}

TEST_F (DatasetIo, ObjectIdsUpToTheLargestIntAreRead)
{
  // A converter may number objects by large track ids: up to 2147483647 they are read
  // (a label above it used to wrap to a negative id; 1e9 used to be the bound).
  ScanPair pair = makeSmallPair ();
  pair.objects[1].id = 2147483647;
  for (std::vector<int>* labels : {&pair.source_object, &pair.target_object})
    std::replace (labels->begin (), labels->end (), 3, 2147483647);
  pcl_crf::saveScanPair (pair, (dir_ / "large").string ());
  EXPECT_EQ (pcl_crf::loadScanPair ((dir_ / "large").string ()).target_object.back (), 2147483647);
  const std::string pair_dir = writeSmallPair ();
  replaceInFile (fs::path (pair_dir) / "target.pcd", "3.0999999 -0.5 0 3", "3.0999999 -0.5 0 3000000000");
  expectLoadError (pair_dir, "target.pcd: point 2 has label 3000000000, beyond the largest object id 2147483647");
  replaceInFile (fs::path (pair_dir) / "pair.txt", "object 3 moving", "object 3000000000 moving");
  expectLoadError (pair_dir, "pair.txt:6: object id must be a whole number in [0, 2147483647], not 3000000000");
}

TEST_F (DatasetIo, ScanIntervalIsOptionalAndPositive)
{
  ScanPair pair = makeSmallPair ();  // interval unknown: no line
  pcl_crf::saveScanPair (pair, (dir_ / "unknown").string ());
  std::ifstream unknown_text (dir_ / "unknown" / "pair.txt");
  std::stringstream unknown;
  unknown << unknown_text.rdbuf ();
  EXPECT_EQ (unknown.str ().find ("interval"), std::string::npos);
  EXPECT_EQ (pcl_crf::loadScanPair ((dir_ / "unknown").string ()).odometry.interval, 0.0);
  pair.odometry.interval = 0.08;
  pcl_crf::saveScanPair (pair, (dir_ / "known").string ());
  EXPECT_EQ (pcl_crf::loadScanPair ((dir_ / "known").string ()).odometry.interval, 0.08);  // exact: %.17g
  replaceInFile (dir_ / "known" / "pair.txt", "interval 0.080000000000000002", "interval 0");
  expectLoadError ((dir_ / "known").string (), "pair.txt:5: the interval between the scans must be > 0 s");
  replaceInFile (dir_ / "known" / "pair.txt", "interval 0", "interval 0.1\ninterval 0.2");
  expectLoadError ((dir_ / "known").string (), "pair.txt:6: 'interval' given twice");
  pair.odometry.interval = -0.1;
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
  pair.odometry.interval = std::numeric_limits<double>::quiet_NaN ();
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
}

TEST_F (DatasetIo, BadCovarianceIsAnError)
{
  ScanPair pair = makeSmallPair ();
  pair.odometry.covariance (0, 0) = 0.0;
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
  pair = makeSmallPair ();
  pair.odometry.covariance (0, 1) = 1e-3;
  EXPECT_THROW (pcl_crf::validateScanPair (pair, "x"), DatasetError);
}

}  // namespace
