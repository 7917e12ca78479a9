#include "headless.h"

#include <vtkImageData.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <unistd.h>
#include <vector>

namespace pcl_crf {
namespace visualization {
namespace {

constexpr const char* kGuard = "PCL_CRF_VIEWER_UNDER_XVFB";

/** Full path of an executable found on PATH, or "". */
std::string
findOnPath (const std::string& name)
{
  const char* path = std::getenv ("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= dirs.size ()) {
    const std::size_t end = std::min (dirs.find (':', begin), dirs.size ());
    const std::filesystem::path candidate = std::filesystem::path (dirs.substr (begin, end - begin)) / name;
    if (access (candidate.c_str (), X_OK) == 0)
      return candidate.string ();
    begin = end + 1;
  }
  return "";
}

}  // namespace

bool
hasDisplay ()
{
  const char* display = std::getenv ("DISPLAY");
  return display && *display;
}

bool
runningUnderOurXvfb ()
{
  return std::getenv (kGuard) != nullptr;
}

void
reexecUnderXvfb (int argc, char** argv, int width, int height, std::string& problem)
{
  if (runningUnderOurXvfb ()) {
    problem = "xvfb-run started, but no X display is set";
    return;
  }
  const std::string xvfb_run = findOnPath ("xvfb-run");
  if (xvfb_run.empty ()) {
    problem = "no X display (DISPLAY is unset) and no xvfb-run to make one: install Debian's xvfb and xauth "
              "packages, or run under an X server";
    return;
  }
  std::error_code error;
  const std::string self = std::filesystem::read_symlink ("/proc/self/exe", error).string ();
  const std::string screen = "-screen 0 " + std::to_string (width) + "x" + std::to_string (height) +
                             "x24 -nolisten tcp";
  // -a finds a free display; starting the search at a number derived from the
  // process id keeps parallel runs (ctest -j) from racing for the same one.
  const std::string first_display = std::to_string (100 + getpid () % 400);
  std::vector<std::string> words = {xvfb_run, "-a", "-n", first_display, "-s", screen,
                                    error ? std::string (argv[0]) : self};
  for (int i = 1; i < argc; ++i)
    words.emplace_back (argv[i]);
  std::vector<char*> args;
  for (auto& word : words)
    args.push_back (word.data ());
  args.push_back (nullptr);
  setenv (kGuard, "1", 1);
  execv (xvfb_run.c_str (), args.data ());
  problem = std::string ("cannot run ") + xvfb_run + ": " + std::strerror (errno);
}

bool
writeScreenshot (vtkRenderWindow* window, const std::string& path, const unsigned char background[3],
                 ScreenshotStats& stats)
{
  window->Render ();
  auto grabber = vtkSmartPointer<vtkWindowToImageFilter>::New ();
  grabber->SetInput (window);
  grabber->SetInputBufferTypeToRGB ();
  grabber->ReadFrontBufferOff ();
  grabber->Update ();
  vtkImageData* image = grabber->GetOutput ();
  int dims[3];
  image->GetDimensions (dims);
  stats = {};
  stats.width = dims[0];
  stats.height = dims[1];
  const auto* pixels = static_cast<const unsigned char*> (image->GetScalarPointer ());
  const int components = image->GetNumberOfScalarComponents ();
  std::set<std::uint32_t> colours;
  for (long i = 0; pixels && i < static_cast<long> (dims[0]) * dims[1]; ++i) {
    const unsigned char* p = pixels + i * components;
    colours.insert ((std::uint32_t (p[0]) << 16) | (std::uint32_t (p[1]) << 8) | p[2]);
    if (p[0] != background[0] || p[1] != background[1] || p[2] != background[2])
      ++stats.foreground_pixels;
  }
  stats.distinct_colours = static_cast<long> (colours.size ());
  auto writer = vtkSmartPointer<vtkPNGWriter>::New ();
  writer->SetFileName (path.c_str ());
  writer->SetInputConnection (grabber->GetOutputPort ());
  writer->Write ();
  return writer->GetErrorCode () == 0 && std::filesystem::is_regular_file (path);
}

}  // namespace visualization
}  // namespace pcl_crf
