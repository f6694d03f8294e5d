// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowMapPass.h"

#include "csmAtlas.h"    // csm::kAtlasFullMaps
#include "csmPages.h"    // csm::kPageTexels and the other page constants
#include "csmProps.h"    // csmScreenSizes, csmPropDigest
#include "csmSceneFit.h" // csm::sceneFittedBiasShare
#include "csmScreenCache.h"
#include "csmSpotSetup.h" // csm::perspectiveBiasFactor
#include "csmVTKMath.h"   // csmFromRowMajor

#include "vtkAbstractMapper.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCameraPass.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkLight.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderState.h"
#include "vtkSequencePass.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include "csmScreenProbeFS.h" // Module/glsl/csmScreenProbeFS.glsl
#include "csmScreenProbeVS.h" // Module/glsl/csmScreenProbeVS.glsl
#include "csmShadowFS.h"      // the GLSL of Module/glsl/csmShadowFS.glsl
#if CSM_COMPARISON_TECHNIQUES
#include "csmComparisonFS.h" // the comparison techniques' lookup, Module/glsl/csmComparisonFS.glsl
#endif

#include <algorithm>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkCascadedShadowMapPass);
vtkCxxSetObjectMacro(vtkCascadedShadowMapPass, ShadowMapBakerPass, vtkCascadedShadowMapBakerPass);

namespace
{
const char* const kVertexVC = "vec4 vertexVC = vertexVCVSOutput;";
constexpr int kMaxCascades = vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES;
const char* const kShadowDec = "//CSM::Shadow::Dec";

const char* const kSystemDec = "//VTK::System::Dec";
const char* const kLightImpl = "//VTK::Light::Impl";

std::string indexed(const char* name, size_t j)
{
  return std::string(name) + std::to_string(j);
}

size_t occurrences(const std::string& text, const char* word)
{
  size_t n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
  {
    ++n;
  }
  return n;
}

/// Does the current context have sampler objects (for the per-texel compares' own unit)?
bool samplerObjects()
{
  return GLEW_VERSION_3_3 || GLEW_ARB_sampler_objects;
}

/// Can a prop's fragments take their factors from the pixel (csmScreenCache)? Opaque, and shaded
/// only where the depth test passed them: no depth of their own, no discard but VTK's of a fully
/// transparent colour (which an opaque prop does not have); and VTK's tags where the extension
/// and the store go.
bool screenCapable(const std::string& fragmentShader, vtkProp* prop)
{
  return prop && !prop->HasTranslucentPolygonalGeometry() &&
    fragmentShader.find("gl_FragDepth =") == std::string::npos &&
    fragmentShader.find("gl_FragDepth=") == std::string::npos &&
    occurrences(fragmentShader, "discard;") ==
    occurrences(fragmentShader, "gl_FragData[0].a <= 0.0") &&
    fragmentShader.find(kSystemDec) != std::string::npos &&
    fragmentShader.find(kLightImpl) != std::string::npos;
}
}

vtkCascadedShadowMapPass::vtkCascadedShadowMapPass()
  : ScreenCache(new csmScreenCache)
{
  this->ShadowMapBakerPass = vtkCascadedShadowMapBakerPass::New();
}

vtkCascadedShadowMapPass::~vtkCascadedShadowMapPass()
{
  this->SetShadowMapBakerPass(nullptr);
}

void vtkCascadedShadowMapPass::SetPCFSize(int size)
{
  const int odd = std::max(1, std::min(7, size | 1));
  if (odd != this->PCFSize)
  {
    this->PCFSize = odd;
    this->Modified();
  }
}

vtkMTimeType vtkCascadedShadowMapPass::GetShaderStageMTime()
{
  return this->ShaderTime.GetMTime();
}

void vtkCascadedShadowMapPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;
  this->ScreenMode = csmScreenCache::OFF;
  vtkRenderer* renderer = s->GetRenderer();
  this->ClearLights(renderer);
  this->UpdateLightGeometry(renderer);
  this->UpdateLights(renderer);
  vtkCascadedShadowMapBakerPass* baker = this->ShadowMapBakerPass;
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  renderer->GetTiledSizeAndOrigin(size, size + 1, origin, origin + 1);
  if (!baker)
  {
    this->ReportOnce("no shadow map baker pass set (SetShadowMapBakerPass): no shadows");
  }
  else if (!renderer->GetSelector() && size[0] > 0 && size[1] > 0 &&
    baker->GetLastRenderer() != renderer)
  {
    this->ReportOnce("the shadow map baker pass did not render this renderer before this pass "
                     "(it goes before it in the renderer's pass sequence, as UseShadowsOn puts "
                     "it): no shadows");
  }
  // The view's depth the baker drew this frame stays in the depth buffer, a few steps farther
  // than the surfaces (its visible-depth pass, csmMapDrawing::DrawViewDepth): the frame's
  // geometry passes it under VTK's own depth test, which keeps the first drawn of surfaces at
  // one depth, as a frame without shadows and one drawn as the last one (no depth drawn) do.
  const bool shadowed = !renderer->GetSelector() && baker && !baker->GetLightMaps(renderer).empty();
  if (!shadowed)
  {
    // Picking, or nothing shadowed: the renderer's own geometry pass (over the view's depth
    // where the baker drew it).
    this->UpdateGeometry(renderer, s->GetFrameBuffer());
    return;
  }
  this->DrawShadowed(s);
}

