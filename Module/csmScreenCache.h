// SPDX-License-Identifier: BSD-3-Clause
// The shadow factors of the last frame at its pixels, for a frame drawn as that one
// (vtkCascadedShadowMapPass, internal).
//
// A frame that shows the same surfaces from the same camera under the same maps (the baker
// planned it as its last frame: vtkCascadedShadows::FrameStatistics::AsLastFrame) has the same
// shadow factor at every pixel, whatever colours, scalars or materials changed. The frame that
// stores them makes its lookup as usual and writes each light's factor at the fragment's pixel
// (a fragment that passes the depth test before it is shaded: the last one at a pixel is the
// surface the frame shows); the frames after it read the factor there instead of the lookup.
#ifndef csmScreenCache_h
#define csmScreenCache_h

#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <string>

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
  /// The most shadowed lights whose factors a pixel holds (one channel each).
  static constexpr int MAXIMUM_LIGHTS = 4;

  /// This frame's mode, its image bound for it: READ where the image holds this renderer's
  /// factors of its last frame, drawn as this one (asLastFrame, the same viewport and key: the
  /// shader, the options and the lights' attenuations), STORE where it can hold them, OFF
  /// where it cannot (a multisampled framebuffer, more lights, no image load/store, debug).
  Mode Begin(vtkRenderer* renderer, vtkOpenGLRenderWindow* window, bool asLastFrame, int lights,
    bool enabled, const std::string& key);
  /// After the frame's geometry: the image unbound; does it hold this frame's factors?
  bool End();
  /// The viewport's lower left in window pixels (csmScreenOrigin) and the image unit.
  const int* GetOrigin() const { return this->Viewport; }
  int GetImageUnit() const { return 0; }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkSmartPointer<vtkTextureObject> Image;
  vtkWeakPointer<vtkRenderer> Renderer; ///< whose factors the image holds (null: none)
  int Viewport[4] = { 0, 0, 0, 0 };     ///< x, y, width, height of its frame
  std::string Key;
  Mode Current = OFF;
  vtkRenderer* CurrentRenderer = nullptr;
};

#endif
