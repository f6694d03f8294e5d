// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPVCascadedShadowsView
 * @brief   ParaView's render view with cascaded shadow maps.
 *
 * Installs sequence{ vtkCascadedShadowMapBakerPass, vtkCascadedShadowMapPass } as the render
 * pass of ParaView's synchronized renderers, that is below ParaView's own camera pass (and any
 * image-processing or FXAA pass ParaView puts above it). With shadows off the view is exactly
 * ParaView's render view (vtkPVDefaultPass). During hardware selection the passes draw what
 * the default pass draws (they render plainly while the renderer has a selector), so picking
 * keeps working. In distributed rendering (pvserver or pvbatch on several MPI ranks) each rank
 * draws its own casters into the maps, which the baker combines across the ranks.
 *
 * Shadowed lights: scene and camera lights that are on (the headlight never, as in VTK).
 * ParaView's light kit has a headlight and four camera lights; by default only its key light
 * casts shadows (ShadowedLights = KEY_LIGHT), as a sun would, while its fill and back lights,
 * which stand in for indirect light, do not (their ShadowAttenuation is set to 0; the baker still
 * renders their maps). Lights added in ParaView's Light Inspector cast shadows when they are
 * scene or camera lights.
 */
#ifndef vtkPVCascadedShadowsView_h
#define vtkPVCascadedShadowsView_h

#include "vtkNew.h"                     // for members
#include "vtkPVCascadedShadowsModule.h" // for export macro
#include "vtkPVRenderView.h"
#include "vtkSmartPointer.h" // for members

class vtkCascadedShadowMapPass;
class vtkLightCollection;
class vtkRenderPass;
class vtkSequencePass;

class VTKPVCASCADEDSHADOWS_EXPORT vtkPVCascadedShadowsView : public vtkPVRenderView
{
public:
  static vtkPVCascadedShadowsView* New();
  vtkTypeMacro(vtkPVCascadedShadowsView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Cascaded shadows on (default) or off (ParaView's default pass).
  virtual void SetCascadedShadows(bool on);
  vtkGetMacro(CascadedShadows, bool);
  ///@}

  enum ShadowedLightsModes
  {
    KEY_LIGHT = 0, ///< of the light kit, only the key light casts shadows
    ALL_LIGHTS = 1 ///< the key, fill and back lights of the light kit cast shadows
  };
  ///@{
  /// Which lights of the light kit cast shadows. Default KEY_LIGHT.
  virtual void SetShadowedLights(int mode);
  vtkGetMacro(ShadowedLights, int);
  ///@}

  ///@{
  /**
   * The shadow pass the view renders with, and with it its baker
   * (GetShadowPass()->GetShadowMapBakerPass()): the sequence { baker, pass } is the view's
   * render pass. The view creates one; the server manager sets the pass of the view proxy's
   * ShadowPass subproxy, whose properties (the pass's and its baker's options, with their
   * defaults) the view proxy exposes (CascadedShadowsView.xml).
   */
  virtual void SetShadowPass(vtkCascadedShadowMapPass* pass);
  vtkCascadedShadowMapPass* GetShadowPass();
  ///@}

protected:
  vtkPVCascadedShadowsView();
  ~vtkPVCascadedShadowsView() override;

  /// Gives the baker the global controller while this render is distributed, else none.
  void Render(bool interactive, bool skip_rendering) override;
  /// Asks IceT to render on every rank, also those with nothing in view: the baker's
  /// collective calls need all of them.
  void Update() override;
  void UpdateLightKitShadows();
  /// Makes the sequence { baker, pass } of the current pass and its current baker.
  void UpdateShadowSequence();

  bool CascadedShadows = true;
  int ShadowedLights = KEY_LIGHT;
  vtkNew<vtkLightCollection> FillAndBackLights; // the light kit's camera lights but the key light
  vtkSmartPointer<vtkCascadedShadowMapPass> ShadowPass;
  vtkNew<vtkSequencePass> ShadowSequence;  // { baker, shadow pass }
  vtkRenderPass* SequencedBaker = nullptr; // the baker in ShadowSequence (compared only)

private:
  vtkPVCascadedShadowsView(const vtkPVCascadedShadowsView&) = delete;
  void operator=(const vtkPVCascadedShadowsView&) = delete;
};

#endif
