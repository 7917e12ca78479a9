#pragma once
// Draws a pcl_crf::visualization::PairScene into a PCLVisualizer viewport.

#include <pcl_crf/visualization/pair_scene.h>

#include <pcl/visualization/pcl_visualizer.h>

#include <string>
#include <vector>

namespace pcl_crf {
namespace visualization {

/** \brief How a scene is drawn. */
struct RenderOptions
{
  /** draw the association lines (default true). */
  bool lines = true;
  /** point sizes of the source / target scan [pixels] (default 6 and 3: the
   *  target is drawn on top, so both show where they overlap). */
  double source_point_size = 6.0;
  double target_point_size = 3.0;
  /** width of boxes, arrows and sensor marks [pixels] (default 3). */
  double shape_line_width = 3.0;
  /** font size of the title / legend [points] (default 16 / 13). */
  int title_font_size = 16;
  int legend_font_size = 13;
};

/** \brief Adds the scene's clouds, lines, boxes, arrows and legend to \a viewport.
 *  \param[in] window_height the window height [pixels] (the legend hangs from the top)
 *  \param[in] x_offset left edge of the viewport [pixels] (for text placement)
 */
void
drawScene (pcl::visualization::PCLVisualizer& viewer, const PairScene& scene, int viewport,
           const std::string& prefix, const RenderOptions& options, int window_height, int x_offset);

/** \brief Height of the title and legend drawScene puts at the top [pixels]. */
int
legendHeight (const PairScene& scene, const RenderOptions& options);

/** \brief Looks straight down on the scenes (parallel projection, x right, y up)
 *  so that every point of every scene fits a viewport of width x height pixels
 *  below a top band of \a top_margin pixels (the legend).
 */
void
fitTopDownCamera (pcl::visualization::PCLVisualizer& viewer, const std::vector<PairScene>& scenes, int width,
                  int height, int top_margin);

}  // namespace visualization
}  // namespace pcl_crf
