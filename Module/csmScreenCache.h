// SPDX-License-Identifier: BSD-3-Clause
// The shadow factors of a renderer's last frame at its pixels, for a frame drawn as that one
// (vtkCascadedShadowMapPass, internal).
//
// A frame that shows the same surfaces from the same camera under the same maps (the baker
// planned it as its last frame: vtkCascadedShadows::FrameStatistics::AsLastFrame) has the same
// shadow factor at every pixel, whatever colours, scalars or materials changed. The frame that
// stores them makes its lookup as usual and writes each light's factor at the fragment's pixel
// (a fragment that passes the depth test before it is shaded: the last one at a pixel is the
// surface the frame shows); the frames after it read the factor there instead of the lookup.
// The store costs a frame about a sixth (Results.md, "A still frame"): a renderer whose last
// stored factors went unread (the view or the scene keeps changing) stores again only in a
// frame planned as its last one.
#ifndef csmScreenCache_h
#define csmScreenCache_h

#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class csmScreenCache
{
public:
  /// What a frame's opaque surfaces do with the factors (CSM_SCREEN in csmShadowFS.glsl).
  enum Mode
  {
    OFF = 0,   ///< the lookup alone
    STORE = 1, ///< the lookup, its factors written at the pixel
    READ = 2   ///< the factors the last frame wrote at the pixel, no lookup
  };
  /// The most shadowed lights whose factors a pixel holds (one channel each); in a
  /// multisampled framebuffer one fewer (a channel holds the depth that tells the surfaces of a
  /// pixel apart).
  static constexpr int MAXIMUM_LIGHTS = 4;

  csmScreenCache();
  ~csmScreenCache();

  /// This frame's mode, its renderer's image bound for it: READ where the image holds the
  /// factors of the renderer's last frame, drawn as this one (asLastFrame, the same viewport
  /// and key: the shader, the options and the lights' attenuations); STORE where it can hold
  /// them and they may be read; OFF where they cannot be (more lights, no image load/store,
  /// not enabled) or the last ones went unread. A multisampled
  /// framebuffer needs GL_ARB_post_depth_coverage and GL_ARB_gpu_shader5 (gl_SampleMaskIn).
  /// compiles(samples) says whether the shaders that store and read compile in this context
  /// (asked once per window and sample count; OFF where they do not).
  Mode Begin(vtkRenderer* renderer, vtkOpenGLRenderWindow* window, bool asLastFrame, int lights,
    bool enabled, const std::string& key, const std::function<bool(int samples)>& compiles);
  /// After the frame's geometry: the image unbound; does it hold this frame's factors?
  bool End();
  /// The frame's viewport's lower left in window pixels (csmScreenOrigin), its framebuffer's
  /// samples (CSM_SCREEN_SAMPLES: 1 single-sampled) and the image unit.
  const int* GetOrigin() const;
  int GetSamples() const { return this->Samples; }
  int GetImageUnit() const { return 0; }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  struct Entry
  {
    vtkWeakPointer<vtkRenderer> Renderer;
    vtkWeakPointer<vtkOpenGLRenderWindow> Window; ///< the context of the image
    vtkSmartPointer<vtkTextureObject> Image;
    int Viewport[4] = { 0, 0, 0, 0 }; ///< x, y, width, height of the frame it holds
    std::string Key;
    int Samples = 1;
    bool Holds = false;    ///< the factors of the renderer's last frame
    bool StoreRead = true; ///< the last factors stored were read (or none were stored)
  };
  std::vector<Entry> Entries; ///< per renderer
  struct Probe
  {
    vtkWeakPointer<vtkOpenGLRenderWindow> Window;
    int Samples = 1;
    bool Compiles = false;
  };
  std::vector<Probe> Probes; ///< what compiles(samples) said, per window and sample count
  bool Compiles(vtkOpenGLRenderWindow* window, const std::function<bool(int)>& compiles);
  Entry* Current = nullptr; ///< this frame's, between Begin() and End()
  Mode CurrentMode = OFF;
  int Samples = 1;
};

#endif