namespace
{
/// View space as the mappers' shaders see it (their vertexVC) -> world: VTK's key matrices of
/// the camera, which it refreshes on the camera's modification time (a camera copied back onto
/// the active one keeps the last frame's until it is modified), not the camera's own transform.
void mappersViewToWorld(vtkRenderer* renderer, vtkMatrix4x4* viewToWorld)
{
  vtkOpenGLCamera* glCamera = vtkOpenGLCamera::SafeDownCast(renderer->GetActiveCamera());
  if (glCamera)
  {
    vtkMatrix4x4 *worldToViewGL = nullptr, *viewToDisplay = nullptr, *worldToDisplay = nullptr;
    vtkMatrix3x3* normals = nullptr;
    glCamera->GetKeyMatrices(renderer, worldToViewGL, normals, viewToDisplay, worldToDisplay);
    vtkMatrix4x4::Transpose(worldToViewGL, viewToWorld); // (stored transposed, for the GL)
    viewToWorld->Invert();
  }
  else
  {
    vtkMatrix4x4::Invert(renderer->GetActiveCamera()->GetModelViewTransformMatrix(), viewToWorld);
  }
}
} // namespace

namespace
{
int freeUnits(vtkTextureUnitManager* units)
{
  int free = 0;
  for (int unit = 0; unit < units->GetNumberOfTextureUnits(); ++unit)
  {
    free += units->IsAllocated(unit) ? 0 : 1;
  }
  return free;
}
} // namespace

void vtkCascadedShadowMapPass::PackMaps(
  const vtkCascadedShadowMapBakerPass::LightMaps& maps, vtkMatrix4x4* viewToWorld)
{
  const double toUnit[16] = { 0.5, 0, 0, 0.5, 0, 0.5, 0, 0.5, 0, 0, 0.5, 0.5, 0, 0, 0, 1 };
  ShaderUniforms& u = this->Uniforms;
  u.LightIndex.push_back(maps.LightIndex);
  u.Count.push_back(maps.GetNumberOfCascades());
  u.SplitNear.push_back(static_cast<float>(maps.SplitNear));
  u.Attenuation.push_back(
    static_cast<float>(this->ShadowDarkness * maps.Light->GetShadowAttenuation()));
  const int count = maps.GetNumberOfCascades();
  const double atlasWidth = std::max(1, maps.AtlasSize[0]);
  const double atlasHeight = std::max(1, maps.AtlasSize[1]);
  for (int c = 0; c < kMaxCascades; ++c)
  {
    static const vtkCascadedShadowMapBakerPass::CascadeMap none;
    const vtkCascadedShadowMapBakerPass::CascadeMap& map = c < count ? maps.Cascades[c] : none;
    double clipFromView[16], mapFromView[16];
    if (c < count)
    {
      vtkMatrix4x4::Multiply4x4(map.WorldToMap, viewToWorld->GetData(), clipFromView);
      vtkMatrix4x4::Multiply4x4(toUnit, clipFromView, mapFromView);
    }
    else
    {
      vtkMatrix4x4::Identity(mapFromView);
    }
    for (int column = 0; column < 4; ++column)
    {
      for (int row = 0; row < 4; ++row)
      {
        u.ToMap.push_back(static_cast<float>(mapFromView[4 * row + column]));
      }
    }
    u.Handedness.push_back(vtkMatrix4x4::Determinant(mapFromView) < 0.0 ? -1.0f : 1.0f);
    // (A spot light's perspective map: minus its f n, the bias scaled in the lookup by f n / w^2.)
    const double perspective =
      c < count && maps.Kind == vtkCascadedShadowMapBakerPass::LightKind::Spot
      ? csm::perspectiveBiasFactor(csmFromRowMajor(map.WorldToMap))
      : 0.0;
    u.BiasShare.push_back(perspective > 0.0 ? static_cast<float>(-perspective)
        : c < count && map.IsSceneFitted()  ? static_cast<float>(csm::sceneFittedBiasShare(
                                                std::max(map.Resolution[0], map.Resolution[1])))
                                            : 1.0f);
    // The map's rectangle in the atlas (the lower left of its tile), in [0, 1].
    u.Tile.push_back(static_cast<float>(map.Tile[0] / atlasWidth));
    u.Tile.push_back(static_cast<float>(map.Tile[1] / atlasHeight));
    u.Tile.push_back(static_cast<float>(map.Resolution[0] / atlasWidth));
    u.Tile.push_back(static_cast<float>(map.Resolution[1] / atlasHeight));
    u.SplitFar.push_back(static_cast<float>(map.SplitFar));
    for (int axis = 0; axis < 2; ++axis)
    {
      u.Texel.push_back(1.0f / static_cast<float>(std::max(1, map.Resolution[axis])));
    }
  }
  // (A light whose page table finds no free texture unit reads its base alone.)
  vtkTextureUnitManager* units = maps.Atlas && maps.Atlas->GetContext()
    ? maps.Atlas->GetContext()->GetTextureUnitManager()
    : nullptr;
  const bool paged = maps.Pages.Active && maps.Pages.TableTexture && count == 1 && units &&
    units->GetNumberOfTextureUnits() > 0 && freeUnits(units) > 0;
  u.PageLevels.push_back(paged ? maps.Pages.Levels : 0);
  u.PageDepth.push_back(paged ? static_cast<float>(maps.Pages.BaseDepth) : 0.0f);
  u.PageVirtual.push_back(static_cast<float>(paged ? maps.Pages.BaseTexels[0] : 1.0));
  u.PageVirtual.push_back(static_cast<float>(paged ? maps.Pages.BaseTexels[1] : 1.0));
  u.PageTile.push_back(static_cast<float>(csm::kPageTexels / atlasWidth));
  u.PageTile.push_back(static_cast<float>(csm::kPageTexels / atlasHeight));
  u.PageUnit.push_back(-1);
  if (paged)
  {
    maps.Pages.TableTexture->Activate();
    u.PageUnit.back() = maps.Pages.TableTexture->GetTextureUnit();
  }
}

