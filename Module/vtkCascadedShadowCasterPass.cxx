// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowCasterPass.h"

#include "csmProps.h"
#include "csmReportOnce.h"

#include "csmCaster.h"       // the GLSL of Module/glsl/csmCaster.glsl
#include "csmCasterLineGS.h" // the GLSL of Module/glsl/csmCasterLineGS.glsl

#include "vtkActor.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkProperty.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include <cmath>
#include <regex>
#include <sstream>
#include <utility>

vtkStandardNewMacro(vtkCascadedShadowCasterPass);

void vtkCascadedShadowCasterPass::BeginCascade(
  vtkOpenGLState* state, const CasterUniforms& uniforms, std::map<vtkProp*, unsigned int> cullFaces)
{
  this->CullState = state;
  this->Uniforms = uniforms;
  this->CullFaces = std::move(cullFaces);
}

int vtkCascadedShadowCasterPass::DrawCasters(
  vtkRenderer* renderer, vtkFrameBufferObjectBase* frameBuffer, std::vector<vtkProp*>& props)
{
  vtkRenderState state(renderer);
  state.SetPropArrayAndCount(props.data(), static_cast<int>(props.size()));
  state.SetFrameBuffer(frameBuffer);
  this->PreRender(&state);
  int rendered = 0;
  for (vtkProp* prop : props)
  {
    rendered += prop->RenderOpaqueGeometry(renderer);
  }
  this->PostRender(&state);
  return rendered;
}

void vtkCascadedShadowCasterPass::SetViewDepthNudge(float viewDepthNudge)
{
  const float nudge =
    std::isfinite(viewDepthNudge) && viewDepthNudge > 0.0f ? viewDepthNudge : 0.0f;
  if ((nudge > 0.0f) != (this->ViewDepthNudge > 0.0f))
  {
    this->ShaderStageTime.Modified();
  }
  this->ViewDepthNudge = nudge;
}

vtkMTimeType vtkCascadedShadowCasterPass::GetShaderStageMTime()
{
  return this->ShaderStageTime.GetMTime();
}

void vtkCascadedShadowCasterPass::EndCascade()
{
  if (this->CullState && !this->CullFaces.empty())
  {
    this->CullState->vtkglEnable(GL_POLYGON_OFFSET_FILL); // as the baker set it for the maps
  }
  this->CullFaces.clear();
  this->CullState = nullptr;
}

void vtkCascadedShadowCasterPass::ReportOnce(bool error, const std::string& message)
{
  csmReportOnce(this, this->Reported, error, message);
}

namespace
{
/// Does GLSL source assign gl_FragDepth (outside // comments)?
bool writesDepth(const std::string& source)
{
  static const std::regex assignment(R"(\bgl_FragDepth\s*=(?!=))");
  std::istringstream lines(source);
  std::string line;
  while (std::getline(lines, line))
  {
    if (std::regex_search(line.substr(0, line.find("//")), assignment))
    {
      return true;
    }
  }
  return false;
}

/// Does the mapper draw nothing but lines for the prop, wider than one pixel (a polydata of
/// lines, or any surface as wireframe; no vertices or points)? The GL draws such lines itself
/// (in texels of the map); the map pass widens them in its geometry shader instead.
bool drawsOnlyWideLines(vtkAbstractMapper* mapper, vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  vtkPolyDataMapper* polyMapper = vtkPolyDataMapper::SafeDownCast(mapper);
  vtkPolyData* data = polyMapper ? polyMapper->GetInput() : nullptr;
  float sizes[2];
  csmScreenSizes(prop, sizes);
  if (!property || !data || sizes[0] <= 1.0f || property->GetRepresentation() == VTK_POINTS ||
    property->GetVertexVisibility() || data->GetNumberOfVerts() > 0)
  {
    return false;
  }
  return property->GetRepresentation() == VTK_WIREFRAME ||
    (data->GetNumberOfLines() > 0 && data->GetNumberOfPolys() == 0 &&
      data->GetNumberOfStrips() == 0);
}
}

bool vtkCascadedShadowCasterPass::PreReplaceShaderValues(std::string&, std::string& geometryShader,
  std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop)
{
  // Depth only: no lighting in the maps' fragment shader (the mapper finds no tag to expand).
  // This also keeps the depth program apart from the main pass's in the shader cache.
  vtkShaderProgram::Substitute(fragmentShader, "//VTK::Light::Impl",
    "gl_FragData[0] = vec4(1.0); // cascaded shadow map: depth pass\n", false);
  // Lines VTK widens in a geometry shader (tubes; wide lines the GL cannot draw), and wide lines
  // the GL would draw: our template, which widens them as the main view does (wide lines as
  // tubes of their width), with the same tags for the mapper to fill.
  if (geometryShader.find("uniform vec2 lineWidthNVC") != std::string::npos ||
    (geometryShader.empty() && drawsOnlyWideLines(mapper, prop)))
  {
    geometryShader = csmCasterLineGS;
    if (!vtkShaderProgram::Substitute(geometryShader, "//CSM::Caster::Dec", csmCaster, false))
    {
      this->ReportOnce(true, "the caster line template lost its declaration tag");
      return false;
    }
  }
  return true;
}

