#include "pair_renderer.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

namespace pcl_crf {
namespace visualization {
namespace {

// Drawing order in the top-down view: lines below points below shapes.
constexpr double kLineZ = -0.02, kSourceZ = 0.0, kTargetZ = 0.01, kShapeZ = 0.03;

/** Line segments with one colour each, as one VTK poly data (one actor). */
class SegmentBatch
{
public:
  SegmentBatch ()
  {
    colours_->SetNumberOfComponents (3);
    colours_->SetName ("Colors");
  }

  void
  add (const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z, const Rgb& c)
  {
    const vtkIdType ia = points_->InsertNextPoint (a.x (), a.y (), z);
    const vtkIdType ib = points_->InsertNextPoint (b.x (), b.y (), z);
    const unsigned char rgb[3] = {c.r, c.g, c.b};
    colours_->InsertNextTypedTuple (rgb);
    colours_->InsertNextTypedTuple (rgb);
    const vtkIdType ids[2] = {ia, ib};
    cells_->InsertNextCell (2, ids);
  }

  void
  addPolygon (const std::vector<Eigen::Vector2d>& corners, double z, const Rgb& c)
  {
    for (std::size_t k = 0; k < corners.size (); ++k)
      add (corners[k], corners[(k + 1) % corners.size ()], z, c);
  }

  void
  addArrow (const Eigen::Vector2d& from, const Eigen::Vector2d& to, double z, const Rgb& c, double head)
  {
    const Eigen::Vector2d d = to - from;
    const double length = d.norm ();
    add (from, to, z, c);
    if (length < 1e-6)
      return;
    head = std::min (head, 0.6 * length);
    const Eigen::Vector2d u = d / length, n (-u.y (), u.x ());
    add (to, to - head * u + 0.5 * head * n, z, c);
    add (to, to - head * u - 0.5 * head * n, z, c);
  }

  bool
  empty () const
  {
    return cells_->GetNumberOfCells () == 0;
  }