void vtkCascadedShadowMapPass::DrawShadowed(const vtkRenderState* s)
{
  vtkRenderer* renderer = s->GetRenderer();
  vtkCascadedShadowMapBakerPass* baker = this->ShadowMapBakerPass;
  // View space -> map coordinates in [0,1]^3, composed in double, uploaded as float.
  vtkNew<vtkMatrix4x4> viewToWorld;
  mappersViewToWorld(renderer, viewToWorld);
  std::string signature;
  ShaderUniforms& u = this->Uniforms;
  u = ShaderUniforms();
  this->GatherThisFrame = vtkCascadedShadowMapPass::GatherTexels();
  for (const auto& maps : baker->GetLightMaps(renderer))
  {
    // (The atlas's units first: a page table takes a unit only where one is left.)
    maps.Atlas->Activate();
    u.TextureUnit.push_back(maps.Atlas->GetTextureUnit());
    u.NearestUnit.push_back(this->BindNearest(
      static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow()), maps.Atlas));
    this->PackMaps(maps, viewToWorld);
#if CSM_COMPARISON_TECHNIQUES
    this->PackComparison(maps, viewToWorld);
#endif
    signature += std::to_string(maps.LightIndex) + ";";
  }
  if (this->NearestSampler)
  {
    // (Raw depths for the gather; else one texel's compare.)
    glSamplerParameteri(this->NearestSampler, GL_TEXTURE_COMPARE_MODE,
      this->GatherThisFrame ? GL_NONE : GL_COMPARE_REF_TO_TEXTURE);
  }
  // The kernel, its size (for few lights), the debug view and the gather are compiled into the
  // lookup (see csmShadowFS.glsl).
  signature += this->GatherThisFrame ? " gather" : "";
  signature += " pages";
  for (size_t j = 0; j < u.Lights(); ++j)
  {
    signature += u.Paged(j) ? " 1" : " 0";
  }
  signature += " kernel " + std::to_string(this->PCFKernel) + " debug " +
    std::to_string(this->DebugMode) + (this->SingleMapShaders() ? " single map" : "");
#if CSM_COMPARISON_TECHNIQUES
  signature += std::string(u.Faces ? " faces" : "") + (u.CameraSpace ? " camera space" : "");