bool vtkCascadedShadowCasterPass::PostReplaceShaderValues(std::string& vertexShader, std::string&,
  std::string& fragmentShader, vtkAbstractMapper*, vtkProp* prop)
{
  // Points: sized per vertex as the main view draws them (gl_PointSize, GL_PROGRAM_POINT_SIZE
  // is on while the maps render); spheres keep only their silhouette; impostors (tubes,
  // spheres) write the depth of their centre, not the one VTK computes for a view camera.
  const size_t vertexMain = vertexShader.find("void main");
  const size_t vertexEnd = vertexShader.rfind('}');
  const size_t fragmentMain = fragmentShader.find("void main");
  const size_t fragmentEnd = fragmentShader.rfind('}');
  if (vertexMain == std::string::npos || vertexEnd == std::string::npos || vertexEnd < vertexMain ||
    fragmentMain == std::string::npos || fragmentEnd == std::string::npos ||
    fragmentEnd < fragmentMain)
  {
    this->ReportOnce(
      false, "a mapper's shaders have no main(): its lines and points cast shadows one texel wide");
    return true;
  }
  // Only props whose points are drawn bigger than a pixel pay for the sizing: a software
  // rasterizer runs both sides of its branch for every vertex (a changed point size changes
  // the property, and VTK then builds the shaders again).
  float sizes[2];
  csmScreenSizes(prop, sizes);
  vertexShader.insert(vertexEnd,
    sizes[1] > 1.0f ? "  csmSizePoint(gl_Position);\n" : "  csmSphereView = vec4(0.0);\n");
  vertexShader.insert(vertexMain, std::string("#define CSM_CASTER_VERTEX\n") + csmCaster + "\n");
  std::string fragmentEndCode;
  const bool sphere = fragmentShader.find("gl_PointCoord") != std::string::npos;
  if (sphere)
  {
    fragmentEndCode += "  if (csmOutsideSphere()) { discard; }\n";
  }
  if (fragmentShader.find("ZCalcR") != std::string::npos)
  {
    fragmentEndCode += "  gl_FragDepth = gl_FragCoord.z;\n";
  }
  if (fragmentShader.find("offsetVCVSOutput") != std::string::npos)
  {
    // vtkPointGaussianMapper's splats: VTK fades each one's triangle by its opacity (a Gaussian
    // by default), which a depth cannot; the map holds the splat where it is at least half
    // opaque (the default's disc of sqrt(2 ln 2) = 1.18 standard deviations), not the triangle.
    fragmentEndCode += "  if (opacity < 0.5) { discard; }\n";
  }
  std::string fragmentDefines = sphere ? "#define CSM_CASTER_SPHERE_FRAGMENT\n" : "";
  if (this->ViewDepthNudge > 0.0f)
  {
    // (After any depth the mapper writes itself: VTK's coincident-topology offsets.)
    const bool written = writesDepth(fragmentShader) || writesDepth(fragmentEndCode);
    fragmentEndCode += std::string("  gl_FragDepth = csmViewDepth(") +
      (written ? "gl_FragDepth" : "gl_FragCoord.z") + ");\n";
    fragmentDefines += "#define CSM_CASTER_VIEW_DEPTH\n";
  }
  fragmentShader.insert(fragmentEnd, fragmentEndCode);
  if (!fragmentDefines.empty())
  {
    fragmentShader.insert(fragmentMain, fragmentDefines + csmCaster + "\n");
  }
  return true;
}

bool vtkCascadedShadowCasterPass::SetShaderParameters(
  vtkShaderProgram* program, vtkAbstractMapper*, vtkProp* prop, vtkOpenGLVertexArrayObject*)
{
  // Closed casters: only their exit layer (the property has just set its own culling), at its
  // own depth: at a concave crease it touches a face turned toward the light that it shadows,
  // and the baker's polygon offset (steepest on faces nearly along the light) would push it off
  // that face by about a texel, a line of light along the crease. Other casters keep the offset.
  const auto cull = this->CullState ? this->CullFaces.find(prop) : this->CullFaces.end();
  if (cull != this->CullFaces.end())
  {
    this->CullState->vtkglCullFace(cull->second);
    this->CullState->vtkglEnable(GL_CULL_FACE);
    this->CullState->vtkglDisable(GL_POLYGON_OFFSET_FILL);
  }
  else if (this->CullState && !this->CullFaces.empty())
  {
    this->CullState->vtkglEnable(GL_POLYGON_OFFSET_FILL);
  }
  if (program->IsUniformUsed("csmViewDepthNudge"))
  {
    program->SetUniformf("csmViewDepthNudge", this->ViewDepthNudge);
  }
  if (!program->IsUniformUsed("csmCasterWidth"))
  {
    return true;
  }
  float width[2];
  csmScreenSizes(prop, width);
  CasterUniforms& u = this->Uniforms;
  program->SetUniform2f("csmCasterWidth", width);
  program->SetUniformMatrix4x4("csmMapToView", u.MapToView);
  program->SetUniformMatrix4x4("csmViewToMap", u.ViewToMap);
  program->SetUniform4f("csmLightView", u.LightView);
  program->SetUniform2f("csmPixelWorld", u.PixelWorld);
  program->SetUniform4f("csmMapViewport", u.Viewport);
  return true;
}

void vtkCascadedShadowCasterPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CulledCasters: " << this->CullFaces.size() << "\n";
}
