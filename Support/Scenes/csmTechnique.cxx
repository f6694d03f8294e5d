// SPDX-License-Identifier: BSD-3-Clause
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

std::string NoComparisonTechniques(const std::string& what)
{
  return what +
    ": this build has no comparison techniques (configure with "
    "-DCSM_COMPARISON_TECHNIQUES=ON)";
}

ShadowOptions::ShadowOptions()
{
  static const ShadowOptions defaults(vtkNew<vtkCascadedShadowMapPass>().GetPointer());
  *this = defaults;
}

ShadowOptions::ShadowOptions(vtkCascadedShadowMapPass* pass)
{
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  this->Warp = baker->GetPlanner()->GetWarpMode();
  this->Partition = baker->GetPlanner()->GetSplitScheme();
  this->Cascades = baker->GetPlanner()->GetNumberOfCascades();
  this->Lambda = baker->GetPlanner()->GetLambda();
  this->Alpha = baker->GetPlanner()->GetAlpha();
  this->Resolution = baker->GetResolution();
  this->ErrorTarget = baker->GetPlanner()->GetErrorTarget();
  this->AdaptiveCascades = baker->GetPlanner()->GetAdaptiveCascades();
  this->CullClosedCasters = baker->GetCullClosedCasters();
  this->CompactCasters = baker->GetCompactCasters();
  this->CullCastersWithoutReceivers = baker->GetCullCastersWithoutReceivers();
  this->VisibleDepthFit = baker->GetVisibleDepthFit();
  this->VisibleFootprintFit = baker->GetVisibleFootprintFit();
  this->SceneFittedCascades = baker->GetPlanner()->GetSceneFittedCascades();
  this->MoveKeptMaps = baker->GetMoveKeptMaps();
  this->LightSpacePages = baker->GetLightSpacePages();
#if CSM_COMPARISON_TECHNIQUES
  this->FacePartitions = baker->GetPlanner()->GetFacePartitions();
  this->CameraSpace = baker->GetPlanner()->GetCameraSpace();
  this->CameraSpaceFocus = baker->GetPlanner()->GetCameraSpaceFocus();
#endif
  this->DepthClamp = baker->GetPlanner()->GetDepthClamp();
  this->PCF = pass->GetPCFSize();
  this->Kernel = pass->GetPCFKernel();
  this->ConstantBias = pass->GetConstantBias();
  this->SlopeBias = pass->GetSlopeBias();
  this->ClosedSurfaceBiasFactor = pass->GetClosedSurfaceBiasFactor();
  this->Blend = pass->GetBlendBand();
  this->Darkness = pass->GetShadowDarkness();
  this->Debug = pass->GetDebugMode();
  this->ReuseShadowFactors = pass->GetReuseShadowFactors();
}

void Configure(vtkCascadedShadowMapPass* pass, const ShadowOptions& o)
{
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SetWarpMode(o.Warp);
  baker->GetPlanner()->SetSplitScheme(o.Partition);
  baker->GetPlanner()->SetNumberOfCascades(o.Cascades);
  baker->GetPlanner()->SetLambda(o.Lambda);
  baker->GetPlanner()->SetAlpha(o.Alpha);
  baker->SetResolution(o.Resolution);
  baker->GetPlanner()->SetErrorTarget(o.ErrorTarget);
  baker->GetPlanner()->SetAdaptiveCascades(o.AdaptiveCascades);
  baker->SetCullClosedCasters(o.CullClosedCasters);
  baker->SetCompactCasters(o.CompactCasters);
  baker->SetCullCastersWithoutReceivers(o.CullCastersWithoutReceivers);
  baker->SetVisibleDepthFit(o.VisibleDepthFit);
  baker->SetVisibleFootprintFit(o.VisibleFootprintFit);
  baker->GetPlanner()->SetSceneFittedCascades(o.SceneFittedCascades);
  baker->SetMoveKeptMaps(o.MoveKeptMaps);
  baker->SetLightSpacePages(o.LightSpacePages);
#if CSM_COMPARISON_TECHNIQUES
  baker->GetPlanner()->SetFacePartitions(o.FacePartitions);
  baker->GetPlanner()->SetCameraSpace(o.CameraSpace);
  baker->GetPlanner()->SetCameraSpaceFocus(o.CameraSpaceFocus);
#endif
  baker->GetPlanner()->SetDepthClamp(o.DepthClamp);
  pass->SetPCFSize(o.PCF);
  pass->SetPCFKernel(o.Kernel);
  pass->SetConstantBias(o.ConstantBias);
  pass->SetSlopeBias(o.SlopeBias);
  pass->SetClosedSurfaceBiasFactor(o.ClosedSurfaceBiasFactor);
  pass->SetBlendBand(o.Blend);
  pass->SetShadowDarkness(o.Darkness);
  pass->SetDebugMode(o.Debug);
  pass->SetReuseShadowFactors(o.ReuseShadowFactors);
}

vtkSmartPointer<vtkRenderPass> BuildChain(const ShadowOptions& o, Installed& installed)
{
  installed = Installed();
  vtkSmartPointer<vtkOpenGLRenderPass> shadows;
  vtkRenderPass* baker = nullptr;
  if (o.Technique == "csm")
  {
    auto pass = vtkSmartPointer<vtkCascadedShadowMapPass>::New();
    Configure(pass, o);
    baker = pass->GetShadowMapBakerPass();
    installed.Cascaded = pass;
    shadows = pass;
  }
  else if (o.Technique == "vtk")
  {
    // VTK's own pair, as its documentation and tests use it.
    auto pass = vtkSmartPointer<vtkShadowMapPass>::New();
    pass->GetShadowMapBakerPass()->SetResolution(o.Resolution);
    baker = pass->GetShadowMapBakerPass();
    installed.Vtk = pass;
    shadows = pass;
  }
  else
  {
    return nullptr;
  }
  vtkNew<vtkRenderPassCollection> passes;
  passes->AddItem(baker);
  passes->AddItem(shadows);
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(passes);
  auto cameraPass = vtkSmartPointer<vtkCameraPass>::New();
  cameraPass->SetDelegatePass(sequence);
  return cameraPass;
}

Installed InstallTechnique(vtkRenderer* renderer, const ShadowOptions& o)
{
  Installed installed;
  vtkSmartPointer<vtkRenderPass> chain = BuildChain(o, installed);
  renderer->SetPass(chain);
  return installed;
}

} // namespace csmScenes