#endif
  if (this->ConstantKernelSize())
  {
    signature += " radius " + std::to_string(this->PCFSize / 2);
  }
  signature += " from behind " +
    csmPropDigest(renderer, [baker](vtkProp* prop) { return baker->DrawsFromBehind(prop); });
  signature += " translucent " +
    csmPropDigest(
      renderer, [](vtkProp* prop) { return prop->HasTranslucentPolygonalGeometry() != 0; });
  // A frame drawn as the last one reads the factors that frame stored at its pixels: the same
  // shaders, options and shadow darkness.
  std::ostringstream key;
  key << signature << " options " << this->GetMTime();
  for (const float attenuation : u.Attenuation)
  {
    key << " " << attenuation;
  }
  vtkOpenGLRenderWindow* window = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  // (With several processes no frame is planned as the last one: each sees only its own props.)
  vtkMultiProcessController* controller = baker->GetController();
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1;
  this->ScreenMode = this->ScreenCache->Begin(renderer, window,
    baker->GetLastFrameStatistics().AsLastFrame, static_cast<int>(u.Lights()),
    this->ReuseShadowFactors && this->DebugMode == DEBUG_OFF && !distributed, key.str(),
    [this, window](int samples) { return this->ScreenShadersCompile(window, samples); });
  signature += " screen " + std::to_string(this->ScreenMode) + " samples " +
    std::to_string(this->ScreenCache->GetSamples());
  if (signature != this->ShaderSignature)
  {
    this->ShaderSignature = signature;
    this->ShaderTime.Modified();
  }

  this->PreRender(s);
  this->UpdateGeometry(renderer, s->GetFrameBuffer());
  this->PostRender(s);
  baker->SetFactorsHeldFor(this->ScreenCache->End() ? renderer : nullptr);
  this->UnbindNearest(window);
  for (const auto& maps : baker->GetLightMaps(renderer))
  {
    maps.Atlas->Deactivate();
    if (maps.Pages.TableTexture)
    {
      maps.Pages.TableTexture->Deactivate();
    }
  }
  vtkOpenGLCheckErrorMacro("failed after rendering with cascaded shadows");
}

bool vtkCascadedShadowMapPass::SingleMapShaders() const
{
  const ShaderUniforms& u = this->Uniforms;
#if CSM_COMPARISON_TECHNIQUES
  if (u.Faces)
  {
    return false; // (face partitions choose their map by half-spaces)
  }
#endif
  return this->SingleMapLookup &&
    std::all_of(u.Count.begin(), u.Count.end(), [](int count) { return count <= 1; });
}

bool vtkCascadedShadowMapPass::GatherTexels()
{
  return samplerObjects() && GLEW_ARB_texture_gather;
}

std::string vtkCascadedShadowMapPass::GatherDeclarations(bool gather)
{
  return gather ? "#extension GL_ARB_texture_gather : require\n#define CSM_GATHER 1\n"
                : "#define CSM_GATHER 0\n";
}

int vtkCascadedShadowMapPass::BindNearest(vtkOpenGLRenderWindow* window, vtkTextureObject* atlas)
{
  // The atlas on a second unit with a sampler object for the per-texel compares at texel
  // centres: one that does not compare, whose gather reads the four texels of a bilinear
  // footprint at once (GatherTexels), or else one that reads one texel a compare (nearest), not
  // a bilinear compare's four.
  vtkTextureUnitManager* units = window ? window->GetTextureUnitManager() : nullptr;
  const int unit = units && samplerObjects() ? units->Allocate() : -1;
  if (unit < 0)
  {
    this->GatherThisFrame = false; // (the atlas's own unit compares)
    return atlas->GetTextureUnit();
  }
  if (!this->NearestSampler)
  {
    GLuint sampler = 0;
    glGenSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    this->NearestSampler = sampler;
  }
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, atlas->GetHandle());
  glBindSampler(static_cast<GLuint>(unit), this->NearestSampler);
  this->NearestUnits.push_back(unit);
  return unit;
}

void vtkCascadedShadowMapPass::UnbindNearest(vtkOpenGLRenderWindow* window)
{
  for (const int unit : this->NearestUnits)
  {
    glBindSampler(static_cast<GLuint>(unit), 0);
    window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, 0);
    window->GetTextureUnitManager()->Free(unit);
  }
  this->NearestUnits.clear();
  if (this->NearestSampler)
  {
    // (One a frame: a sampler object belongs to the context of the frame.)
    GLuint sampler = this->NearestSampler;
    glDeleteSamplers(1, &sampler);
    this->NearestSampler = 0;
  }
}

bool vtkCascadedShadowMapPass::PreReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper*, vtkProp*)
{
  // Our declarations go beside the lights' (VTK's place for a shadow pass's); written in the
  // post hook, once the mapper has said whether it draws impostors.
  if (this->Uniforms.Lights() > 0)
  {
    vtkShaderProgram::Substitute(
      fragmentShader, "//VTK::Light::Dec", std::string(kShadowDec) + "\n//VTK::Light::Dec", false);
  }
  return true;
}

