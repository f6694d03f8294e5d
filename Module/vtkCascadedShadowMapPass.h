// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowMapPass
 * @brief   Renders the scene with cascaded shadow maps: a drop-in for vtkShadowMapPass.
 *
 * Reads the maps of its vtkCascadedShadowMapBakerPass and injects the lookup into every
 * polydata mapper's fragment shader: the cascade is picked by view depth (Lloyd et al. §6.3),
 * the map is sampled with texel-space PCF whose taps are virtual samples on the receiver plane
 * (Barroso & Celes §2.2) with constant and slope-scaled bias, and cascades are blended over a
 * narrow band. Each shadowed light's factor multiplies that light's diffuse and specular terms
 * (and the PBR radiance), never the ambient light. Outside every cascade a surface is lit as
 * without shadows. Opaque and translucent props, volumes and overlays are drawn as the renderer
 * would; while a hardware selector is active the pass renders exactly like the renderer without
 * shadows, so picking keeps working.
 *
 * Use it like VTK's pair:
 * @code
 * vtkNew<vtkCascadedShadowMapPass> shadows;
 * vtkNew<vtkSequencePass> seq;  // { shadows->GetShadowMapBakerPass(), shadows }
 * vtkNew<vtkCameraPass> cameraPass; cameraPass->SetDelegatePass(seq);
 * renderer->SetPass(cameraPass);
 * @endcode
 * or in one call: vtkCascadedShadowMapPass::UseShadowsOn(renderer).
 */
#ifndef vtkCascadedShadowMapPass_h
#define vtkCascadedShadowMapPass_h

#include "vtkCascadedShadowsSetMacro.h" // for vtkSetFiniteClampMacro
#include "vtkOpenGLRenderPass.h"
#include "vtkRenderingCascadedShadowsModule.h" // for export macro
#include "vtkSmartPointer.h"                   // for members

#include <memory> // for members
#include <set>    // for members
#include <string> // for members
#include <vector> // for members

#include "vtkCascadedShadowMapBakerPass.h" // for GetShadowMapBakerPass() options
class csmScreenCache;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;

