// SPDX-License-Identifier: BSD-3-Clause
#include "csmScreenCache.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

csmScreenCache::Mode csmScreenCache::Begin(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  bool asLastFrame, int lights, bool enabled, const std::string& key)
{
  this->Current = OFF;
  this->CurrentRenderer = renderer;
  int viewport[4] = { 0, 0, 0, 0 };
  renderer->GetTiledSizeAndOrigin(viewport + 2, viewport + 3, viewport, viewport + 1);
  // A multisampled framebuffer shades a pixel once for the samples of several surfaces: one
  // factor a pixel would give the samples of one surface another's.
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  if (!enabled || lights < 1 || lights > MAXIMUM_LIGHTS || samples > 1 || viewport[2] < 1 ||
    viewport[3] < 1 || !(GLEW_VERSION_4_2 || GLEW_ARB_shader_image_load_store))
  {
    return OFF;
  }
  const bool holds = this->Renderer == renderer && this->Image &&
    std::equal(viewport, viewport + 4, this->Viewport) && this->Key == key;
  if (!this->Image)
  {
    this->Image = vtkSmartPointer<vtkTextureObject>::New();
  }
  this->Image->SetContext(window);
  if (static_cast<int>(this->Image->GetWidth()) != viewport[2] ||
    static_cast<int>(this->Image->GetHeight()) != viewport[3] || !this->Image->GetHandle())
  {
    this->Image->Allocate2D(viewport[2], viewport[3], 4, VTK_FLOAT);
  }
  if (!this->Image->GetHandle())
  {
    return OFF;
  }
  this->Current = holds && asLastFrame ? READ : STORE;
  std::copy(viewport, viewport + 4, this->Viewport);
  glBindImageTexture(static_cast<GLuint>(this->GetImageUnit()), this->Image->GetHandle(), 0,
    GL_FALSE, 0, this->Current == READ ? GL_READ_ONLY : GL_WRITE_ONLY, GL_RGBA32F);
  if (this->Current == STORE)
  {
    // Until the frame is drawn, the image holds no frame's factors.
    this->Renderer = nullptr;
    this->Key = key;
  }
  return this->Current;
}

bool csmScreenCache::End()
{
  if (this->Current == OFF)
  {
    if (this->Renderer == this->CurrentRenderer)
    {
      this->Renderer = nullptr; // this renderer's last frame is not the image's
    }
    return false;
  }
  glBindImageTexture(
    static_cast<GLuint>(this->GetImageUnit()), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  if (this->Current == STORE)
  {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    this->Renderer = this->CurrentRenderer;
  }
  this->Current = OFF;
  return true;
}

void csmScreenCache::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Image)
  {
    this->Image->ReleaseGraphicsResources(window);
  }
  this->Renderer = nullptr;
}