bool vtkCascadedShadowMapPass::PostReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop)
{
  if (this->Uniforms.Lights() == 0)
  {
    return true;
  }
  if (fragmentShader.find(kVertexVC) == std::string::npos)
  {
    // Unlit: no view-space position, no lights to shadow.
    vtkShaderProgram::Substitute(fragmentShader, kShadowDec, "", false);
    return true;
  }
  // Tubes and spheres (VTK's impostors) receive on the surface they show, not on their quad.
  const bool impostor = fragmentShader.find("uniform float ZCalcR") != std::string::npos &&
    fragmentShader.find("normalVCVSOutput") != std::string::npos;
  std::ostringstream decl;
  decl << vtkCascadedShadowMapPass::GetShaderDefinitions(static_cast<int>(this->Uniforms.Lights()),
    this->PCFKernel, this->DebugMode, this->ConstantKernelSize() ? this->PCFSize / 2 : -1);
  // Surfaces compare each texel with their plane's depth at its centre; impostors (whose
  // surface is not what the maps hold) take hardware bilinear compares.
  decl << "#define CSM_PLANE_TAPS " << (impostor ? 0 : 1) << "\n"
       << "#define CSM_SINGLE_MAP " << (this->SingleMapShaders() ? 1 : 0) << "\n";
  const int screen =
    impostor || !screenCapable(fragmentShader, prop) ? csmScreenCache::OFF : this->ScreenMode;
  decl << "#define CSM_SCREEN " << screen << "\n"
       << "#define CSM_SCREEN_SAMPLES " << this->ScreenCache->GetSamples() << "\n";
#if CSM_COMPARISON_TECHNIQUES
  decl << this->ComparisonDefinitions();
#endif
  if (impostor)
  {
    decl << "#define CSM_IMPOSTOR\n";
    if (fragmentShader.find("gl_PointCoord") != std::string::npos)
    {
      decl << "#define CSM_IMPOSTOR_SPHERE\n";
    }
  }
  decl << csmShadowFS << "\n";
  for (size_t j = 0; j < this->Uniforms.Lights(); ++j)
  {
    decl << "uniform sampler2DShadow csmMap" << j << ";\n";
    decl << "uniform csmTexelSampler csmNearest" << j << ";\n";
    if (this->Uniforms.Paged(j))
    {
      decl << "uniform sampler2D csmPages" << j << ";\n";
    }
  }
  const std::string mapperName = mapper ? mapper->GetClassName() : "a mapper";
  if (!vtkShaderProgram::Substitute(fragmentShader, kShadowDec, decl.str(), false))
  {
    this->ReportOnce(mapperName +
      "'s fragment shader has no //VTK::Light::Dec: its props are "
      "drawn without shadows");
    return true;
  }
  this->InjectLookups(fragmentShader, mapperName, impostor, screen);
  if (this->DebugMode != DEBUG_OFF)
  {
    vtkShaderProgram::Substitute(fragmentShader, kLightImpl,
      "//VTK::Light::Impl\n  gl_FragData[0] = csmDebugColor(gl_FragData[0], csmResult0);\n", false);
  }
  return true;
}

