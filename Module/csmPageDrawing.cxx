// SPDX-License-Identifier: BSD-3-Clause
#include "csmPageDrawing.h"

#include "csmBakerState.h"
#include "csmMapDrawing.h"
#include "csmPages.h"
#include "csmVTKMath.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <array>
#include <vector>

using vtkCascadedShadows::CascadeMap;
using vtkCascadedShadows::FrameStatistics;
using vtkCascadedShadows::LightMaps;

namespace
{
/// The scratch bound for drawing: a depth texture of the atlas's format, side texels a side, in a
/// framebuffer of its own; false where it cannot serve (no image copies, a GL error).
bool bindScratch(vtkOpenGLRenderWindow* window, csmRendererMaps& state, int side)
{
  if (!(GLEW_VERSION_4_3 || GLEW_ARB_copy_image) || side < csm::kPageTexels)
  {
    return false;
  }
  if (!state.PageScratch)
  {
    state.PageScratch = vtkSmartPointer<vtkTextureObject>::New();
    state.PageFrameBuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  }
  vtkTextureObject* scratch = state.PageScratch;
  if (scratch->GetContext() != window || static_cast<int>(scratch->GetWidth()) != side ||
    !scratch->GetHandle())
  {
    scratch->ReleaseGraphicsResources(window);
    scratch->SetContext(window);
    if (!scratch->AllocateDepth(side, side, vtkTextureObject::Float32))
    {
      return false;
    }
  }
  state.PageFrameBuffer->SetContext(window);
  state.PageFrameBuffer->Bind();
  state.PageFrameBuffer->AddDepthAttachment(scratch);
  state.PageFrameBuffer->DeactivateDrawBuffers();
  state.PageFrameBuffer->DeactivateReadBuffer();
  if (state.PageFrameBuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
  {
    state.FrameBuffer->Bind();
    return false;
  }
  return true;
}
} // namespace

int csmPageDrawing::DrawPages(csmMapDrawing& drawing, vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  LightMaps& maps, int scratchSide, bool depthClamp, FrameStatistics& statistics)
{
  // The pages a view brings in together drawn in one pass a block (a caster pass costs its
  // triangles whatever it covers; a block's clip space whatever pages come with it, so that a
  // page's texels are too) into the scratch, then copied to their slots; one pass a page
  // straight into its slot where the GL cannot copy images.
  const vtkCascadedShadows::LightPages& pages = maps.Pages;
  int drawn = 0;
  if (pages.Drawn.empty() || maps.Cascades.size() != 1)
  {
    return drawn;
  }
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(pages.BaseTexels[0], pages.BaseTexels[1]);
  levels.baseDepth = pages.BaseDepth;
  levels.count = pages.Levels;
  const glm::dmat4 wsToBase = csmFromRowMajor(maps.Cascades[0].WorldToMap);
  LightMaps one = maps;
  one.Pages = vtkCascadedShadows::LightPages();
  auto draw = [&](vtkOpenGLFramebufferObject* frameBuffer, const glm::dmat4& clip, int x, int y,
                const glm::ivec2& size, const std::array<int, 4>& area)
  {
    one.Atlas = frameBuffer == state.FrameBuffer ? maps.Atlas : state.PageScratch;
    CascadeMap& map = one.Cascades[0];
    map.Tile[0] = x;
    map.Tile[1] = y;
    map.Tile[2] = map.Resolution[0] = size.x;
    map.Tile[3] = map.Resolution[1] = size.y;
    csmToRowMajor(clip, map.WorldToMap);
    csmMapDrawing::ClearMap(window->GetState(), one, 0, area.data());
    drawn += drawing.DrawCascade(
      renderer, frameBuffer, one, 0, props, depthClamp, false, statistics, area.data());
    glFlush();
  };
  std::vector<csm::PageKey> keys;
  for (const auto& page : pages.Drawn)
  {
    keys.push_back(csm::PageKey{ page[0], page[1], page[2] });
  }
  const int side = scratchSide;
  if (!bindScratch(window, state, side))
  {
    for (size_t i = 0; i < keys.size(); ++i)
    {
      draw(state.FrameBuffer, csm::pageClip(wsToBase, levels, keys[i]), pages.Drawn[i][3],
        pages.Drawn[i][4], glm::ivec2(csm::kPageTexels),
        { 0, 0, csm::kPageTexels, csm::kPageTexels });
    }
    return drawn;
  }
  for (const csm::PageBatch& batch :
    csm::batchPages(keys, (side - 2 * csm::kPageBorder) / csm::kPageInterior))
  {
    draw(state.PageFrameBuffer,
      csm::pagesClip(wsToBase, levels, batch.level, batch.first, batch.last), 0, 0, batch.texels(),
      batch.drawn());
    for (const size_t i : batch.pages)
    {
      const glm::ivec2 from = (glm::ivec2(keys[i].x, keys[i].y) - batch.first) * csm::kPageInterior;
      csmMapDrawing::CopyTexels(state.PageScratch, from.x, from.y, maps.Atlas, pages.Drawn[i][3],
        pages.Drawn[i][4], csm::kPageTexels, csm::kPageTexels);
    }
  }
  state.FrameBuffer->Bind();
  return drawn;
}

void csmPageDrawing::UploadPageTable(
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, size_t slot, LightMaps& maps)
{
  // The table as a float texture (its entries are small integers), a level's window of
  // kPageTableSide entries a side above the one before.
  if (!maps.Pages.Active || maps.Pages.Table.empty())
  {
    return;
  }
  if (state.PageTablePool.size() <= slot)
  {
    state.PageTablePool.resize(slot + 1);
  }
  vtkSmartPointer<vtkTextureObject>& table = state.PageTablePool[slot];
  if (!table)
  {
    table = vtkSmartPointer<vtkTextureObject>::New();
  }
  table->SetContext(window);
  table->SetMinificationFilter(vtkTextureObject::Nearest);
  table->SetMagnificationFilter(vtkTextureObject::Nearest);
  const int side = csm::kPageTableSide;
  const int rows = static_cast<int>(maps.Pages.Table.size() / (4 * static_cast<size_t>(side)));
  table->Create2DFromRaw(side, rows, 4, VTK_FLOAT, maps.Pages.Table.data());
  maps.Pages.TableTexture = table;
}
