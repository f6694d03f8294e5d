/**
 * The passes in ../../../Module include the export header of their libvtk9 module,
 * CSM::RenderingCascadedShadows. In the ParaView plugin they are compiled into
 * CSM::PVCascadedShadows, so this header stands in for it and maps the macro.
 */
#ifndef vtkRenderingCascadedShadowsModule_h
#define vtkRenderingCascadedShadowsModule_h

#include "vtkPVCascadedShadowsModule.h"

#define VTKRENDERINGCASCADEDSHADOWS_EXPORT VTKPVCASCADEDSHADOWS_EXPORT

#endif