void vtkCascadedShadowMapPass::InjectLookups(
  std::string& fragmentShader, const std::string& mapperName, bool impostor, int screen)
{
  // Screen derivatives where control flow is still uniform; the lookup itself only where the
  // light reaches the surface (df > 0: behind it, diffuse and specular are 0 anyway), or always
  // for the debug views.
  const std::string reaches = this->DebugMode == DEBUG_OFF ? "df > 0.0" : "true";
  // The extensions and the gather's #define right after the #version VTK's shader cache puts
  // there (every shader it compiles has the tag, so the sampler of the per-texel compares' unit
  // and the GLSL agree).
  vtkShaderProgram::Substitute(fragmentShader, kSystemDec,
    std::string(kSystemDec) + "\n" +
      (screen != csmScreenCache::OFF
          ? vtkCascadedShadowMapPass::ScreenExtensions(this->ScreenCache->GetSamples())
          : std::string()) +
      vtkCascadedShadowMapPass::GatherDeclarations(this->GatherThisFrame),
    false);
  std::ostringstream impl;
  impl << kVertexVC
       << (screen == csmScreenCache::READ
              ? "\n  vec4 csmCached = csmScreenRead();\n"
              : "\n  vec4 csmDVCdx = dFdx(vertexVC);\n  vec4 csmDVCdy = dFdy(vertexVC);\n");
  for (size_t j = 0; j < this->Uniforms.Lights(); ++j)
  {
    impl << "  vec4 csmResult" << j << " = vec4(1.0, -1.0, 0.0, 1.0);\n";
  }
  vtkShaderProgram::Substitute(fragmentShader, kVertexVC, impl.str(), false);
  for (size_t j = 0; j < this->Uniforms.Lights(); ++j)
  {
    const std::string k = std::to_string(this->Uniforms.LightIndex[j]);
    const std::string result = "csmResult" + std::to_string(j);
    const std::string map =
      "csmMap" + std::to_string(j) + ", csmNearest" + std::to_string(j) + ", " + std::to_string(j);
    // (Impostors of a paged light read its base map.)
    const std::string paged = "csmMap" + std::to_string(j) + ", csmNearest" + std::to_string(j) +
      ", csmPages" + std::to_string(j) + ", " + std::to_string(j);
    const std::string lookup = result +
      (screen == csmScreenCache::READ ? " = csmShadowRead(csmCached, " + std::to_string(j) + ");"
          : impostor ? " = csmImpostorShadow(" + map + ", vertexVC, normalVCVSOutput);"
          : this->Uniforms.Paged(j)
          ? " = csmPagedShadow(" + paged + ", vertexVC, csmDVCdx, csmDVCdy);"
          : " = csmShadow(" + map + ", vertexVC, csmDVCdx, csmDVCdy);");
    const std::string factor = result + ".x * ";
    // Phong-style lighting (diffuse and specular), or PBR (radiance, directional or positional).
    const bool phong =
      vtkShaderProgram::Substitute(fragmentShader, "diffuse += (df * lightColor" + k + ");",
        "if (" + reaches + ") { " + lookup + " }\n  diffuse += (df * " + factor + "lightColor" + k +
          ");",
        false);
    const bool specular =
      vtkShaderProgram::Substitute(fragmentShader, "specular += (sf * lightColor" + k + ");",
        "specular += (sf * " + factor + "lightColor" + k + ");", false);
    const bool pbr = vtkShaderProgram::Substitute(fragmentShader, "radiance = lightColor" + k + ";",
                       lookup + "\n  radiance = " + factor + "lightColor" + k + ";", false) |
      vtkShaderProgram::Substitute(fragmentShader, "radiance = lightColor" + k + " * attenuation;",
        lookup + "\n  radiance = " + factor + "lightColor" + k + " * attenuation;", false);
    if (!(phong && specular) && !pbr)
    {
      this->ReportOnce("light " + k + "'s shading was not found in " + mapperName +
        "'s fragment shader: it is drawn without that light's shadow");
    }
  }
  if (screen == csmScreenCache::STORE)
  {
    std::string factors = "vec4(";
    for (size_t j = 0; j < static_cast<size_t>(csmScreenCache::MAXIMUM_LIGHTS); ++j)
    {
      factors += (j ? ", " : "") +
        (j < this->Uniforms.Lights() ? "csmResult" + std::to_string(j) + ".x" : std::string("1.0"));
    }
    vtkShaderProgram::Substitute(fragmentShader, kLightImpl,
      std::string(kLightImpl) + "\n  csmScreenStore(" + factors + "));\n", false);
  }
}

std::string vtkCascadedShadowMapPass::ScreenExtensions(int samples)
{
  return std::string("#extension GL_ARB_shader_image_load_store : require\n") +
    (samples > 1 ? "#extension GL_ARB_post_depth_coverage : require\n"
                   "#extension GL_ARB_gpu_shader5 : require\n"
                 : "");
}

bool vtkCascadedShadowMapPass::ScreenShadersCompile(vtkOpenGLRenderWindow* window, int samples)
{
  // The lookup with its store, and the read, each in a program of its own: a driver that names
  // the extensions but does not compile the shaders gets the lookup alone (a mapper whose
  // shader does not compile draws nothing, or worse).
  for (const int mode : { csmScreenCache::STORE, csmScreenCache::READ })
  {
    std::ostringstream fragment;
    fragment << kSystemDec << "\n"
             << vtkCascadedShadowMapPass::ScreenExtensions(samples)
             << vtkCascadedShadowMapPass::GatherDeclarations(GatherTexels())
             << vtkCascadedShadowMapPass::GetShaderDefinitions(1, KERNEL_GRID, DEBUG_OFF, 1)
             << "#define CSM_SCREEN " << mode << "\n#define CSM_SCREEN_SAMPLES " << samples << "\n"
             << csmShadowFS << "\n"
             << csmScreenProbeFS;
    if (!window->GetShaderCache()->ReadyShaderProgram(csmScreenProbeVS, fragment.str().c_str(), ""))
    {
      this->ReportOnce("the shaders that keep a frame's shadow factors for the next do not "
                       "compile here: every frame makes the lookup (ReuseShadowFactors)");
      return false;
    }
  }
  return true;
}

