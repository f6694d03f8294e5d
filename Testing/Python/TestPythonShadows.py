# SPDX-License-Identifier: BSD-3-Clause
"""The Python package in a plain VTK script: a box over a ground plane, a scene light.

The ground's pixels are compared with the ground rendered alone (no box, no pass): with
vtkCascadedShadowMapPass.UseShadowsOn(renderer) at least MIN_SHADOWED of them are darker (the
box's shadow), without the pass none. The box's own pixels are left out (a mask drawn with the
box alone). Also checks that the module's classes are there with every public Set/Get/Use
method of their headers (Module/*.h), that the internal caster pass is not, and that options
set from Python reach the passes. Prints "FAIL: ..." and exits 1 on a
failure.
"""
import os
import re
import sys

from cascadedshadows import (vtkCascadedShadowMapBakerPass, vtkCascadedShadowMapPass,
                             vtkCascadedShadowMapPlanner)
import cascadedshadows
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow)

from csmPythonTesting import darkened, grab

MIN_SHADOWED = 1000  # the box's shadow darkens about 1600 ground pixels of the 320x240 picture
failures = []


def check(condition, message):
    if not condition:
        print("FAIL: " + message)
        failures.append(message)


# The wrapped classes, and only those: the casters' pass is internal.
check(not hasattr(cascadedshadows, "vtkCascadedShadowCasterPass"),
      "vtkCascadedShadowCasterPass is wrapped")
check(not hasattr(cascadedshadows.vtkRenderingCascadedShadows, "vtkCascadedShadowCasterPass"),
      "vtkCascadedShadowCasterPass is in the extension module")
# Every option of the C++ headers (their public Set/Get methods and macros) is reachable; those
# under #if CSM_COMPARISON_TECHNIQUES as the build has them (CTest sets the variable: 1 or 0):
# there with it, absent without.
COMPARISON = os.environ.get("CSM_COMPARISON_TECHNIQUES", "0") not in ("", "0", "OFF")


def option_names(code):
    """The public Set/Get/Use names of a header's declarations (comments removed)."""
    public = code.split("protected:")[0]
    names = set()
    for kind, name in re.findall(r"vtk(Set|Get|Boolean)\w*Macro\(\s*(\w+)", public):
        names |= {name + "On", name + "Off"} if kind == "Boolean" else {kind + name}
    names |= set(re.findall(r"\b((?:Set|Get|Use)[A-Z]\w*)\s*\(", public))
    # The baker's per-light map state for the shadow pass (and its structs' own methods) and its
    # frame statistics (C++ structs, for tests and benchmarks), not options; the planner's
    # visible footprint, a struct of the math the baker measures each frame. (The planner's
    # GetNumberOfCascades is checked below.)
    return names - {"GetLightMaps", "GetLastFrameStatistics", "GetCascadeSeconds",
                    "GetNumberOfCascades", "SetVisibleFootprint"}


def split_comparison(code):
    """The code with the comparison techniques' blocks as the build has them, and the code of
    those blocks alone (#if CSM_COMPARISON_TECHNIQUES ... #else ... #endif, nested #if kept)."""
    kept, comparison = [], []
    stack = []  # per open #if: True/False for the option's blocks, None for any other
    for line in code.splitlines():
        directive = line.strip()
        if re.match(r"#\s*if\s+!\s*CSM_COMPARISON_TECHNIQUES\b", directive):
            stack.append(not COMPARISON)
            continue
        if re.match(r"#\s*if\s+CSM_COMPARISON_TECHNIQUES\b", directive):
            stack.append(COMPARISON)
            continue
        if re.match(r"#\s*if", directive):
            stack.append(None)
        elif re.match(r"#\s*else", directive) and stack and stack[-1] is not None:
            stack[-1] = not stack[-1]
            continue
        elif re.match(r"#\s*endif", directive) and stack:
            if stack.pop() is not None:
                continue
        inside = any(state is not None for state in stack)
        (comparison if inside else kept).append(line)
        if inside and all(state is not False for state in stack):
            kept.append(line)
    return "\n".join(kept), "\n".join(comparison)


module_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Module")
for cls in (vtkCascadedShadowMapPass, vtkCascadedShadowMapBakerPass, vtkCascadedShadowMapPlanner):
    header = open(os.path.join(module_dir, cls.__name__ + ".h"), encoding="utf-8").read()
    code = re.sub(r"//[^\n]*|/\*.*?\*/", "", header, flags=re.S)  # declarations, not comments
    kept, comparison = split_comparison(code)
    names = option_names(kept)
    missing = sorted(n for n in names if not hasattr(cls, n))
    check(not missing, "%s lacks %s in Python" % (cls.__name__, ", ".join(missing)))
    if not COMPARISON:
        extra = sorted(n for n in option_names(comparison) - names if hasattr(cls, n))
        check(not extra, "%s has %s in Python in a build without the comparison techniques"
              % (cls.__name__, ", ".join(extra)))
    print("%s: %d options and methods reachable (comparison techniques %s)"
          % (cls.__name__, len(names), "on" if COMPARISON else "off"))

