// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowCasterPass
 * @brief   The shader hooks of the shadow map pass (internal to vtkCascadedShadowMapBakerPass).
 *
 * While vtkCascadedShadowMapBakerPass renders a cascade, this pass is the one in the casters'
 * render-pass keys: depth only (no lighting in the fragment shader), screen-sized casters drawn
 * as wide as the main view draws them (Module/glsl/csmCaster.glsl, csmCasterLineGS.glsl), the
 * culled face of each closed caster. It holds no reference to the baker: mappers keep the passes
 * of their last render (vtkOpenGLPolyDataMapper's LastRenderPassInfo), and the baker owns
 * mappers of its own (the compact caster blocks), so a baker in their keys would keep itself
 * alive.
 */
#ifndef vtkCascadedShadowCasterPass_h
#define vtkCascadedShadowCasterPass_h

#include "vtkOpenGLRenderPass.h"
#include "vtkTimeStamp.h" // for members

#include <map>    // for members
#include <set>    // for members
#include <string> // for members
#include <vector> // for DrawCasters

class vtkFrameBufferObjectBase;
class vtkOpenGLState;
class vtkRenderer;
class vtkProp;

class vtkCascadedShadowCasterPass : public vtkOpenGLRenderPass
{
public:
  static vtkCascadedShadowCasterPass* New();
  vtkTypeMacro(vtkCascadedShadowCasterPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Nothing: the baker draws the casters between PreRender() and PostRender().
  void Render(const vtkRenderState*) override {}

  /// What the map pass's shaders need to draw screen-sized casters with the main view's size
  /// (Module/glsl/csmCaster.glsl), for the cascade being rendered; float, as uploaded.
  struct CasterUniforms
  {
    float MapToView[16] = {}; ///< light clip -> main view, column-major
    float ViewToMap[16] = {}; ///< main view -> light clip, column-major
    float LightView[4] = {};  ///< toward a directional light (w = 0) or its position (w = 1)
    float PixelWorld[2] = {}; ///< world size of a main-view pixel at view depth d: [0] + [1] d
    float Viewport[4] = {};   ///< the cascade's tile, in texels
  };

  /// For the cascade about to render: its uniforms, the face (GL_FRONT / GL_BACK) to cull per
  /// closed caster, and the state to cull it with (SetShaderParameters runs after the property
  /// set its own culling). A culled caster is drawn without the polygon offset (a map holds its
  /// exit layer at its own depth).
  void BeginCascade(vtkOpenGLState* state, const CasterUniforms& uniforms,
    std::map<vtkProp*, unsigned int> cullFaces);
  /// The view's depth pass: each fragment's depth is written its change across the pixel and
  /// viewDepthNudge (window depth) farther than the surface, so that the frame's own geometry
  /// passes it at every sample under VTK's depth test (GL_LESS: of surfaces at one depth the
  /// first drawn shows, as without shadows) whatever the surface's slope; 0 for the maps (the
  /// depth as drawn). The shaders change between the two.
  void SetViewDepthNudge(float viewDepthNudge);

  /// Changes when the shaders' source does (the view depth nudge switched on or off).
  vtkMTimeType GetShaderStageMTime() override;
  /// Draws the props' opaque geometry with this pass's hooks into the framebuffer (null: the
  /// one bound); returns how many rendered something.
  int DrawCasters(
    vtkRenderer* renderer, vtkFrameBufferObjectBase* frameBuffer, std::vector<vtkProp*>& props);
  /// After the cascade: no culling, no state.
  void EndCascade();

protected:
  vtkCascadedShadowCasterPass() = default;
  ~vtkCascadedShadowCasterPass() override = default;

  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* vao) override;

  /// vtkErrorMacro / vtkWarningMacro, once per distinct message.
  void ReportOnce(bool error, const std::string& message);

  CasterUniforms Uniforms;
  std::map<vtkProp*, unsigned int> CullFaces;
  vtkOpenGLState* CullState = nullptr;
  float ViewDepthNudge = 0.0f;
  vtkTimeStamp ShaderStageTime;
  std::set<std::string> Reported;

private:
  vtkCascadedShadowCasterPass(const vtkCascadedShadowCasterPass&) = delete;
  void operator=(const vtkCascadedShadowCasterPass&) = delete;
};

#endif