std::string vtkCascadedShadowMapPass::GetShaderDefinitions(
  int lights, int kernel, int debugMode, int pcfRadius)
{
  // The limits and option values the GLSL uses, from their one definition here.
  std::ostringstream decl;
  decl << "#define CSM_LIGHTS " << lights << "\n"
       << "#define CSM_MAX_CASCADES " << kMaxCascades << "\n"
       << "#define CSM_PAGE_TEXELS " << csm::kPageTexels << "\n"
       << "#define CSM_PAGE_BORDER " << csm::kPageBorder << "\n"
       << "#define CSM_PAGE_INTERIOR " << csm::kPageInterior << "\n"
       << "#define CSM_PAGE_TABLE_SIDE " << csm::kPageTableSide << "\n"
       << "#define CSM_PAGE_BAND " << csm::kPageBlendBand << "\n"
       << "#define CSM_KERNEL_GRID " << KERNEL_GRID << "\n"
       << "#define CSM_KERNEL_JITTERED " << KERNEL_JITTERED << "\n"
       << "#define CSM_KERNEL " << kernel << "\n"
       << "#define CSM_DEBUG_CASCADES " << DEBUG_CASCADES << "\n"
       << "#define CSM_DEBUG_ERROR " << DEBUG_ERROR << "\n"
       << "#define CSM_DEBUG_FACTOR " << DEBUG_FACTOR << "\n"
       << "#define CSM_DEBUG " << debugMode << "\n"
       << "#define CSM_SCREEN_OFF " << csmScreenCache::OFF << "\n"
       << "#define CSM_SCREEN_STORE " << csmScreenCache::STORE << "\n"
       << "#define CSM_SCREEN_READ " << csmScreenCache::READ << "\n";
  if (pcfRadius >= 0)
  {
    decl << "#define CSM_PCF_RADIUS " << pcfRadius << "\n";
  }
  return decl.str();
}

#if CSM_COMPARISON_TECHNIQUES
void vtkCascadedShadowMapPass::PackComparison(
  const vtkCascadedShadowMapBakerPass::LightMaps& maps, vtkMatrix4x4* viewToWorld)
{
  ShaderUniforms& u = this->Uniforms;
  const int count = maps.GetNumberOfCascades();
  for (int c = 0; c < kMaxCascades; ++c)
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
    program->SetUniform4fv("csmPlanes", lights * kMaxCascades * 4, u.Planes.data());
  }
  if (u.CameraSpace)
  {
    program->SetUniform1fv("csmDepthW", lights * kMaxCascades, u.DepthW.data());
  }
}
#endif

bool vtkCascadedShadowMapPass::GetLastFrameReusedShadowFactors() const
{
  return this->ScreenMode == csmScreenCache::READ;
}

bool vtkCascadedShadowMapPass::GetLastFrameStoredShadowFactors() const
{
  return this->ScreenMode == csmScreenCache::STORE;
}

bool vtkCascadedShadowMapPass::ConstantKernelSize() const
{
  return this->Uniforms.Lights() <= static_cast<size_t>(MAXIMUM_LIGHTS_WITH_CONSTANT_KERNEL);
}

void vtkCascadedShadowMapPass::ReportOnce(const std::string& message)
{
  if (this->Reported.insert(message).second)
  {
    vtkWarningMacro(<< message);
  }
}

bool vtkCascadedShadowMapPass::SetShaderParameters(
  vtkShaderProgram* program, vtkAbstractMapper*, vtkProp* prop, vtkOpenGLVertexArrayObject*)
{
  if (this->Uniforms.Lights() > 0 && program->IsUniformUsed("csmScreenOrigin"))
  {
    program->SetUniformi("csmScreen", this->ScreenCache->GetImageUnit());
    program->SetUniform2i("csmScreenOrigin", this->ScreenCache->GetOrigin());
  }
  if (this->Uniforms.Lights() == 0 || !program->IsUniformUsed("csmToMap"))
  {
    return true;
  }
  if (program->IsUniformUsed("csmImpostorPixels"))
  {
    float pixels[2];
    csmScreenSizes(prop, pixels);
    program->SetUniform2f("csmImpostorPixels", pixels);
  }
  if (program->IsUniformUsed("csmPCFRadius"))
  {
    program->SetUniformi("csmPCFRadius", this->PCFSize / 2);
  }
  // Per prop: the faces turned toward the light of a closed surface drawn into the maps from
  // behind are compared texel by texel with a share of the constant bias (the lookup tells which
  // way each face turns).
  const bool fromBehind =
    this->ShadowMapBakerPass && this->ShadowMapBakerPass->DrawsFromBehind(prop);
  program->SetUniformf("csmConstantBias", static_cast<float>(this->ConstantBias));
  program->SetUniformf("csmSlopeBias", static_cast<float>(this->SlopeBias));
  program->SetUniformi("csmFromBehind", fromBehind ? 1 : 0);
  program->SetUniformf("csmClosedBiasShare", static_cast<float>(this->ClosedSurfaceBiasFactor));
  program->SetUniformf("csmBlendBand", static_cast<float>(this->BlendBand));
  const ShaderUniforms& u = this->Uniforms;
  const int lights = static_cast<int>(u.Lights());
  for (int j = 0; j < lights; ++j)
  {
    program->SetUniformi(indexed("csmMap", j).c_str(), u.TextureUnit[j]);
    if (program->IsUniformUsed(indexed("csmNearest", j).c_str()))
    {
      program->SetUniformi(indexed("csmNearest", j).c_str(), u.NearestUnit[j]);
    }
  }
  program->SetUniformMatrix4x4v(
    "csmToMap", lights * kMaxCascades, const_cast<float*>(u.ToMap.data()));
  program->SetUniform1fv("csmHandedness", lights * kMaxCascades, u.Handedness.data());
  program->SetUniform1fv("csmBiasShare", lights * kMaxCascades, u.BiasShare.data());
  program->SetUniform4fv("csmTile", lights * kMaxCascades, u.Tile.data());
  program->SetUniform2fv("csmTexel", lights * kMaxCascades, u.Texel.data());
  program->SetUniform1fv("csmSplitFar", lights * kMaxCascades, u.SplitFar.data());
#if CSM_COMPARISON_TECHNIQUES
  this->SetComparisonUniforms(program);
#endif
  program->SetUniform1fv("csmSplitNear", lights, u.SplitNear.data());
  if (program->IsUniformUsed("csmPageDepth"))
  {
    program->SetUniform1iv("csmPageLevels", lights, u.PageLevels.data());
    program->SetUniform1fv("csmPageDepth", lights, u.PageDepth.data());
    program->SetUniform2fv("csmPageVirtual", lights, u.PageVirtual.data());
    program->SetUniform2fv("csmPageTile", lights, u.PageTile.data());
    for (int j = 0; j < lights; ++j)
    {
      if (u.Paged(static_cast<size_t>(j)) && program->IsUniformUsed(indexed("csmPages", j).c_str()))
      {
        program->SetUniformi(indexed("csmPages", j).c_str(), u.PageUnit[static_cast<size_t>(j)]);
      }
    }
  }
  program->SetUniform1iv("csmCount", lights, u.Count.data());
  program->SetUniform1fv("csmAttenuation", lights, u.Attenuation.data());
  return true;
}

