# SPDX-License-Identifier: BSD-3-Clause
"""What the Python benchmarks' scenes share: a ground, one scene light, an offscreen window."""
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401


def ground_and_light(renderer, low, high, light_position):
    """A ground square at y = 0 from (low, low) to (high, high) in x and z, and a directional
    scene light from light_position toward the origin (no automatic lights)."""
    ground = vtkPlaneSource()
    ground.SetOrigin(low, 0, low)
    ground.SetPoint1(high, 0, low)
    ground.SetPoint2(low, 0, high)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(ground.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    renderer.AutomaticLightCreationOff()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(*light_position)
    light.SetFocalPoint(0, 0, 0)
    renderer.AddLight(light)


def offscreen_window(renderer, width, height):
    """An offscreen window without multisampling, rendering the renderer."""
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    return window
