// SPDX-License-Identifier: BSD-3-Clause
#include "csmTestHelpers.h"

#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtk_glew.h"

#include <cstdlib>

namespace csmTest
{
namespace
{
vtkUnsignedCharArray* Pixels(vtkImageData* image)
{
  return image ? vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars()) : nullptr;
}
} // namespace

vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window, bool rerender)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->SetShouldRerender(rerender);
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

long DarkenedPixels(
  vtkImageData* shadowed, vtkImageData* plain, const std::vector<char>* mask, long* maskPixels)
{
  vtkUnsignedCharArray* a = Pixels(shadowed);
  vtkUnsignedCharArray* b = Pixels(plain);
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
    (mask && static_cast<vtkIdType>(mask->size()) != a->GetNumberOfTuples()))
  {
    return -1;
  }
  const int nc = a->GetNumberOfComponents();
  long count = 0, inMask = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    if (mask && !(*mask)[i])
    {
      continue;
    }
    ++inMask;
    double la = 0, lb = 0;
    for (int c = 0; c < 3 && c < nc; ++c)
    {
      la += a->GetValue(nc * i + c);
      lb += b->GetValue(nc * i + c);
    }
    count += IsDarkened(la, lb);
  }
  if (maskPixels)
  {
    *maskPixels = inMask;
  }
  return count;
}

long DifferingValues(vtkImageData* a, vtkImageData* b, int tolerance)
{
  vtkUnsignedCharArray* pa = Pixels(a);
  vtkUnsignedCharArray* pb = Pixels(b);
  if (!pa || !pb || pa->GetNumberOfValues() != pb->GetNumberOfValues())
  {
    return -1;
  }
  long count = 0;
  for (vtkIdType i = 0; i < pa->GetNumberOfValues(); ++i)
  {
    count += std::abs(int(pa->GetValue(i)) - int(pb->GetValue(i))) > tolerance;
  }
  return count;
}

long DifferingPixels(vtkImageData* a, vtkImageData* b, int tolerance)
{
  vtkUnsignedCharArray* pa = Pixels(a);
  vtkUnsignedCharArray* pb = Pixels(b);
  if (!pa || !pb || pa->GetNumberOfValues() != pb->GetNumberOfValues() ||
    pa->GetNumberOfComponents() != pb->GetNumberOfComponents())
  {
    return -1;
  }
  const int nc = pa->GetNumberOfComponents();
  long count = 0;
  for (vtkIdType i = 0; i < pa->GetNumberOfTuples(); ++i)
  {
    bool off = false;
    for (int c = 0; c < 3 && c < nc; ++c)
    {
      off =
        off || std::abs(int(pa->GetValue(nc * i + c)) - int(pb->GetValue(nc * i + c))) > tolerance;
    }
    count += off;
  }
  return count;
}

vtkSmartPointer<vtkActor> SegmentsActor(
  const std::vector<std::array<double, 6>>& segments, float pixels, bool tubes)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  for (const auto& s : segments)
  {
    const vtkIdType ids[2] = { points->InsertNextPoint(s.data()),
      points->InsertNextPoint(s.data() + 3) };
    lines->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetLineWidth(pixels);
  actor->GetProperty()->SetRenderLinesAsTubes(tubes);
  return actor;
}

vtkSmartPointer<vtkActor> GroundPlane(double halfWidth, int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-halfWidth, 0.0, -halfWidth);
  plane->SetPoint1(halfWidth, 0.0, -halfWidth);
  plane->SetPoint2(-halfWidth, 0.0, halfWidth);
  plane->SetResolution(resolution, resolution);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

vtkSmartPointer<vtkActor> BoxActor(
  double xmin, double xmax, double ymin, double ymax, double zmin, double zmax)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(xmin, xmax, ymin, ymax, zmin, zmax);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

BoxOverPlane::BoxOverPlane(int width, int height)
  : BoxOverPlane(
      [width, height]()
      {
        BoxOverPlaneSettings settings;
        settings.Size[0] = width;
        settings.Size[1] = height;
        return settings;
      }())
{
}

