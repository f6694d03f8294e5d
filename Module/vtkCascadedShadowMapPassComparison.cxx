// SPDX-License-Identifier: BSD-3-Clause
// The shadow pass's part of the comparison techniques (CSM_COMPARISON_TECHNIQUES): face
// partitions' half-spaces and camera space maps' depth, packed for their lookup
// (glsl/csmComparisonFS.glsl). The planning is vtkCascadedShadowMapPlannerComparison.cxx.
#include "vtkCascadedShadowMapPass.h"

#include "csmComparisonFS.h" // the comparison techniques' lookup, Module/glsl/csmComparisonFS.glsl
#include "vtkCascadedShadowMapPlanner.h"

#include "vtkMatrix4x4.h"
#include "vtkShaderProgram.h"

#include <sstream>
#include <string>

static_assert(CSM_COMPARISON_TECHNIQUES, "built with CSM_COMPARISON_TECHNIQUES only");

void vtkCascadedShadowMapPass::PackComparison(
  const vtkCascadedShadowMapBakerPass::LightMaps& maps, vtkMatrix4x4* viewToWorld)
{
  ShaderUniforms& u = this->Uniforms;
  const int count = maps.GetNumberOfCascades();
  for (int c = 0; c < vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES; ++c)
  {
    static const vtkCascadedShadowMapBakerPass::CascadeMap none;
    const vtkCascadedShadowMapBakerPass::CascadeMap& map = c < count ? maps.Cascades[c] : none;
    // A face partition's half-spaces in view space: the world plane (a row) times view -> world.
    for (int k = 0; k < 4; ++k)
    {
      const double* plane = map.Planes + 4 * k;
      const bool used = maps.SelectedByPlanes() && c < count;
      for (int column = 0; column < 4; ++column)
      {
        double value = 0.0;
        for (int row = 0; row < 4; ++row)
        {
          value += plane[row] * viewToWorld->GetElement(row, column);
        }
        u.Planes.push_back(static_cast<float>(used ? value : (column == 3 ? 1.0 : 0.0)));
      }
    }
    u.DepthW.push_back(static_cast<float>(map.DepthW));
    u.CameraSpace = u.CameraSpace || map.DepthW > 0.0;
  }
  u.Faces = u.Faces || maps.SelectedByPlanes();
}

std::string vtkCascadedShadowMapPass::ComparisonDefinitions() const
{
  if (!this->Uniforms.Faces && !this->Uniforms.CameraSpace)
  {
    return std::string();
  }
  std::ostringstream decl;
  if (this->Uniforms.Faces)
  {
    decl << "#define CSM_FACES\n"; // maps selected by their half-spaces (face partitions)
  }
  if (this->Uniforms.CameraSpace)
  {
    decl << "#define CSM_CAMERA_SPACE\n"; // a depth bias that follows each ray's w
  }
  decl << csmComparisonFS << "\n";
  return decl.str();
}

void vtkCascadedShadowMapPass::SetComparisonUniforms(vtkShaderProgram* program) const
{
  const ShaderUniforms& u = this->Uniforms;
  const int lights = static_cast<int>(u.Lights());
  if (u.Faces)
  {
    program->SetUniform4fv("csmPlanes",
      lights * vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES * 4, u.Planes.data());
  }
  if (u.CameraSpace)
  {
    program->SetUniform1fv("csmDepthW",
      lights * vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES, u.DepthW.data());
  }
}
