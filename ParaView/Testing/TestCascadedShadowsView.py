# SPDX-License-Identifier: BSD-3-Clause
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
     them back to their defaults gives the first image again;
  7. lines shown with "Render Lines As Tubes" cast shadows as wide as the view draws the tubes:
     three lines 3 units over a plane, LineWidth 12, one oblique directional scene light, seen
     from straight above (parallel projection): the darkened pixels number about as many as
     the tubes' own pixels, lie in the analytic footprint of 12-pixel cylinders, and the same
     lines as 1-pixel hairlines darken far fewer.
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
# 7. Tubes: 3 lines of 320 x 12 pixels (11520 tube pixels, measured) cast 13479 darkened pixels
# (the analytic footprint of the cylinders is 1.12 x the tubes' pixels at the light's 63.4 deg
# across the lines); as 1-pixel lines without tubes they darken 614 (0.05 x).
TUBE_WIDTH = 12  # LineWidth, pixels
TUBE_HEIGHT = 3.0  # lines over the plane, world units
MIN_TUBE_SHADOW = 0.8  # darkened pixels / tube pixels, at least (measured 1.17)
MAX_TUBE_SHADOW = 1.5  # and at most
MIN_IN_FOOTPRINT = 0.95  # share of the darkened pixels within FOOTPRINT_SLACK of the footprint
MIN_FOOTPRINT_DARK = 0.9  # share of the footprint's pixels darkened
FOOTPRINT_SLACK = 3  # pixels
MAX_HAIRLINE_SHADOW = 0.25  # 1-pixel lines: darkened pixels / tube pixels, at most (0.05)

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
            "PCFSize": ("3x3", "5x5", "PCFSize: 5"),
            "ShadowDarkness": (1.0, 0.5, "ShadowDarkness: 0.5"),
            "ShadowDebugMode": ("Off", "Cascades", "DebugMode: 1"),
            "NumberOfCascades": (8, 3, "NumberOfCascades: 3"),
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



# 7. Lines drawn as tubes cast shadows as wide as the tubes.
def tube_footprint(lines, light, ppu, focal):
    """Pixels (rows from the top) of the ground whose ray toward the light meets a tube."""
    rows, cols = numpy.mgrid[0:SIZE[1], 0:SIZE[0]] + 0.5
    gx = focal[0] + (cols - SIZE[0] / 2) / ppu  # screen right is +x, screen down is +z
    gz = focal[2] + (rows - SIZE[1] / 2) / ppu
    radius = TUBE_WIDTH / 2 / ppu
    direction = numpy.array(light, dtype=float) / numpy.linalg.norm(light)
    inside = numpy.zeros(gx.shape, dtype=bool)
    for (x0, y0, z0), (x1, _, _) in lines:
        # The ray g + t * direction meets the axis (parallel to x at height y0, depth z0) closest
        # where its (y, z) comes nearest (y0, z0); a capped cylinder: x there within the ends.
        t = (y0 * direction[1] + (z0 - gz) * direction[2]) / (direction[1] ** 2 + direction[2] ** 2)
        dy, dz = t * direction[1] - y0, gz + t * direction[2] - z0
        x = gx + t * direction[0]
        inside |= (dy * dy + dz * dz <= radius * radius) & (x >= x0 - radius) & (x <= x1 + radius)
    return inside


def dilate(mask, steps):
    out = mask.copy()
    for _ in range(steps):
        grown = out.copy()
        grown[1:, :] |= out[:-1, :]
        grown[:-1, :] |= out[1:, :]
        grown[:, 1:] |= out[:, :-1]
        grown[:, :-1] |= out[:, 1:]
        out = grown
    return out


tube_view = CreateView("CascadedShadowsView")
tube_view.ViewSize = SIZE
tube_view.OrientationAxesVisibility = 0
tube_view.UseColorPaletteForBackground = 0
tube_view.Background = [0.32, 0.34, 0.43]
tube_view.UseLight = 0  # no light kit: one directional scene light, 63.4 deg over the ground
tube_light = [0.3, 2.0, -1.0]  # towards the light; shadows fall 1.5 units to +z, 0.45 to -x
light = AddLight(view=tube_view)
light.Coords = "Scene"
light.Type = "Directional"
light.Position = tube_light
light.FocalPoint = [0.0, 0.0, 0.0]
light.Intensity = 1.0
focal = [0.0, 0.0, 0.5]
tube_view.CameraPosition = [0.0, 20.0, 0.5]  # straight down, screen up = -z, right = +x
tube_view.CameraFocalPoint = focal
tube_view.CameraViewUp = [0.0, 0.0, -1.0]
tube_view.CameraParallelProjection = 1
tube_view.CameraParallelScale = 6.0  # 40 pixels a unit at 640x480
pixels_per_unit = SIZE[1] / (2 * 6.0)
ground = Plane(Origin=[-7, 0, -7], Point1=[7, 0, -7], Point2=[-7, 0, 7])
Show(ground, tube_view)
line_ends = [((-4.0, TUBE_HEIGHT, z), (4.0, TUBE_HEIGHT, z)) for z in (-3.0, 0.0, 3.0)]
line_sources = [Line(Point1=list(a), Point2=list(b)) for a, b in line_ends]
tubes = [Show(source, tube_view) for source in line_sources]
for tube in tubes:
    tube.RenderLinesAsTubes = 1
    tube.LineWidth = TUBE_WIDTH
    tube.AmbientColor = tube.DiffuseColor = [0.9, 0.5, 0.2]