BoxOverPlane::BoxOverPlane(const BoxOverPlaneSettings& s)
{
  this->Ground->SetMapper(GroundPlane(s.GroundHalfWidth, s.GroundResolution)->GetMapper());
  this->Ground->GetProperty()->SetColor(s.GroundColor[0], s.GroundColor[1], s.GroundColor[2]);
  this->Box->SetMapper(
    BoxActor(s.Box[0], s.Box[1], s.Box[2], s.Box[3], s.Box[4], s.Box[5])->GetMapper());
  this->Box->GetProperty()->SetColor(s.BoxColor[0], s.BoxColor[1], s.BoxColor[2]);
  this->Renderer->AddActor(this->Ground);
  this->Renderer->AddActor(this->Box);
  this->Renderer->SetBackground(s.Background[0], s.Background[1], s.Background[2]);
  this->Renderer->AutomaticLightCreationOff();
  this->Light->SetLightTypeToSceneLight();
  this->Light->SetPositional(false);
  this->Light->SetPosition(s.LightPosition[0], s.LightPosition[1], s.LightPosition[2]);
  this->Light->SetFocalPoint(0, 0, 0);
  this->Renderer->AddLight(this->Light);
  this->Window->SetSize(s.Size[0], s.Size[1]);
  this->Window->SetMultiSamples(0);
  this->Window->SetOffScreenRendering(1);
  this->Window->AddRenderer(this->Renderer);
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  camera->SetPosition(s.CameraPosition[0], s.CameraPosition[1], s.CameraPosition[2]);
  camera->SetFocalPoint(s.CameraFocalPoint[0], s.CameraFocalPoint[1], s.CameraFocalPoint[2]);
  camera->SetViewUp(0, 1, 0);
  this->Renderer->ResetCameraClippingRange();
}

void BoxOverPlane::AddBlockBehindTheCamera()
{
  vtkNew<vtkCubeSource> behind, front;
  behind->SetBounds(-1, 1, 13, 15, 18, 20);
  front->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(behind->GetOutputPort());
  both->AddInputConnection(front->GetOutputPort());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(both->GetOutputPort());
  this->Box->SetMapper(mapper);
  this->Renderer->ResetCameraClippingRange();
}

namespace
{
std::vector<float> ReadAtlas(vtkRenderWindow* window, vtkTextureObject* atlas)
{
  window->MakeCurrent();
  std::vector<float> all(static_cast<size_t>(atlas->GetWidth()) * atlas->GetHeight());
  atlas->Bind();
  glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, all.data());
  atlas->Deactivate();
  return all;
}

std::vector<float> TileOf(const std::vector<float>& all, int width, int height,
  const vtkCascadedShadowMapBakerPass::CascadeMap& map)
{
  // The map fills the lower left of its tile.
  const int x = map.Tile[0], y = map.Tile[1], w = map.Resolution[0], h = map.Resolution[1];
  if (x + w > width || y + h > height)
  {
    return {};
  }
  std::vector<float> tile;
  for (int row = y; row < y + h; ++row)
  {
    tile.insert(tile.end(), all.begin() + static_cast<size_t>(row) * width + x,
      all.begin() + static_cast<size_t>(row) * width + x + w);
  }
  return tile;
}
} // namespace

std::vector<float> CascadeDepths(
  vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c)
{
  vtkTextureObject* atlas = maps.Atlas;
  return TileOf(ReadAtlas(window, atlas), static_cast<int>(atlas->GetWidth()),
    static_cast<int>(atlas->GetHeight()), maps.Cascades[c]);
}

std::vector<std::vector<float>> AllCascadeDepths(
  vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps)
{
  vtkTextureObject* atlas = maps.Atlas;
  const std::vector<float> all = ReadAtlas(window, atlas);
  std::vector<std::vector<float>> tiles;
  for (const auto& map : maps.Cascades)
  {
    tiles.push_back(
      TileOf(all, static_cast<int>(atlas->GetWidth()), static_cast<int>(atlas->GetHeight()), map));
  }
  return tiles;
}

} // namespace csmTest