  vtkSmartPointer<vtkPolyData>
  polyData () const
  {
    auto data = vtkSmartPointer<vtkPolyData>::New ();
    data->SetPoints (points_);
    data->SetLines (cells_);
    data->GetPointData ()->SetScalars (colours_);
    return data;
  }

private:
  vtkSmartPointer<vtkPoints> points_ = vtkSmartPointer<vtkPoints>::New ();
  vtkSmartPointer<vtkCellArray> cells_ = vtkSmartPointer<vtkCellArray>::New ();
  vtkSmartPointer<vtkUnsignedCharArray> colours_ = vtkSmartPointer<vtkUnsignedCharArray>::New ();
};

pcl::PointCloud<pcl::PointXYZRGB>::Ptr
toCloud (const Eigen::Matrix2Xd& points, const std::vector<Rgb>& colours, double z)
{
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud (new pcl::PointCloud<pcl::PointXYZRGB>);
  for (Eigen::Index i = 0; i < points.cols (); ++i) {
    const Rgb& c = colours[i];
    pcl::PointXYZRGB p (c.r, c.g, c.b);
    p.x = static_cast<float> (points (0, i));
    p.y = static_cast<float> (points (1, i));
    p.z = static_cast<float> (z);
    cloud->push_back (p);
  }
  return cloud;
}

void
addCloud (pcl::visualization::PCLVisualizer& viewer, const pcl::PointCloud<pcl::PointXYZRGB>::Ptr& cloud,
          const std::string& id, double size, int viewport)
{
  if (cloud->empty ())
    return;
  pcl::visualization::PointCloudColorHandlerRGBField<pcl::PointXYZRGB> colours (cloud);
  viewer.addPointCloud<pcl::PointXYZRGB> (cloud, colours, id, viewport);
  viewer.setPointCloudRenderingProperties (pcl::visualization::PCL_VISUALIZER_POINT_SIZE, size, id, viewport);
}

void
addSegments (pcl::visualization::PCLVisualizer& viewer, const SegmentBatch& batch, const std::string& id,
             double width, int viewport)
{
  if (batch.empty ())
    return;
  viewer.addModelFromPolyData (batch.polyData (), id, viewport);
  viewer.setShapeRenderingProperties (pcl::visualization::PCL_VISUALIZER_LINE_WIDTH, width, id, viewport);
}

/** A small triangle at a sensor pose, pointing forward (+x), \a size metres long. */
std::vector<Eigen::Vector2d>
sensorMark (const Rigid2d& pose, double size)
{
  return {pose * Eigen::Vector2d (0.6 * size, 0.0), pose * Eigen::Vector2d (-0.4 * size, 0.35 * size),
          pose * Eigen::Vector2d (-0.4 * size, -0.35 * size)};
}

double
unit (std::uint8_t v)
{
  return v / 255.0;
}

}  // namespace

void
drawScene (pcl::visualization::PCLVisualizer& viewer, const PairScene& scene, int viewport,
           const std::string& prefix, const RenderOptions& options, int window_height, int x_offset)
{
  if (options.lines) {
    SegmentBatch lines;
    for (std::size_t k = 0; k < scene.lines.size (); ++k)
      lines.add (scene.source.col (scene.lines[k].first), scene.target.col (scene.lines[k].second), kLineZ,
                 scene.line_colours[k]);
    addSegments (viewer, lines, prefix + "lines", 1.0, viewport);
  }
  addCloud (viewer, toCloud (scene.target, scene.target_colours, kTargetZ), prefix + "target",
            options.target_point_size, viewport);
  addCloud (viewer, toCloud (scene.source, scene.source_colours, kSourceZ), prefix + "source",
            options.source_point_size, viewport);

  SegmentBatch shapes;
  for (const auto& cluster : scene.clusters) {
    if (cluster.is_static || cluster.box.empty ())
      continue;
    shapes.addPolygon (cluster.box, kShapeZ, cluster.colour);
    shapes.addArrow (cluster.arrow_from, cluster.arrow_to, kShapeZ, cluster.colour, 0.02 * scene.extent);
  }
  const Rgb sensor_target{60, 90, 170}, sensor_source{190, 70, 70};
  const double mark = std::max (0.5, 0.02 * scene.extent);
  shapes.addPolygon (sensorMark (Rigid2d::Identity (), mark), kShapeZ, sensor_target);
  shapes.addPolygon (sensorMark (scene.source_sensor, mark), kShapeZ, sensor_source);
  addSegments (viewer, shapes, prefix + "shapes", options.shape_line_width, viewport);

  const ScenePalette palette;
  int y = window_height - 10 - options.title_font_size;
  viewer.addText (scene.title, x_offset + 10, y, options.title_font_size, unit (palette.text.r),
                  unit (palette.text.g), unit (palette.text.b), prefix + "title", viewport);
  y -= options.title_font_size / 2 + 4;
  const auto line = [&] (const std::string& text, const Rgb& c, const std::string& id) {
    y -= options.legend_font_size + 4;
    viewer.addText (text, x_offset + 14, y, options.legend_font_size, unit (c.r), unit (c.g), unit (c.b), id,
                    viewport);
  };
  line ("source scan (earlier)  " + std::to_string (scene.source.cols ()) + " pts", Rgb{200, 80, 80},
        prefix + "legend_source");
  line ("target scan (later)  " + std::to_string (scene.target.cols ()) + " pts", Rgb{60, 90, 190},
        prefix + "legend_target");
  for (std::size_t k = 0; k < scene.legend.size (); ++k)
    line (scene.legend[k], scene.legend_colours[k], prefix + "legend_" + std::to_string (k));
}

int
legendHeight (const PairScene& scene, const RenderOptions& options)
{
  // as laid out by drawScene: title, a gap, then the two scan lines and the legend lines
  return 10 + options.title_font_size + options.title_font_size / 2 + 4 +
         static_cast<int> (2 + scene.legend.size ()) * (options.legend_font_size + 4) + 14;
}

void
fitTopDownCamera (pcl::visualization::PCLVisualizer& viewer, const std::vector<PairScene>& scenes, int width,
                  int height, int top_margin)
{
  Eigen::Vector2d lo = Eigen::Vector2d::Constant (-1.0), hi = Eigen::Vector2d::Constant (1.0);
  for (const auto& scene : scenes)
    for (const Eigen::Matrix2Xd* points : {&scene.source, &scene.target})
      if (points->cols () > 0) {
        lo = lo.cwiseMin (points->rowwise ().minCoeff ());
        hi = hi.cwiseMax (points->rowwise ().maxCoeff ());
      }
  constexpr int kBorder = 12;  // pixels left free around the points
  const int free_height = std::max (50, height - top_margin - kBorder);
  const Eigen::Vector2d size = (hi - lo).cwiseMax (Eigen::Vector2d::Constant (1e-3));
  const double pixels_per_metre =
      std::min (free_height / size.y (), std::max (50, width - 2 * kBorder) / size.x ());
  // the points' centre goes to the middle of the free band below the legend
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const double centre_pixel = kBorder + 0.5 * free_height;
  const double focal_y = centre.y () + (0.5 * height - centre_pixel) / pixels_per_metre;
  vtkRenderer* first = viewer.getRendererCollection ()->GetFirstRenderer ();
  vtkCamera* camera = first->GetActiveCamera ();
  camera->ParallelProjectionOn ();
  camera->SetFocalPoint (centre.x (), focal_y, 0.0);
  camera->SetPosition (centre.x (), focal_y, 100.0);
  camera->SetViewUp (0.0, 1.0, 0.0);
  camera->SetParallelScale (0.5 * height / pixels_per_metre);
  camera->SetClippingRange (1.0, 200.0);
}

}  // namespace visualization
}  // namespace pcl_crf
