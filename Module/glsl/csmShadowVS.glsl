// SPDX-License-Identifier: BSD-3-Clause
// Per-vertex map coordinates for the cascaded shadow-map lookup (csmShadowFS.glsl), injected
// into VTK's polydata vertex shaders by vtkCascadedShadowMapPass where no geometry shader sits
// between the stages. A cascade's homogeneous map coordinates are a linear function of the view
// position, so interpolating them across a triangle gives exactly the product the fragment
// shader would compute, and a software rasterizer no longer multiplies matrices per fragment.
// CSM_LIGHTS, CSM_MAX_CASCADES and CSM_MAP_VARYINGS (cascades a light passes) are #defined by
// the pass.

uniform mat4 csmToMap[CSM_LIGHTS * CSM_MAX_CASCADES]; // view space -> map, as in the lookup
out vec4 csmMapCoordVSOutput[CSM_LIGHTS * CSM_MAP_VARYINGS];

void csmMapCoordinates(vec4 vertexVC)
{
  for (int j = 0; j < CSM_LIGHTS; ++j)
  {
    for (int i = 0; i < CSM_MAP_VARYINGS; ++i)
    {
      csmMapCoordVSOutput[j * CSM_MAP_VARYINGS + i] = csmToMap[j * CSM_MAX_CASCADES + i] * vertexVC;
    }
  }
}
