// SPDX-License-Identifier: BSD-3-Clause
// Installs a shadow technique on a renderer: ours (cascaded), VTK's own pass, or none.
#pragma once

#include "vtkCascadedShadowsConfigure.h" // for CSM_COMPARISON_TECHNIQUES
#include "vtkSmartPointer.h"

#include <string>

class vtkCascadedShadowMapPass;
class vtkRenderPass;
class vtkRenderer;
class vtkShadowMapPass;

namespace csmScenes
{

/// What a program says when asked for a comparison technique (face partitioning, camera space
/// maps) in a build without them; `what` names the request (a flag and its value).
std::string NoComparisonTechniques(const std::string& what);

/// The options of a technique, as the flags of csm-demo and csm-bench set them. The cascaded
/// pass's options start at the pass's own defaults: a default-constructed ShadowOptions reads
/// them from a new vtkCascadedShadowMapPass and its baker, so they are stated once, in the pass.
struct ShadowOptions
{
  /// Technique csm with every option at the pass's default.
  ShadowOptions();
  /// Technique csm with the options a pass has now (its own and its baker's): what Configure()
  /// would set to give the pass exactly these.
  explicit ShadowOptions(vtkCascadedShadowMapPass* pass);

  std::string Technique = "csm"; ///< csm | vtk | none
  // Set by the constructors:
  int Warp;      ///< vtkCascadedShadowMapPlanner::WarpModes
  int Partition; ///< vtkCascadedShadowMapPlanner::SplitSchemes
  int Cascades;
  double Lambda;
  double Alpha;
  int Resolution;                   ///< also VTK's pass's, for technique vtk
  double ErrorTarget;               ///< resolution from need (0: always Resolution)
  bool AdaptiveCascades;            ///< Cascades: the most; fewer where they meet ErrorTarget
  bool CullClosedCasters;           ///< closed casters drawn into the maps from behind
  bool CompactCasters;              ///< casters drawn into the maps from compact spatial blocks
  bool CullCastersWithoutReceivers; ///< casters that shadow nothing left out of the maps
  bool VisibleDepthFit;             ///< cascades fitted to the depths the view has samples at
  bool VisibleFootprintFit;         ///< ... and to where on the image (VisibleFootprintFit)
  bool SceneFittedCascades;         ///< the farthest cascade may be a map fixed in the world
  bool MoveKeptMaps;                ///< kept maps move with the view (their strips drawn)
  bool LightSpacePages; ///< the scene-fitted map refined by light-space pages where they serve
#if CSM_COMPARISON_TECHNIQUES
  int FacePartitions;      ///< 0 cascades; 1 FP+W, 2 FP+ZP+W (z-partitions per face)
  bool CameraSpace;        ///< camera space shadow maps (general case)
  double CameraSpaceFocus; ///< their focus range, a view depth (0: automatic)
#endif
  int PCF;
  int Kernel; ///< vtkCascadedShadowMapPass::Kernels
  double ConstantBias;
  double SlopeBias;
  double ClosedSurfaceBiasFactor; ///< share of the biases for closed surfaces drawn from behind
  double Blend;
  bool DepthClamp;
  double Darkness;
  int Debug;               ///< vtkCascadedShadowMapPass::DebugModes
  bool ReuseShadowFactors; ///< a frame drawn as the last one reads its factors
};

struct Installed
{
  vtkCascadedShadowMapPass* Cascaded = nullptr; ///< set for technique csm
  vtkShadowMapPass* Vtk = nullptr;              ///< set for technique vtk
};

/// Builds the pass chain of a technique (camera pass -> sequence{ baker, shadow pass }; null
/// for technique none) without installing it; `installed` receives the shadow passes.
vtkSmartPointer<vtkRenderPass> BuildChain(const ShadowOptions& options, Installed& installed);

/// Sets the renderer's pass chain for the technique; returns the passes (owned by the chain).
Installed InstallTechnique(vtkRenderer* renderer, const ShadowOptions& options);

/// Applies the options to an installed cascaded pass (and its baker).
void Configure(vtkCascadedShadowMapPass* pass, const ShadowOptions& options);

} // namespace csmScenes
