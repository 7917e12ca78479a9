#pragma once
// Screenshots without a display: re-running the viewer under xvfb-run, and
// writing the render window to a PNG file.

#include <string>

class vtkRenderWindow;

namespace pcl_crf {
namespace visualization {

/** \brief true when an X display is set (DISPLAY is not empty). */
bool
hasDisplay ();

/** \brief true when this process was started by reexecUnderXvfb. */
bool
runningUnderOurXvfb ();

/** \brief Replaces this process by "xvfb-run -a -n N -s '-screen 0 WxHx24' <this program> <args>"
 *  (a virtual X server for headless machines: Debian package xvfb). Returns
 *  only when that is impossible, with the reason in \a problem.
 */
void
reexecUnderXvfb (int argc, char** argv, int width, int height, std::string& problem);

/** \brief What a screenshot shows: its size, how many pixels differ from the
 *  background and how many distinct colours it has. */
struct ScreenshotStats
{
  int width = 0, height = 0;
  long foreground_pixels = 0;
  long distinct_colours = 0;
};

/** \brief Renders \a window and writes it as a PNG file.
 *  \param[in] background the background colour (r, g, b in 0..255) for the statistics
 *  \return false when the file cannot be written. */
bool
writeScreenshot (vtkRenderWindow* window, const std::string& path, const unsigned char background[3],
                 ScreenshotStats& stats);

}  // namespace visualization
}  // namespace pcl_crf
