# SPDX-License-Identifier: BSD-3-Clause
"""Cascaded generalized-LiSPSM shadow maps for VTK.

    from cascadedshadows import vtkCascadedShadowMapPass
    vtkCascadedShadowMapPass.UseShadowsOn(renderer)

The classes: vtkCascadedShadowMapPass (the lookup, a drop-in for vtkShadowMapPass),
vtkCascadedShadowMapBakerPass (the maps, for vtkShadowMapBakerPass) and
vtkCascadedShadowMapPlanner (the cascades of a light for a camera).
"""
# The passes are OpenGL passes: VTK's OpenGL factory overrides (vtkRenderWindow,
# vtkPolyDataMapper, ...) must be registered, as importing vtkRenderingOpenGL2 does.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from .vtkRenderingCascadedShadows import (  # noqa: F401
    vtkCascadedShadowMapBakerPass,
    vtkCascadedShadowMapPass,
    vtkCascadedShadowMapPlanner,
)

__all__ = [
    "vtkCascadedShadowMapBakerPass",
    "vtkCascadedShadowMapPass",
    "vtkCascadedShadowMapPlanner",
]
