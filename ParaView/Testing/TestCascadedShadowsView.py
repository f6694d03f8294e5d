"""pvbatch test of the CascadedShadows plugin.

    pvbatch TestCascadedShadowsView.py <plugin.so> <baseline.png> <output dir>

Renders boxes over a plane in "Render View (Cascaded Shadows)" and checks, with numbers:
  1. the image matches the baseline (share of pixels off by more than PIXEL_TOLERANCE);
  2. shadows appear: against the same view with shadows off, at least MIN_DARKENED pixels are
     darker by more than DARKEN_LEVELS, and at most MAX_BRIGHTENED are brighter;
  3. with shadows off the view draws what ParaView's own Render View draws;
  4. hardware selection (SelectSurfaceCells) picks the same cells as in ParaView's Render View,
     and the image is unchanged after it;
  5. ShadowedLights = All Lights adds the shadows of the light kit's fill and back lights;
  6. the view properties reach the passes (read back from the passes' PrintSelf), and setting
     them back to their defaults gives the first image again.
A missing baseline is written to <output dir> and the test fails: look at it, then copy it.
Exit status 0 on success; every failure prints one line starting with "FAIL".
"""
import os
import re
import sys

import paraview.simple
from paraview.simple import *
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
import numpy

SIZE = [640, 480]
PIXEL_TOLERANCE = 24  # levels (of 255) a pixel may differ from the baseline in any channel
MAX_DIFFERENT_SHARE = 0.005  # share of pixels allowed beyond PIXEL_TOLERANCE
DARKEN_LEVELS = 40  # luminance drop that counts a pixel as shadowed
MIN_DARKENED = 4000  # the key light's shadows darken about 5600 pixels at 640x480
MAX_BRIGHTENED = 50  # shadows never brighten (a few edge pixels may differ)
MIN_MORE_WITH_ALL_LIGHTS = 6000  # fill and back lights darken about 12700 more pixels (box faces)

plugin, baseline, outdir = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(outdir, exist_ok=True)
failures = []


def fail(message):
    print("FAIL: " + message)
    failures.append(message)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return pixels.reshape(height, width, -1)[:, :, :3].astype(numpy.int32)


def luminance(rgb):
    return 0.299 * rgb[:, :, 0] + 0.587 * rgb[:, :, 1] + 0.114 * rgb[:, :, 2]


