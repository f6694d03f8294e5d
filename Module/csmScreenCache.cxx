// SPDX-License-Identifier: BSD-3-Clause
#include "csmScreenCache.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

csmScreenCache::csmScreenCache() = default;
csmScreenCache::~csmScreenCache() = default;

bool csmScreenCache::Compiles(
  vtkOpenGLRenderWindow* window, const std::function<bool(int)>& compiles)
{
  this->Probes.erase(std::remove_if(this->Probes.begin(), this->Probes.end(),
                       [](const Probe& probe) { return !probe.Window; }),
    this->Probes.end());
  for (const Probe& probe : this->Probes)
  {
    if (probe.Window == window && probe.Samples == this->Samples)
    {
      return probe.Compiles;
    }
  }
  Probe probe;
  probe.Window = window;
  probe.Samples = this->Samples;
  probe.Compiles = compiles(this->Samples);
  this->Probes.push_back(probe);
  return probe.Compiles;
}

csmScreenCache::Mode csmScreenCache::Begin(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  bool asLastFrame, int lights, bool enabled, const std::string& key,
  const std::function<bool(int samples)>& compiles)
{
  this->CurrentMode = OFF;
  this->Current = nullptr;
  // Renderers gone take their images with them.
  this->Entries.erase(std::remove_if(this->Entries.begin(), this->Entries.end(),
                        [](const Entry& entry) { return !entry.Renderer; }),
    this->Entries.end());
  auto found = std::find_if(this->Entries.begin(), this->Entries.end(),
    [renderer](const Entry& entry) { return entry.Renderer == renderer; });
  if (found == this->Entries.end())
  {
    this->Entries.emplace_back();
    this->Entries.back().Renderer = renderer;
    found = this->Entries.end() - 1;
  }
  Entry& entry = *found;
  this->Current = &entry;
  int viewport[4] = { 0, 0, 0, 0 };
  renderer->GetTiledSizeAndOrigin(viewport + 2, viewport + 3, viewport, viewport + 1);
  // A multisampled framebuffer shades a pixel once for the samples of several surfaces: each
  // sample holds the factors of its own (and the depth that names it).
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  this->Samples = std::max(1, static_cast<int>(samples));
  const bool multisampled = this->Samples > 1;
  const bool holds = entry.Holds && std::equal(viewport, viewport + 4, entry.Viewport) &&
    entry.Key == key && entry.Samples == this->Samples;
  if (!enabled || lights < 1 || lights > MAXIMUM_LIGHTS - (multisampled ? 1 : 0) ||
    viewport[2] < 1 || viewport[3] < 1 || !GLEW_ARB_shader_image_load_store ||
    (multisampled && !(GLEW_ARB_post_depth_coverage && GLEW_ARB_gpu_shader5)) ||
    (!asLastFrame && !entry.StoreRead) || !this->Compiles(window, compiles))
  {
    return OFF;
  }
  if (entry.Image && entry.Window != window)
  {
    // (The renderer went to another window: the image was of the other context.)
    if (entry.Window)
    {
      entry.Image->ReleaseGraphicsResources(entry.Window);
    }
    entry.Image = nullptr;
  }
  if (!entry.Image)
  {
    entry.Image = vtkSmartPointer<vtkTextureObject>::New();
    entry.Image->SetContext(window);
    entry.Window = window;
  }
  if (static_cast<int>(entry.Image->GetWidth()) != viewport[2] ||
    static_cast<int>(entry.Image->GetHeight()) != viewport[3] || entry.Samples != this->Samples ||
    !entry.Image->GetHandle())
  {
    entry.Image->ReleaseGraphicsResources(window);
    entry.Image->SetContext(window);
    entry.Image->SetSamples(static_cast<unsigned int>(multisampled ? this->Samples : 0));
    entry.Image->Allocate2D(viewport[2], viewport[3], 4, VTK_FLOAT);
    entry.Samples = this->Samples;
  }
  if (!entry.Image->GetHandle())
  {
    return OFF;
  }
  this->CurrentMode = holds && asLastFrame ? READ : STORE;
  std::copy(viewport, viewport + 4, entry.Viewport);
  entry.Key = key;
  glBindImageTexture(static_cast<GLuint>(this->GetImageUnit()), entry.Image->GetHandle(), 0,
    GL_FALSE, 0, this->CurrentMode == READ ? GL_READ_ONLY : GL_WRITE_ONLY, GL_RGBA32F);
  return this->CurrentMode;
}

bool csmScreenCache::End()
{
  Entry* entry = this->Current;
  this->Current = nullptr;
  if (!entry)
  {
    return false;
  }
  if (this->CurrentMode == OFF)
  {
    entry->Holds = false; // the renderer's last frame is not the image's
    return false;
  }
  glBindImageTexture(
    static_cast<GLuint>(this->GetImageUnit()), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  if (this->CurrentMode == STORE)
  {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  entry->Holds = true;
  entry->StoreRead = this->CurrentMode == READ;
  this->CurrentMode = OFF;
  return true;
}

const int* csmScreenCache::GetOrigin() const
{
  static const int none[4] = { 0, 0, 0, 0 };
  return this->Current ? this->Current->Viewport : none;
}

void csmScreenCache::ReleaseGraphicsResources(vtkWindow* window)
{
  // The images of this window's renderers (every one for no window): an image of another
  // window's context stays, holding its renderer's factors.
  for (Entry& entry : this->Entries)
  {
    if (window && entry.Window != window)
    {
      continue;
    }
    if (entry.Image)
    {
      entry.Image->ReleaseGraphicsResources(window ? window : entry.Window.Get());
    }
    entry.Image = nullptr;
    entry.Window = nullptr;
    entry.Holds = false;
  }
}
