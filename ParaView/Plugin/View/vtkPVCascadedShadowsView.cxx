// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPVCascadedShadowsView.h"

#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightKit.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"

vtkStandardNewMacro(vtkPVCascadedShadowsView);

vtkPVCascadedShadowsView::vtkPVCascadedShadowsView()
{
  this->ShadowPass = vtkSmartPointer<vtkCascadedShadowMapPass>::New();
  this->UpdateShadowSequence();
  // ParaView owns the renderer's pass chain (camera pass, FXAA, image processing, IceT):
  // our passes go below its camera pass, where vtkPVDefaultPass would otherwise be.
  this->SynchronizedRenderers->SetRenderPass(this->ShadowSequence);

  // The light kit's camera lights, read from a scratch renderer; the key light is the brightest
  // (fill and back lights are the key light's intensity divided by ratios >= 1).
  vtkNew<vtkRenderer> probe;
  this->LightKit->AddLightsToRenderer(probe);
  vtkLight* key = nullptr;
  vtkCollectionSimpleIterator it;
  vtkLightCollection* kit = probe->GetLights();
  kit->InitTraversal(it);
  while (vtkLight* light = kit->GetNextLight(it))
  {
    if (light->LightTypeIsCameraLight() && (!key || light->GetIntensity() > key->GetIntensity()))
    {
      key = light;
    }
  }
  kit->InitTraversal(it);
  while (vtkLight* light = kit->GetNextLight(it))
  {
    if (light->LightTypeIsCameraLight() && light != key)
    {
      this->FillAndBackLights->AddItem(light);
    }
  }
  this->UpdateLightKitShadows();
}

vtkPVCascadedShadowsView::~vtkPVCascadedShadowsView()
{
  if (this->SynchronizedRenderers->GetRenderPass() == this->ShadowSequence)
  {
    this->SynchronizedRenderers->SetRenderPass(nullptr);
  }
  if (vtkRenderWindow* window = this->GetRenderWindow())
  {
    this->ShadowPass->ReleaseGraphicsResources(window); // the maps of every shadowed light
  }
}

void vtkPVCascadedShadowsView::SetShadowPass(vtkCascadedShadowMapPass* pass)
{
  if (!pass || pass == this->ShadowPass)
  {
    return;
  }
  if (vtkRenderWindow* window = this->GetRenderWindow())
  {
    this->ShadowPass->ReleaseGraphicsResources(window);
  }
  this->ShadowPass = pass;
  this->UpdateShadowSequence();
  this->Modified();
}

vtkCascadedShadowMapPass* vtkPVCascadedShadowsView::GetShadowPass()
{
  return this->ShadowPass;
}

void vtkPVCascadedShadowsView::UpdateShadowSequence()
{
  vtkRenderPass* baker = this->ShadowPass->GetShadowMapBakerPass();
  if (baker == this->SequencedBaker && this->ShadowSequence->GetPasses() &&
    this->ShadowSequence->GetPasses()->IsItemPresent(this->ShadowPass))
  {
    return;
  }
  vtkNew<vtkRenderPassCollection> passes;
  if (baker)
  {
    passes->AddItem(baker);
  }
  passes->AddItem(this->ShadowPass);
  this->ShadowSequence->SetPasses(passes);
  this->SequencedBaker = baker;
}

void vtkPVCascadedShadowsView::Render(bool interactive, bool skip_rendering)
{
  this->UpdateShadowSequence(); // the pass may have been given another baker

  // Distributed rendering: every rank renders its own piece, in step with the others, so the
  // maps must hold the casters of all ranks. Otherwise (one process, or local rendering on the
  // client or on rank 0 alone) no collective calls may happen.
  const bool distributed = interactive ? this->GetUseDistributedRenderingForLODRender()
                                       : this->GetUseDistributedRenderingForRender();
  if (vtkCascadedShadowMapBakerPass* baker = this->ShadowPass->GetShadowMapBakerPass())
  {
    baker->SetController(distributed ? vtkMultiProcessController::GetGlobalController() : nullptr);
  }
  this->Superclass::Render(interactive, skip_rendering);
}

void vtkPVCascadedShadowsView::Update()
{
  this->Superclass::Update(); // recomputes RenderEmptyImages from the representations
  this->RenderEmptyImages = this->RenderEmptyImages || this->CascadedShadows;
}

void vtkPVCascadedShadowsView::SetCascadedShadows(bool on)
{
  if (this->CascadedShadows == on)
  {
    return;
  }
  this->CascadedShadows = on;
  this->RenderEmptyImages = this->RenderEmptyImages || on; // see Update()
  // Leave a pass someone else installed (OSPRay, value capture) alone: ParaView restores the
  // pass it saved, which is ours or the default one.
  vtkRenderPass* current = this->SynchronizedRenderers->GetRenderPass();
  if (current == nullptr || current == this->ShadowSequence)
  {
    this->SynchronizedRenderers->SetRenderPass(on ? this->ShadowSequence.GetPointer() : nullptr);
  }
  this->Modified();
}

void vtkPVCascadedShadowsView::SetShadowedLights(int mode)
{
  mode = mode == ALL_LIGHTS ? ALL_LIGHTS : KEY_LIGHT;
  if (this->ShadowedLights == mode)
  {
    return;
  }
  this->ShadowedLights = mode;
  this->UpdateLightKitShadows();
  this->Modified();
}

void vtkPVCascadedShadowsView::UpdateLightKitShadows()
{
  // A light's ShadowAttenuation scales its shadow (vtkCascadedShadowMapPass): 0 casts none.
  vtkCollectionSimpleIterator it;
  this->FillAndBackLights->InitTraversal(it);
  while (vtkLight* light = this->FillAndBackLights->GetNextLight(it))
  {
    light->SetShadowAttenuation(this->ShadowedLights == ALL_LIGHTS ? 1.0f : 0.0f);
  }
}

void vtkPVCascadedShadowsView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CascadedShadows: " << (this->CascadedShadows ? "on" : "off") << "\n";
  os << indent << "Light kit lights with shadows: "
     << (this->ShadowedLights == ALL_LIGHTS ? "all" : "key light only") << " ("
     << this->FillAndBackLights->GetNumberOfItems() << " fill and back lights)\n";
  os << indent << "ShadowPass:\n";
  this->ShadowPass->PrintSelf(os, indent.GetNextIndent());
}
