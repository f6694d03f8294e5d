#include "csmTechnique.h"

#include "vtkCameraPass.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkNew.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"
#include "vtkShadowMapBakerPass.h"
#include "vtkShadowMapPass.h"

namespace csmScenes
{

void Configure(vtkCascadedShadowMapPass* pass, const ShadowOptions& o)
{
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetWarpMode(o.Warp);
  baker->SetSplitScheme(o.Partition);
  baker->SetNumberOfCascades(o.Cascades);
  baker->SetLambda(o.Lambda);
  baker->SetAlpha(o.Alpha);
  baker->SetResolution(o.Resolution);
  baker->SetDepthClamp(o.DepthClamp);
  pass->SetPCFSize(o.PCF);
  pass->SetPCFKernel(o.Kernel);
  pass->SetConstantBias(o.ConstantBias);
  pass->SetSlopeBias(o.SlopeBias);
  pass->SetBlendBand(o.Blend);
  pass->SetShadowDarkness(o.Darkness);
  pass->SetDebugMode(o.Debug);
}

Installed InstallTechnique(vtkRenderer* renderer, const ShadowOptions& o)
{
  Installed installed;
  if (o.Technique == "csm")
  {
    installed.Cascaded = vtkCascadedShadowMapPass::UseShadowsOn(renderer);
    Configure(installed.Cascaded, o);
  }
  else if (o.Technique == "vtk")
  {
    // VTK's own pair, as its documentation and tests use it.
    vtkNew<vtkShadowMapPass> shadows;
    shadows->GetShadowMapBakerPass()->SetResolution(o.Resolution);
    vtkNew<vtkRenderPassCollection> passes;
    passes->AddItem(shadows->GetShadowMapBakerPass());
    passes->AddItem(shadows);
    vtkNew<vtkSequencePass> sequence;
    sequence->SetPasses(passes);
    vtkNew<vtkCameraPass> cameraPass;
    cameraPass->SetDelegatePass(sequence);
    renderer->SetPass(cameraPass);
    installed.Vtk = shadows;
  }
  else
  {
    renderer->SetPass(nullptr);
  }
  return installed;
}

} // namespace csmScenes
