// SPDX-License-Identifier: BSD-3-Clause
// Drawing light-space pages (vtkCascadedShadowMapBakerPass's internal part; csmPages.h): the
// pages a frame needs anew into their slots of the light's atlas, and the page table the lookup
// reads.
#ifndef csmPageDrawing_h
#define csmPageDrawing_h

#include "vtkCascadedShadowMapTypes.h" // for LightMaps, FrameStatistics

#include <cstddef>

class csmMapDrawing;
class vtkOpenGLRenderWindow;
class vtkOpenGLRenderer;
struct csmFrameCasters;
struct csmRendererMaps;

namespace csmPageDrawing
{
/// Draws maps.Pages.Drawn (the atlas bound for drawing, its depth state set): a block of 4 x 4
/// pages of a level at a time (csm::batchPages, a pass costing its triangles whatever it covers;
/// the block's own clip space, so that a page's texels are the same whichever pages come with
/// it) into a scratch of scratchSide texels a side, each page then copied to its slot; one pass a
/// page straight into its slot where the GL cannot copy images (GL 4.3). Returns the props drawn.
int DrawPages(csmMapDrawing& drawing, vtkOpenGLRenderer* renderer, vtkOpenGLRenderWindow* window,
  csmRendererMaps& state, const csmFrameCasters& props, vtkCascadedShadows::LightMaps& maps,
  int scratchSide, bool depthClamp, vtkCascadedShadows::FrameStatistics& statistics);

/// The page table of a paged light as a float RGBA texture (its entries are small integers), a
/// level's window of csm::kPageTableSide entries a side above the one before: maps.Pages's
/// TableTexture, kept in the renderer's pool per light slot.
void UploadPageTable(vtkOpenGLRenderWindow* window, csmRendererMaps& state, std::size_t slot,
  vtkCascadedShadows::LightMaps& maps);
}

#endif
