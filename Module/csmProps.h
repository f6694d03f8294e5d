// SPDX-License-Identifier: BSD-3-Clause
// What the module's parts read of VTK's props and windows alike (internal): how wide VTK draws
// a prop's lines and points, and whether the user is dragging.
#ifndef csmProps_h
#define csmProps_h

#include "vtkRenderingCascadedShadowsModule.h" // for export macro

#include <functional>
#include <string>
#include <vector>

class vtkLight;
class vtkProp;
class vtkRenderWindow;
class vtkRenderer;

/// The line width and point size VTK draws a prop with, in pixels (1 where not finite).
VTKRENDERINGCASCADEDSHADOWS_EXPORT void csmScreenSizes(vtkProp* prop, float sizes[2]);

/// What a prop casts into a shadow map, as numbers that change when it does: where it is, its
/// visibility, its data's points and cells (their MTimes and counts), the representation, line
/// width, point size and culling it is drawn with, its clipping planes, whether it is opaque.
/// Colours, scalars, lookup tables, textures and lighting coefficients are not among them: they
/// change no map. A prop other than a plain actor of polygonal data counts every change of its own
/// and its mapper's (GetRedrawMTime).
std::vector<double> csmCastingState(vtkProp* prop);

/// Does VTK shadow this light? Scene and camera lights that are on, directional or spot with
/// cone angle < 90 degrees (vtkShadowMapBakerPass's rule), with ShadowAttenuation above 0.
bool csmLightCastsShadows(vtkLight* light);

/// Which of the renderer's props are so, as a digest ("count:hash" of their addresses): what a
/// shader signature holds of per-prop choices compiled into the shaders.
std::string csmPropDigest(vtkRenderer* renderer, const std::function<bool(vtkProp*)>& so);

/// Is the user dragging? (The window's desired update rate is at least 1 a second, VTK's
/// interactor convention.)
bool csmIsInteracting(vtkRenderWindow* window);

#endif
