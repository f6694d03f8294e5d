// SPDX-License-Identifier: BSD-3-Clause
// The module's one bridge between VTK's objects and the math's types (internal): VTK's
// row-major matrices as GLM's, a vtkCamera as a csm::Camera, and the questions the module's
// helpers ask the math about VTK's boxes and cameras. The public classes take VTK types only.
#ifndef csmVTKMath_h
#define csmVTKMath_h

#include "csmTypes.h" // for csm::Camera

#include "vtkRenderingCascadedShadowsModule.h" // for export macro

#include <glm/mat4x4.hpp>

class vtkCamera;

/// VTK's row-major double[16] as GLM's column-major matrix, and back.
glm::dmat4 csmFromRowMajor(const double m[16]);
void csmToRowMajor(const glm::dmat4& m, double out[16]);

/// A vtkCamera of a viewport of the given aspect as the math's camera (false: no camera).
bool csmToCamera(vtkCamera* camera, double aspect, csm::Camera& cam);
/// How many times the image height the frustum of csmToCamera spans (1 + |window centre y|).
double csmWindowCentreScale(vtkCamera* camera);
/// Is the camera's projection the one about its axis that csmToCamera describes exactly (no
/// window centre shift, no off-axis or explicit projection), so that its window samples read
/// back through it?
bool csmCameraOnAxis(vtkCamera* camera);

/// Does any part of a world box (xmin, xmax, ymin, ymax, zmin, zmax) reach the light volume of
/// a cascade (row-major world -> light clip)? With depthClamp, what is nearer than the near
/// plane counts (clamped onto it).
VTKRENDERINGCASCADEDSHADOWS_EXPORT bool csmCascadeReachesBox(
  const double worldToClip[16], const double bounds[6], bool depthClamp);

/// Can a caster inside casterBounds shadow a point inside receiverBounds (world boxes) under a
/// directional light travelling along lightDirection (csm::sweptBoxReachesBox: the caster box
/// swept along the light by more than minimumDistance meets the receiver box)? True for bad
/// input (the safe answer).
bool csmCasterBoxReachesBox(const double lightDirection[3], const double casterBounds[6],
  const double receiverBounds[6], double minimumDistance);

/// Does the camera (of a viewport of the given aspect) see only the outside of every closed
/// surface inside a world box (csm::eyeSeesOnlyOutsideOf: its near plane reaches no point of the
/// box)? False for parallel cameras and bad input.
bool csmViewSeesOnlyOutsideOf(vtkCamera* camera, double aspect, const double bounds[6]);

/// Did the camera take a small step from `before` (a smooth path: csm::smallCameraStep),
/// measured against a view depth (the far end of a cascade)?
bool csmIsSmallCameraStep(vtkCamera* before, vtkCamera* now, double aspect, double depth);

#endif
