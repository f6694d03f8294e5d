// Installs a shadow technique on a renderer: ours (cascaded), VTK's own pass, or none.
#pragma once

#include "vtkSmartPointer.h"

#include <string>

class vtkCascadedShadowMapPass;
class vtkRenderPass;
class vtkRenderer;
class vtkShadowMapPass;

namespace csmScenes
{

struct ShadowOptions
{
  std::string Technique = "csm"; ///< csm | vtk | none
  int Warp = 3;                  ///< vtkCascadedShadowMapPlanner::WarpModes
  int Partition = 4;             ///< vtkCascadedShadowMapPlanner::SplitSchemes
  int Cascades = 2;
  double Lambda = 0.5;
  double Alpha = 2.0;
  int Resolution = 2048;
  int PCF = 5;
  int Kernel = 0;
  double ConstantBias = 0.002;
  double SlopeBias = 1.5;
  double Blend = 0.05;
  bool DepthClamp = true;
  double Darkness = 1.0;
  int Debug = 0;
  bool PassDefaults = false; ///< csm: leave every option at the pass's own default (ignore the above)
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
