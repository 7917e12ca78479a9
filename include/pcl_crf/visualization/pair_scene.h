#pragma once
// What pcl_crf_viewer draws for one scan pair, computed without VTK (header-only,
// so it can be tested and reused by other front ends).

#include <pcl_crf/core/prediction.h>
#include <pcl_crf/core/scan_pair.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace pcl_crf {
namespace visualization {

/** \brief An 8-bit RGB colour. */
struct Rgb
{
  std::uint8_t r = 0, g = 0, b = 0;
};

/** \brief Colours of the viewer (white background, as in the papers' figures). */
struct ScenePalette
{
  Rgb background{255, 255, 255};
  /** static-world points of the source / target scan (dimmed). */
  Rgb static_source{236, 160, 160};
  Rgb static_target{150, 178, 232};
  /** points a method put in no cluster (outliers). */
  Rgb outlier{0, 0, 0};
  /** association lines of static-world points. */
  Rgb static_line{205, 205, 205};
  Rgb text{20, 20, 20};

  /** \brief Colour of the k-th moving cluster (k >= 0; cycles through 10 colours). */
  static Rgb
  moving (std::size_t k)
  {
    static const Rgb colours[] = {{0, 158, 115}, {230, 140, 0},  {150, 70, 190}, {204, 80, 150}, {0, 150, 160},
                                  {150, 100, 40}, {120, 130, 0}, {210, 0, 210},  {40, 110, 40},  {190, 160, 0}};
    return colours[k % 10];
  }