def tube_shots(tag):
    tube_view.CascadedShadows = 1
    on = screenshot(tube_view, "Tubes%s.png" % tag)
    tube_view.CascadedShadows = 0
    off = screenshot(tube_view, "Tubes%s-off.png" % tag)
    return on, off


tubes_on, tubes_off = tube_shots("")
for tube in tubes:
    tube.Visibility = 0
bare = screenshot(tube_view, "Tubes-bare-off.png")
for tube in tubes:
    tube.Visibility = 1
tube_pixels = int((numpy.abs(tubes_off - bare).max(axis=2) > PIXEL_TOLERANCE).sum())
dark = (luminance(tubes_off) - luminance(tubes_on) > DARKEN_LEVELS)[::-1]  # rows from the top
darkened = int(dark.sum())
footprint = tube_footprint(line_ends, tube_light, pixels_per_unit, focal)
in_footprint = int((dark & dilate(footprint, FOOTPRINT_SLACK)).sum())
footprint_dark = int((dark & footprint).sum())
columns = dark[:, SIZE[0] // 2]
runs = numpy.diff(numpy.flatnonzero(numpy.diff(numpy.r_[0, columns.astype(int), 0])))[::2]
print("tubes: %d tube pixels (LineWidth %d); shadows darken %d pixels = %.2f x (need %.2f-%.2f); "
      "shadow widths in the middle column %s pixels"
      % (tube_pixels, TUBE_WIDTH, darkened, darkened / max(tube_pixels, 1), MIN_TUBE_SHADOW,
         MAX_TUBE_SHADOW, runs.tolist()))
print("tubes: analytic footprint %d pixels; %.3f of the darkened pixels within %d pixels of it "
      "(need >= %.2f), %.3f of it darkened (need >= %.2f)"
      % (footprint.sum(), in_footprint / max(darkened, 1), FOOTPRINT_SLACK, MIN_IN_FOOTPRINT,
         footprint_dark / max(footprint.sum(), 1), MIN_FOOTPRINT_DARK))
if tube_pixels < 3 * 300 * TUBE_WIDTH * 0.9:
    fail("the tubes cover only %d pixels" % tube_pixels)
elif not MIN_TUBE_SHADOW * tube_pixels <= darkened <= MAX_TUBE_SHADOW * tube_pixels:
    fail("tube shadows darken %d pixels, %.2f x the tubes' %d (need %.2f-%.2f)"
         % (darkened, darkened / tube_pixels, tube_pixels, MIN_TUBE_SHADOW, MAX_TUBE_SHADOW))
if in_footprint < MIN_IN_FOOTPRINT * darkened:
    fail("only %d of %d darkened pixels lie in the tubes' shadow footprint" % (in_footprint, darkened))
if footprint_dark < MIN_FOOTPRINT_DARK * footprint.sum():
    fail("only %d of the footprint's %d pixels are darkened" % (footprint_dark, footprint.sum()))

for tube in tubes:
    tube.RenderLinesAsTubes = 0
    tube.LineWidth = 1
lines_on, lines_off = tube_shots("-hairlines")
hairline = int((luminance(lines_off) - luminance(lines_on) > DARKEN_LEVELS).sum())
print("hairlines (LineWidth 1, no tubes): %d pixels darkened = %.2f x the tubes' pixels "
      "(allowed <= %.2f)" % (hairline, hairline / max(tube_pixels, 1), MAX_HAIRLINE_SHADOW))
if hairline > MAX_HAIRLINE_SHADOW * tube_pixels:
    fail("1-pixel lines darken %d pixels, as if they were tubes" % hairline)

Delete(tube_view)
Delete(plain)
Delete(view)
if failures:
    print("FAIL: %d check(s) failed" % len(failures))
    sys.exit(1)
print("PASS")