class VTKRENDERINGCASCADEDSHADOWS_EXPORT vtkCascadedShadowMapPass : public vtkOpenGLRenderPass
{
public:
  static vtkCascadedShadowMapPass* New();
  vtkTypeMacro(vtkCascadedShadowMapPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /// The pass that renders the maps this pass reads. Created by default.
  vtkGetObjectMacro(ShadowMapBakerPass, vtkCascadedShadowMapBakerPass);
  virtual void SetShadowMapBakerPass(vtkCascadedShadowMapBakerPass* baker);
  ///@}

  ///@{
  /// PCF kernel width in texels of the cascade: 1, 3, 5 or 7 (even values round up). Default 3
  /// (Barroso & Celes 2007, §4 use 3x3 to 5x5; 3x3 takes 4 bilinear taps where 5x5 takes 9, and
  /// misclassifies fewer pixels than 5x5 on the bench scenes; 1 hardens the edges:
  /// Documentation/Tried.md, "Lookup cost and PCF").
  virtual void SetPCFSize(int size);
  vtkGetMacro(PCFSize, int);
  ///@}

  /// Up to this many shadowed lights the PCF kernel's size is compiled into the lookup (its
  /// loops unroll: ~10 % of a still frame on llvmpipe); beyond it, a uniform, because the
  /// unrolled taps of many lights make a shader too slow to compile. Changing PCFSize then
  /// rebuilds the shaders.
  static constexpr int MAXIMUM_LIGHTS_WITH_CONSTANT_KERNEL = 4;

  /// The #defines the pass prepends to the lookup (Module/glsl/csmShadowFS.glsl): the limits
  /// and option values it uses, for `lights` shadowed lights, a kernel (Kernels), a debug mode
  /// (DebugModes) and the PCF radius compiled in (-1: the uniform csmPCFRadius).
  static std::string GetShaderDefinitions(int lights, int kernel, int debugMode, int pcfRadius);
  /// Can the current context read the per-texel compares' four texels with one gather
  /// (CSM_GATHER in csmShadowFS.glsl), and the #extension and #define that say whether a
  /// shader does.
  static bool GatherTexels();
  static std::string GatherDeclarations(bool gather);

  enum Kernels
  {
    KERNEL_GRID = 0,    ///< regular grid of taps one texel apart
    KERNEL_JITTERED = 1 ///< jittered circular kernel, unaligned virtual samples
  };
  ///@{
  /// PCF kernel shape. Default KERNEL_GRID.
  vtkSetClampMacro(PCFKernel, int, KERNEL_GRID, KERNEL_JITTERED);
  vtkGetMacro(PCFKernel, int);
  ///@}

  ///@{
  /// Constant depth bias, in the map's [0,1] depth (Barroso & Celes Table 1 (a)); a scene-fitted
  /// map, whose depth is the whole scene along the light, and its light-space pages take a share
  /// by their texel (csm::sceneFittedBiasShare). Default 0.002.
  vtkSetFiniteClampMacro(ConstantBias, double, 0.0, 1.0);
  vtkGetMacro(ConstantBias, double);
  ///@}

  ///@{
  /// Slope-scaled bias: times the receiver plane's depth change over one texel, on the faces
  /// whose own depth the maps hold as it is: the faces turned away from the light of a closed
  /// surface drawn from behind (lit at its terminator by an interpolated normal). The faces of
  /// other surfaces meet their own depth pushed back by the baker's PolygonOffset, which scales
  /// with their slope, and take the constant bias only. Default 1.5.
  vtkSetFiniteClampMacro(SlopeBias, double, 0.0, 100.0);
  vtkGetMacro(SlopeBias, double);
  ///@}

  ///@{
  /**
   * Share of ConstantBias for the faces turned toward the light of surfaces whose lit side is
   * not in the maps: closed surfaces that the baker draws with only their faces turned away
   * from the light (vtkCascadedShadowMapBakerPass::DrawsFromBehind). Those faces never meet
   * their own depth in the map, only the far side of their own solid or, along a concave crease
   * or where parts touch, the face that shadows them, which meets them there: a bias only moves
   * the shadow's edge off the crease (a line of light along a fillet's facets, a bar joint, a
   * part on a floor). They take no slope-scaled bias: their lookup compares each texel with the
   * receiver plane's depth at that texel's centre. The share keeps coplanar contact (a part's
   * bottom on another's top) lit against rounding. The lookup tells the way each face turns; the
   * faces turned away (lit at the terminator by an interpolated normal) meet their own depth and
   * take both biases in full. Default 0.01 (Documentation/Tried.md, "Closed casters").
   */
  vtkSetFiniteClampMacro(ClosedSurfaceBiasFactor, double, 0.0, 1.0);
  vtkGetMacro(ClosedSurfaceBiasFactor, double);
  ///@}

  ///@{
  /// Share of each cascade's depth range, at its far end, blended into the next cascade so that
  /// no seam shows; 0 switches blending off. Default 0.05.
  vtkSetFiniteClampMacro(BlendBand, double, 0.0, 0.5);
  vtkGetMacro(BlendBand, double);
  ///@}

  ///@{
  /// How dark a shadow is, 0 (no shadow) .. 1 (light fully blocked). Used when the light's own
  /// ShadowAttenuation is left at its default of 1. Default 1.
  vtkSetFiniteClampMacro(ShadowDarkness, double, 0.0, 1.0);
  vtkGetMacro(ShadowDarkness, double);
  ///@}

  ///@{
  /// A frame drawn as the last one (the same camera, viewport, props, lights and maps: colours,
  /// scalars or materials may have changed) reads each pixel's shadow factors from that frame
  /// instead of making the lookup again, on opaque surfaces, with at most four shadowed lights
  /// (three in a multisampled framebuffer; GL_ARB_shader_image_load_store, and there
  /// GL_ARB_post_depth_coverage and GL_ARB_gpu_shader5). The same image. On.
  vtkSetMacro(ReuseShadowFactors, bool);
  vtkGetMacro(ReuseShadowFactors, bool);
  vtkBooleanMacro(ReuseShadowFactors, bool);
  ///@}

  ///@{
  /// While every shadowed light has at most one map (a scene-fitted map kept across an orbit, a
  /// single cascade), the lookup is compiled without the choice of a cascade: the same image for
  /// less work a pixel. Off: one lookup whatever the count, so that no prop's shader is rebuilt
  /// when a light's count goes to or from one. On.
  vtkSetMacro(SingleMapLookup, bool);
  vtkGetMacro(SingleMapLookup, bool);
  vtkBooleanMacro(SingleMapLookup, bool);
  ///@}

  /// Did the last frame read its shadow factors from the frame before it (no lookup)? Did it
  /// store them for the next (which a renderer whose stored factors went unread does only in a
  /// frame drawn as its last one)?
  bool GetLastFrameReusedShadowFactors() const;
  bool GetLastFrameStoredShadowFactors() const;

  enum DebugModes
  {
    DEBUG_OFF = 0,
    DEBUG_CASCADES = 1, ///< colour by cascade index (first shadowed light)
    DEBUG_ERROR =
      2, ///< heat map of the aliasing error m (Lloyd Eq. 1): blue over-, red undersampled
    DEBUG_FACTOR = 3 ///< the shadow visibility alone, as grey
  };
  ///@{
  /// Debug output. Default DEBUG_OFF.
  vtkSetClampMacro(DebugMode, int, DEBUG_OFF, DEBUG_FACTOR);
  vtkGetMacro(DebugMode, int);
  ///@}

  /**
   * The equivalent of vtkRenderer::UseShadowsOn() for cascaded shadows: installs
   * camera pass -> sequence{ baker, shadow pass } on the renderer and returns the shadow pass
   * (owned by the renderer's pass chain); where an earlier call installed it, returns that
   * pass, its options kept. UseShadowsOff() removes the chain.
   */
  static vtkCascadedShadowMapPass* UseShadowsOn(vtkRenderer* renderer);
  static void UseShadowsOff(vtkRenderer* renderer);

  /// Bumped when the injected shader code changes (lights shadowed, their indices).
  vtkMTimeType GetShaderStageMTime() override;

protected:
  vtkCascadedShadowMapPass();
  ~vtkCascadedShadowMapPass() override;

  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* VAO = nullptr) override;