vtkCascadedShadowMapPass* vtkCascadedShadowMapPass::UseShadowsOn(vtkRenderer* renderer)
{
  if (!renderer)
  {
    return nullptr;
  }
  // Already on (a chain an earlier call installed): that pass, its options kept.
  vtkCameraPass* installed = vtkCameraPass::SafeDownCast(renderer->GetPass());
  vtkSequencePass* sequenceOn =
    installed ? vtkSequencePass::SafeDownCast(installed->GetDelegatePass()) : nullptr;
  vtkRenderPassCollection* on = sequenceOn ? sequenceOn->GetPasses() : nullptr;
  for (int i = 0; on && i < on->GetNumberOfItems(); ++i)
  {
    if (auto* pass = vtkCascadedShadowMapPass::SafeDownCast(on->GetItemAsObject(i)))
    {
      return pass;
    }
  }
  vtkNew<vtkCascadedShadowMapPass> shadows;
  vtkNew<vtkRenderPassCollection> passes;
  passes->AddItem(shadows->GetShadowMapBakerPass());
  passes->AddItem(shadows);
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(passes);
  vtkNew<vtkCameraPass> cameraPass;
  cameraPass->SetDelegatePass(sequence);
  renderer->SetPass(cameraPass);
  return shadows; // kept alive by the renderer's pass chain
}

void vtkCascadedShadowMapPass::UseShadowsOff(vtkRenderer* renderer)
{
  if (renderer)
  {
    renderer->SetPass(nullptr);
  }
}

void vtkCascadedShadowMapPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->ScreenCache->ReleaseGraphicsResources(w);
  if (this->ShadowMapBakerPass)
  {
    this->ShadowMapBakerPass->ReleaseGraphicsResources(w);
  }
}

void vtkCascadedShadowMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PCFSize: " << this->PCFSize << "\n";
  os << indent << "PCFKernel: " << (this->PCFKernel == KERNEL_GRID ? "grid" : "jittered") << "\n";
  os << indent << "ConstantBias: " << this->ConstantBias << "\n";
  os << indent << "SlopeBias: " << this->SlopeBias << "\n";
  os << indent << "ClosedSurfaceBiasFactor: " << this->ClosedSurfaceBiasFactor << "\n";
  os << indent << "BlendBand: " << this->BlendBand << "\n";
  os << indent << "ShadowDarkness: " << this->ShadowDarkness << "\n";
  os << indent << "DebugMode: " << this->DebugMode << "\n";
  os << indent << "ReuseShadowFactors: " << (this->ReuseShadowFactors ? "on" : "off") << "\n";
  os << indent << "SingleMapLookup: " << (this->SingleMapLookup ? "on" : "off") << "\n";
  os << indent << "ShadowMapBakerPass: " << this->ShadowMapBakerPass << "\n";
  if (this->ShadowMapBakerPass)
  {
    this->ShadowMapBakerPass->PrintSelf(os, indent.GetNextIndent());
  }
}