  /** \brief \a c mixed with white: amount 0 keeps it, 1 gives white. */
  static Rgb
  lighter (const Rgb& c, double amount = 0.45)
  {
    const auto mix = [amount] (std::uint8_t v) { return static_cast<std::uint8_t> (v + (255 - v) * amount); };
    return {mix (c.r), mix (c.g), mix (c.b)};
  }
};

/** \brief One cluster (object) as drawn: its points, box, motion arrow and legend line. */
struct SceneCluster
{
  /** the cluster label (prediction) or object id (truth). */
  int id = 0;
  bool is_static = false;
  Rgb colour;
  /** legend text, e.g. "#2 car: 35 pts, moved 1.21 m, 3.4 deg". */
  std::string legend;
  /** indices of its source points. */
  std::vector<int> source_indices;
  /** its motion T_target_source. */
  Rigid2d motion = Rigid2d::Identity ();
  /** oriented box around its source points in the display frame (4 corners, in order). */
  std::vector<Eigen::Vector2d> box;
  /** motion arrow in the display frame: from the centroid at the source time to
   *  where the cluster's motion moves it at the target time. */
  Eigen::Vector2d arrow_from = Eigen::Vector2d::Zero (), arrow_to = Eigen::Vector2d::Zero ();
  /** how far it moved in the world between the scans [m] and turned [rad]. */
  double displacement = 0.0, rotation = 0.0;
};

/** \brief Everything the viewer draws for one pair, in the display frame = the
 *  target sensor frame (the source scan is moved there by the static world's motion).
 */
struct PairScene
{
  std::string title;
  Eigen::Matrix2Xd source;  // display frame
  std::vector<Rgb> source_colours;
  Eigen::Matrix2Xd target;
  std::vector<Rgb> target_colours;
  /** (source index, target index) of every association line, with its colour. */
  std::vector<std::pair<int, int>> lines;
  std::vector<Rgb> line_colours;
  std::vector<SceneCluster> clusters;
  /** the source sensor's pose in the display frame (the target sensor is the origin). */
  Rigid2d source_sensor = Rigid2d::Identity ();
  /** size of the scene: the larger side of the box around all points [m]. */
  double extent = 1.0;
  /** legend lines below the title (the static world and every moving cluster). */
  std::vector<std::string> legend;
  std::vector<Rgb> legend_colours;
};

namespace detail {

constexpr double kDegreesPerRadian = 57.295779513082323;

/** Degrees for the legend, without a "-0.0". */
inline double
degrees (double radians)
{
  const double d = radians * kDegreesPerRadian;
  return std::abs (d) < 0.05 ? 0.0 : d;
}

/** Metres for the legend, without a "-0.00". */
inline double
metres (double value)
{
  return std::abs (value) < 0.005 ? 0.0 : value;
}

/** Oriented box (principal axes) around points, grown by \a margin [m]. */
inline std::vector<Eigen::Vector2d>
orientedBox (const Eigen::Matrix2Xd& points, double margin)
{
  const Eigen::Vector2d mean = points.rowwise ().mean ();
  const Eigen::Matrix2Xd centred = points.colwise () - mean;
  const Eigen::Matrix2d covariance = centred * centred.transpose ();
  const double angle = 0.5 * std::atan2 (2.0 * covariance (0, 1), covariance (0, 0) - covariance (1, 1));
  const Eigen::Matrix2d R = Eigen::Rotation2Dd (angle).toRotationMatrix ();
  const Eigen::Matrix2Xd local = R.transpose () * centred;
  const Eigen::Vector2d lo = local.rowwise ().minCoeff ().array () - margin;
  const Eigen::Vector2d hi = local.rowwise ().maxCoeff ().array () + margin;
  return {mean + R * lo, mean + R * Eigen::Vector2d (hi.x (), lo.y ()), mean + R * hi,
          mean + R * Eigen::Vector2d (lo.x (), hi.y ())};
}

/** The generic form of truth and predictions the scene is built from. */
struct SceneInput
{
  std::vector<int> source_cluster;  // index into motions, or -1
  std::vector<int> target_cluster;  // may be empty
  std::vector<int> source_match;    // may be empty
  std::vector<Rigid2d> motions;
  std::vector<std::string> kinds;
  std::vector<int> ids;
  int static_cluster = -1;
  Rigid2d display_from_source = Rigid2d::Identity ();
};

inline PairScene
buildScene (const ScanPair& pair, const SceneInput& in, const std::string& title,
            const ScenePalette& palette = {})
{
  PairScene scene;
  scene.title = title;
  scene.source_sensor = in.display_from_source;
  scene.source = in.display_from_source * pair.source;
  scene.target = pair.target;
  if (scene.source.cols () > 0 && scene.target.cols () > 0) {
    const Eigen::Vector2d lo = scene.source.rowwise ().minCoeff ().cwiseMin (scene.target.rowwise ().minCoeff ());
    const Eigen::Vector2d hi = scene.source.rowwise ().maxCoeff ().cwiseMax (scene.target.rowwise ().maxCoeff ());
    scene.extent = std::max (1.0, (hi - lo).maxCoeff ());
  }
  // boxes grow with the scene so that small objects stay visible: 0.15 m or 1.5 % of it.
  const double box_margin = std::max (0.15, 0.015 * scene.extent);
  // colours: static world dimmed, moving clusters each their own colour.
  std::vector<Rgb> cluster_colour (in.motions.size (), palette.static_source);
  std::size_t moving_count = 0;
  for (std::size_t c = 0; c < in.motions.size (); ++c)
    if (static_cast<int> (c) != in.static_cluster)
      cluster_colour[c] = ScenePalette::moving (moving_count++);
  const auto source_colour = [&] (int c) {
    if (c < 0)
      return in.static_cluster < 0 && in.motions.empty () ? palette.static_source : palette.outlier;
    return c == in.static_cluster ? palette.static_source : cluster_colour[c];
  };
  for (Eigen::Index i = 0; i < pair.source.cols (); ++i)
    scene.source_colours.push_back (source_colour (in.source_cluster.empty () ? -1 : in.source_cluster[i]));
  // (the callers check that labels and matches fit the pair: validatePrediction, validateScanPair)
  std::vector<int> target_cluster = in.target_cluster;
  if (target_cluster.empty ()) {
    // Predictions label no target point: take the cluster of the source points matching it.
    target_cluster.assign (pair.target.cols (), -1);
    for (std::size_t i = 0; i < in.source_match.size () && i < in.source_cluster.size (); ++i)
      if (in.source_match[i] >= 0 && in.source_cluster[i] >= 0 && in.source_cluster[i] != in.static_cluster)
        target_cluster[in.source_match[i]] = in.source_cluster[i];
  }
  for (Eigen::Index j = 0; j < pair.target.cols (); ++j) {
    const int c = target_cluster[j];
    scene.target_colours.push_back (c < 0 || c == in.static_cluster ? palette.static_target
                                                                    : ScenePalette::lighter (cluster_colour[c]));
  }
  for (std::size_t i = 0; i < in.source_match.size (); ++i)
    if (in.source_match[i] >= 0) {
      const int c = in.source_cluster.empty () ? -1 : in.source_cluster[i];
      scene.lines.emplace_back (static_cast<int> (i), in.source_match[i]);
      scene.line_colours.push_back (c < 0 || c == in.static_cluster ? palette.static_line
                                                                    : ScenePalette::lighter (cluster_colour[c], 0.2));
    }
  // clusters: box, arrow and legend.
  const Rigid2d world = in.display_from_source;
  for (std::size_t c = 0; c < in.motions.size (); ++c) {
    SceneCluster cluster;
    cluster.id = in.ids[c];
    cluster.is_static = static_cast<int> (c) == in.static_cluster;
    cluster.colour = cluster.is_static ? palette.static_source : cluster_colour[c];
    cluster.motion = in.motions[c];
    for (std::size_t i = 0; i < in.source_cluster.size (); ++i)
      if (in.source_cluster[i] == static_cast<int> (c))
        cluster.source_indices.push_back (static_cast<int> (i));
    char text[160];
    if (cluster.is_static) {
      const Eigen::Vector3d ego = toXYTheta (in.motions[c].inverse ());
      std::snprintf (text, sizeof (text), "#%d %s: %zu pts, ego motion %.2f m, %.1f deg", cluster.id,
                     in.kinds[c].c_str (), cluster.source_indices.size (), metres (ego.head<2> ().norm ()),
                     degrees (ego.z ()));
      cluster.legend = text;
      scene.clusters.push_back (cluster);
      continue;
    }
    if (cluster.source_indices.empty ())
      continue;
    Eigen::Matrix2Xd points (2, cluster.source_indices.size ());
    for (std::size_t k = 0; k < cluster.source_indices.size (); ++k)
      points.col (k) = pair.source.col (cluster.source_indices[k]);
    const Eigen::Vector2d centroid = points.rowwise ().mean ();
    cluster.box = orientedBox (world * points, box_margin);
    cluster.arrow_from = world * centroid;
    cluster.arrow_to = in.motions[c] * centroid;
    cluster.displacement = (cluster.arrow_to - cluster.arrow_from).norm ();
    cluster.rotation = rotationAngle (world.inverse () * in.motions[c]);
    std::snprintf (text, sizeof (text), "#%d %s: %zu pts, moved %.2f m, %.1f deg", cluster.id, in.kinds[c].c_str (),
                   cluster.source_indices.size (), metres (cluster.displacement), degrees (cluster.rotation));
    cluster.legend = text;
    scene.clusters.push_back (cluster);
  }
  std::stable_sort (scene.clusters.begin (), scene.clusters.end (),
                    [] (const SceneCluster& a, const SceneCluster& b) { return a.is_static && !b.is_static; });
  for (const auto& cluster : scene.clusters) {
    scene.legend.push_back (cluster.legend);
    scene.legend_colours.push_back (cluster.is_static ? palette.text : cluster.colour);
  }
  return scene;
}

}  // namespace detail

/** \brief Checks that a prediction fits a pair (sizes and indices), truth or not.
 *  \param[out] problem what is wrong, when it returns false */
inline bool
predictionFitsPair (const ScanPair& pair, const Prediction& prediction, std::string& problem)
{
  const std::size_t n = static_cast<std::size_t> (pair.source.cols ());
  const int clusters = static_cast<int> (prediction.cluster_motions.size ());
  if (!prediction.source_match.empty () && prediction.source_match.size () != n)
    problem = "it has " + std::to_string (prediction.source_match.size ()) + " matches for " + std::to_string (n) +
              " source points";
  else if (!prediction.source_cluster.empty () && prediction.source_cluster.size () != n)
    problem = "it has " + std::to_string (prediction.source_cluster.size ()) + " cluster labels for " +
              std::to_string (n) + " source points";
  else if (prediction.static_cluster >= clusters)
    problem = "its static cluster " + std::to_string (prediction.static_cluster) + " does not exist";
  else {
    for (int m : prediction.source_match)
      if (m < kNoMatch || m >= pair.target.cols ())
        problem = "match " + std::to_string (m) + " is not a target point";
    for (int c : prediction.source_cluster)
      if (c < kOutlierCluster || c >= clusters)
        problem = "cluster label " + std::to_string (c) + " has no motion";
  }
  return problem.empty ();
}

/** \brief The scene of a pair's ground truth: objects as clusters, true
 *  associations as lines, the source scan moved by the true static-world motion.
 *  An unlabelled pair (no labels, ScanPair::hasTruth () false) shows its scans
 *  aligned by the reference motion if it has one, else by the odometry.
 */
inline PairScene
makeTruthScene (const ScanPair& pair, const ScenePalette& palette = {})
{
  detail::SceneInput in;
  for (const auto& object : pair.objects) {
    in.motions.push_back (object.T_target_source);
    in.kinds.push_back (object.kind);
    in.ids.push_back (object.id);
    if (object.is_static)
      in.static_cluster = static_cast<int> (in.motions.size ()) - 1;
  }
  in.display_from_source = in.static_cluster >= 0 ? in.motions[in.static_cluster]
                                                  : Rigid2d (pair.odometry.T_source_target.inverse ());
  const bool labelled = pair.hasTruth ();
  if (labelled) {
    for (int id : pair.source_object)
      in.source_cluster.push_back (pair.objectIndex (id));
    for (int id : pair.target_object)
      in.target_cluster.push_back (pair.objectIndex (id));
    in.source_match = pair.source_match;
  }
  else if (in.static_cluster >= 0) {
    in.source_cluster.assign (pair.source.cols (), in.static_cluster);
    in.target_cluster.assign (pair.target.cols (), in.static_cluster);
  }
  std::string title = pair.name + ": " + (labelled ? "ground truth" : in.static_cluster >= 0
                                                                          ? "reference motion (unlabelled)"
                                                                          : "odometry (no reference)");
  return detail::buildScene (pair, in, title, palette);
}

/** \brief The scene of a method's prediction: its clusters, associations and
 *  the source scan moved by its static cluster's motion (or its ego motion).
 */
inline PairScene
makePredictionScene (const ScanPair& pair, const Prediction& prediction, const std::string& method,
                     const ScenePalette& palette = {})
{
  detail::SceneInput in;
  in.motions = prediction.cluster_motions;
  for (std::size_t c = 0; c < in.motions.size (); ++c) {
    in.ids.push_back (static_cast<int> (c));
    in.kinds.push_back (static_cast<int> (c) == prediction.static_cluster ? "static" : "moving");
  }
  in.static_cluster = prediction.static_cluster;
  in.source_cluster = prediction.source_cluster;
  in.source_match = prediction.source_match;
  in.display_from_source = in.static_cluster >= 0 && in.static_cluster < static_cast<int> (in.motions.size ())
                               ? in.motions[in.static_cluster]
                               : Rigid2d (prediction.T_source_target.inverse ());
  char timing[48];
  std::snprintf (timing, sizeof (timing), " (%.3f s)", prediction.seconds);
  return detail::buildScene (pair, in, pair.name + ": " + method + timing, palette);
}

}  // namespace visualization
}  // namespace pcl_crf