def build_scene(view):
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.32, 0.34, 0.43]
    view.CameraPosition = [9.0, 8.0, 13.0]
    view.CameraFocalPoint = [0.0, 0.8, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = 30.0


def screenshot(view, name):
    path = os.path.join(outdir, name)
    Render(view)
    SaveScreenshot(path, view, ImageResolution=SIZE)
    return read_png(path)


def compare_to_first(view, tag, what):
    image = screenshot(view, "CascadedShadowsView-%s.png" % tag)
    largest = int(numpy.abs(image - shadowed).max())
    print("%s: largest channel difference to the first render %d (allowed %d)"
          % (what, largest, PIXEL_TOLERANCE))
    if largest > PIXEL_TOLERANCE:
        fail("%s the image differs from the first render by %d levels" % (what, largest))


def selected_plane_cells(view, plane):
    ClearSelection(plane)
    SelectSurfaceCells(Rectangle=[0, 0, SIZE[0] - 1, SIZE[1] - 1], View=view, Modifier=None)
    extract = ExtractSelection(Input=plane)
    extract.UpdatePipeline()
    cells = extract.GetDataInformation().GetNumberOfCells()
    Delete(extract)
    ClearSelection(plane)
    return cells


LoadPlugin(plugin, remote=False, ns=globals())
paraview.simple._DisableFirstRenderCameraReset()  # keep the camera set below

# A plane of 20x20 cells (for selection), a floating box, a standing column.
plane = Plane(Origin=[-6, 0, -6], Point1=[6, 0, -6], Point2=[-6, 0, 6],
              XResolution=20, YResolution=20)
floating = Box(XLength=2, YLength=2, ZLength=2, Center=[-1.0, 2.0, 0.5])
column = Box(XLength=1, YLength=4, ZLength=1, Center=[2.5, 2.0, -1.5])
sources = [plane, floating, column]

view = CreateView("CascadedShadowsView")
if view.SMProxy.GetXMLLabel() != "Render View (Cascaded Shadows)":
    fail("the view is labelled %r" % view.SMProxy.GetXMLLabel())
build_scene(view)
for source in sources:
    Show(source, view)

# 1. Against the baseline.
shadowed = screenshot(view, "CascadedShadowsView.png")
if not os.path.exists(baseline):
    fail("no baseline %s; this run's image is %s: look at it, then copy it there"
         % (baseline, os.path.join(outdir, "CascadedShadowsView.png")))
else:
    expected = read_png(baseline)
    if expected.shape != shadowed.shape:
        fail("image is %s, baseline is %s" % (shadowed.shape, expected.shape))
    else:
        off = numpy.abs(expected - shadowed).max(axis=2) > PIXEL_TOLERANCE
        share = off.mean()
        print("baseline: %d pixels (%.4f%%) differ by more than %d levels (allowed %.2f%%)"
              % (off.sum(), 100 * share, PIXEL_TOLERANCE, 100 * MAX_DIFFERENT_SHARE))
        if share > MAX_DIFFERENT_SHARE:
            fail("image differs from the baseline in %.3f%% of the pixels" % (100 * share))

# 2. Shadows appear: darkened pixels against the same view with shadows off.
view.CascadedShadows = 0
unshadowed = screenshot(view, "CascadedShadowsView-off.png")
drop = luminance(unshadowed) - luminance(shadowed)
darkened = int((drop > DARKEN_LEVELS).sum())
brightened = int((drop < -DARKEN_LEVELS).sum())
print("shadows: %d pixels darker by more than %d levels (need >= %d), %d brighter (allowed <= %d)"
      % (darkened, DARKEN_LEVELS, MIN_DARKENED, brightened, MAX_BRIGHTENED))
if darkened < MIN_DARKENED:
    fail("only %d pixels are shadowed (need >= %d)" % (darkened, MIN_DARKENED))
if brightened > MAX_BRIGHTENED:
    fail("%d pixels are brighter with shadows (allowed <= %d)" % (brightened, MAX_BRIGHTENED))

# 3. Shadows off is ParaView's own render view.
plain = CreateView("RenderView")
build_scene(plain)
for source in sources:
    Show(source, plain)
reference = screenshot(plain, "RenderView.png")
largest = int(numpy.abs(reference - unshadowed).max())
print("shadows off against ParaView's Render View: largest channel difference %d (allowed %d)"
      % (largest, PIXEL_TOLERANCE))
if largest > PIXEL_TOLERANCE:
    fail("with shadows off the view differs from ParaView's Render View by %d levels" % largest)

# 4. Hardware selection works as in ParaView's Render View and leaves the shadows intact.
view.CascadedShadows = 1
ours = selected_plane_cells(view, plane)
theirs = selected_plane_cells(plain, plane)
print("selection: %d plane cells picked in the shadow view, %d in Render View" % (ours, theirs))
if ours != theirs or ours == 0:
    fail("selection picked %d cells, Render View %d" % (ours, theirs))
compare_to_first(view, "after-selection", "after a selection")

# 5. The fill and back lights of the light kit cast shadows on request.
view.ShadowedLights = "All Lights"
all_lights = screenshot(view, "CascadedShadowsView-all-lights.png")
more = int((luminance(shadowed) - luminance(all_lights) > DARKEN_LEVELS).sum())
print("all lights of the light kit: %d more pixels darker by more than %d levels (need >= %d)"
      % (more, DARKEN_LEVELS, MIN_MORE_WITH_ALL_LIGHTS))
if more < MIN_MORE_WITH_ALL_LIGHTS:
    fail("the fill and back lights cast no shadows (%d pixels)" % more)
view.ShadowedLights = "Key Light"
compare_to_first(view, "key-light-again", "after ShadowedLights All -> Key")

# 6. Properties reach the passes, and setting them back gives the first image again: first the
# options that keep the size of the maps, then the two that reallocate them.
# name: (documented default, a different value, what the passes' PrintSelf then shows)
settings = {"WarpMode": ("Generalized", "LiSPSM", "WarpMode: lispsm"),
            "SplitScheme": ("Adaptive", "Practical", "SplitScheme: practical"),
            "PCFSize": ("5x5", "3x3", "PCFSize: 3"),
            "ShadowDarkness": (1.0, 0.5, "ShadowDarkness: 0.5"),
            "ShadowDebugMode": ("Off", "Cascades", "DebugMode: 1"),
            "NumberOfCascades": (2, 3, "NumberOfCascades: 3"),
            "ShadowMapResolution": ("2048", "1024", "Resolution: 1024")}
for name, (default, _, _) in settings.items():
    start = view.GetProperty(name).GetData()
    if start != default:
        fail("property %s starts at %s, documented default %s" % (name, start, default))
for group in (("WarpMode", "SplitScheme", "PCFSize", "ShadowDarkness", "ShadowDebugMode"),
              ("NumberOfCascades",), ("ShadowMapResolution",)):
    for name in group:
        setattr(view, name, settings[name][1])
    Render(view)
    state = str(view.GetClientSideObject())
    for name in group:
        if settings[name][2] not in state:
            fail("property %s = %s did not reach the passes (no '%s' in their PrintSelf)"
                 % (name, settings[name][1], settings[name][2]))
    baked = re.findall(r"ShadowedLights: (\d+)", state)
    print("passes: %s; lights with maps: %s" % (
        ", ".join(settings[name][2] for name in group if settings[name][2] in state), baked))
    for name in group:
        setattr(view, name, settings[name][0])
    changes = ", ".join("%s %s" % (name, settings[name][1]) for name in group)
    compare_to_first(view, "restored-" + group[0], "after %s and back" % changes)

Delete(plain)
Delete(view)
if failures:
    print("FAIL: %d check(s) failed" % len(failures))
    sys.exit(1)
print("PASS")