  vtkCascadedShadowMapBakerPass* ShadowMapBakerPass = nullptr;
  int PCFSize = 3;
  int PCFKernel = KERNEL_GRID;
  double ConstantBias = 0.002;
  double SlopeBias = 1.5;
  double ClosedSurfaceBiasFactor = 0.01;
  double BlendBand = 0.05;
  double ShadowDarkness = 1.0;
  int DebugMode = DEBUG_OFF;
  bool ReuseShadowFactors = true;
  bool SingleMapLookup = true;

  /// What the shader needs this frame, packed as its uniform arrays (light j's cascade c at
  /// 8 j + c): filled once per frame in Render(), only uploaded per draw.
  struct ShaderUniforms
  {
    std::vector<int> LightIndex;  ///< per light: index among the switched-on lights
    std::vector<int> TextureUnit; ///< per light: its atlas
    /// per light: its atlas again, read a texel a compare (the per-texel compares of surfaces,
    /// impostors aside); the atlas's own unit where no sampler object or unit is free
    std::vector<int> NearestUnit;
    std::vector<int> Count;                    ///< per light: cascades
    std::vector<float> SplitNear, Attenuation; ///< per light
    std::vector<float> ToMap;                  ///< per cascade: view -> map, 16 floats column-major
    std::vector<float> Handedness;             ///< per cascade: the sign of ToMap's determinant
    std::vector<float> BiasShare;              ///< per cascade: its share of the constant bias
    std::vector<float> Tile;                   ///< per cascade: atlas offset and scale, 4 floats
    std::vector<float> SplitFar;               ///< per cascade
    std::vector<float>
      Texel; ///< per cascade: one texel along s and t in the cascade's [0,1] coordinates
    /// per light, for light-space pages (0 levels and no unit: none): the levels finer than the
    /// base, the view depth from which the base meets the target, the base's texels along s
    /// and t, a page's side in the atlas's [0, 1], the unit of the page table
    std::vector<int> PageLevels, PageUnit;
    std::vector<float> PageDepth, PageVirtual, PageTile;
    bool Paged(size_t j) const { return j < this->PageUnit.size() && this->PageUnit[j] >= 0; }
    size_t Lights() const { return this->Count.size(); }
#if CSM_COMPARISON_TECHNIQUES
    std::vector<float> Planes; ///< per cascade: 4 view-space half-spaces (face partitions)
    bool Faces = false;        ///< some light's maps are face partitions
    std::vector<float> DepthW; ///< per cascade: a camera space map's smallest w (0: none)
    bool CameraSpace = false;  ///< some light's map is a camera space map
#endif
  };
  ShaderUniforms Uniforms;
  /// The lookup without the cascade choice this frame (SingleMapLookup, every light's count at
  /// most one)?
  bool SingleMapShaders() const;
  /// The units Render() bound the atlases to for NearestUnit, and their sampler object.
  std::vector<int> NearestUnits;
  unsigned int NearestSampler = 0;
  /// This frame's shaders gather the per-texel compares' texels: the context can, and every
  /// light's atlas got a unit of its own for them (else they compare through the atlas's unit).
  bool GatherThisFrame = false;
  int BindNearest(vtkOpenGLRenderWindow* window, vtkTextureObject* atlas);
  void UnbindNearest(vtkOpenGLRenderWindow* window);
  /// Render() with the baker's maps: the uniforms, then the renderer's geometry.
  void DrawShadowed(const vtkRenderState* s);
  /// One light's maps packed into Uniforms (view -> map matrices composed in double).
  void PackMaps(const vtkCascadedShadowMapBakerPass::LightMaps& maps, vtkMatrix4x4* viewToWorld);
  /// The lookup (or the factors read at the pixel, CSM_SCREEN) put into a fragment shader
  /// whose declarations are in: where each light's shading is, and the factors' store.
  void InjectLookups(
    std::string& fragmentShader, const std::string& mapperName, bool impostor, int screen);
  /// The #extension lines of shaders that keep the factors (ReuseShadowFactors) for a
  /// framebuffer of `samples`, and whether such shaders compile in the window's context.
  static std::string ScreenExtensions(int samples);
  bool ScreenShadersCompile(vtkOpenGLRenderWindow* window, int samples);
  std::string ShaderSignature;    // what the injected code is compiled for (lights, kernel, debug)
  std::set<std::string> Reported; // warnings said already: once each
  void ReportOnce(const std::string& message);
  bool ConstantKernelSize() const; // is the PCF radius compiled in (few lights)?
  vtkTimeStamp ShaderTime;
  /// The last frame's factors at its pixels (ReuseShadowFactors) and what this frame's opaque
  /// surfaces do with them (csmScreenCache::Mode).
  std::unique_ptr<csmScreenCache> ScreenCache;
  int ScreenMode = 0;
#if CSM_COMPARISON_TECHNIQUES
  /// The comparison techniques: a light's planes and w packed into Uniforms, the #defines and
  /// GLSL of their lookup (Module/glsl/csmComparisonFS.glsl; empty where no map needs it), and
  /// their uniforms uploaded.
  void PackComparison(
    const vtkCascadedShadowMapBakerPass::LightMaps& maps, vtkMatrix4x4* viewToWorld);
  std::string ComparisonDefinitions() const;
  void SetComparisonUniforms(vtkShaderProgram* program) const;
#endif

private:
  vtkCascadedShadowMapPass(const vtkCascadedShadowMapPass&) = delete;
  void operator=(const vtkCascadedShadowMapPass&) = delete;
};

#endif