planner = vtkCascadedShadowMapPlanner()
planner.SetWarpMode(vtkCascadedShadowMapPlanner.WARP_LISPSM)
check(planner.GetWarpMode() == vtkCascadedShadowMapPlanner.WARP_LISPSM, "planner warp mode")

ground = vtkPlaneSource()
ground.SetOrigin(-10, 0, -10)
ground.SetPoint1(10, 0, -10)
ground.SetPoint2(-10, 0, 10)
box = vtkCubeSource()
box.SetBounds(-1, 1, 2, 4, -1, 1)
actors = []
renderer = vtkRenderer()
for source in (ground, box):
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    actors.append(actor)
ground_actor, box_actor = actors
sun = vtkLight()
sun.SetLightTypeToSceneLight()
sun.SetPositional(False)
sun.SetPosition(3, 10, 2)
sun.SetFocalPoint(0, 0, 0)
renderer.AddLight(sun)

window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetMultiSamples(0)
window.SetSize(320, 240)
window.AddRenderer(renderer)
camera = renderer.GetActiveCamera()
camera.SetPosition(0, 14, 16)  # looking down at the ground
camera.SetFocalPoint(0, 0, 0)
renderer.ResetCameraClippingRange()

# Reference: the ground alone; the mask: the box alone, unlit white on black.
box_actor.VisibilityOff()
ground_only = grab(window)
box_actor.VisibilityOn()
ground_actor.VisibilityOff()
box_actor.GetProperty().SetLighting(False)
mask = grab(window).sum(axis=2) > 0
box_actor.GetProperty().SetLighting(True)
ground_actor.VisibilityOn()
check(mask.sum() > 100, "the box covers %d pixels" % mask.sum())

without = darkened(grab(window), ground_only, mask)
print("shadowed_pixels_without_pass: %d" % without)
check(without == 0, "%d ground pixels darkened without the pass" % without)

shadows = vtkCascadedShadowMapPass.UseShadowsOn(renderer)
check(isinstance(shadows, vtkCascadedShadowMapPass), "UseShadowsOn returns the pass")
baker = shadows.GetShadowMapBakerPass()
check(isinstance(baker, vtkCascadedShadowMapBakerPass), "the pass has its baker")
baker.GetPlanner().SetNumberOfCascades(3)
baker.GetPlanner().SetErrorTarget(1.0)
shadows.SetPCFSize(5)
shadows.SetPCFKernel(vtkCascadedShadowMapPass.KERNEL_GRID)
check(baker.GetPlanner().GetNumberOfCascades() == 3 and shadows.GetPCFSize() == 5, "options from Python")
check(baker.GetPlanner().GetErrorTarget() == 1.0, "the baker's options reach its planner")

with_pass = darkened(grab(window), ground_only, mask)
print("shadowed_pixels_with_pass: %d" % with_pass)
check(with_pass >= MIN_SHADOWED, "%d shadowed pixels with the pass (at least %d expected)"
      % (with_pass, MIN_SHADOWED))
check(baker.GetPlanner().GetNumberOfPlannedCascades() > 0, "the baker made maps")
# The frame statistics from Python: the grab's frame drew maps; a still frame after it keeps
# every map and draws no texel.
drawn = baker.GetLastFrameCascadesRendered() + baker.GetLastFrameCascadesKept()
check(drawn > 0, "no map in the frame statistics")
for _ in range(2):
    window.Render()
print("still frame: maps rendered %d, kept %d, texels %g"
      % (baker.GetLastFrameCascadesRendered(), baker.GetLastFrameCascadesKept(),
         baker.GetLastFrameTexelsRendered()))
check(baker.GetLastFrameCascadesRendered() == 0 and baker.GetLastFrameCascadesKept() == drawn
      and baker.GetLastFrameTexelsRendered() == 0.0,
      "a still frame drew maps (rendered %d, kept %d, texels %g)"
      % (baker.GetLastFrameCascadesRendered(), baker.GetLastFrameCascadesKept(),
         baker.GetLastFrameTexelsRendered()))
box_actor.SetPosition(0.5, 0.0, 0.0)  # a caster moved: its maps are drawn again
window.Render()
check(baker.GetLastFrameTexelsRendered() > 0.0 and baker.GetLastFrameCascadesRendered() > 0,
      "a moved caster drew no map (texels %g)" % baker.GetLastFrameTexelsRendered())
box_actor.SetPosition(0.0, 0.0, 0.0)

vtkCascadedShadowMapPass.UseShadowsOff(renderer)
after = darkened(grab(window), ground_only, mask)
print("shadowed_pixels_after_UseShadowsOff: %d" % after)
check(after == 0, "%d ground pixels darkened after UseShadowsOff" % after)

if failures:
    sys.exit(1)
print("PASS")
