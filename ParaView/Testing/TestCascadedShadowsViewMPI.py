# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch test of the CascadedShadows plugin on 2 MPI ranks (IceT compositing).

    mpiexec -np 2 pvbatch --mpi TestCascadedShadowsViewMPI.py <plugin.so> <output dir>

The box exists on rank 0 only (its source is not parallel); the plane is split between the
ranks (RedistributeDataSet), so most of the box's shadow falls on rank 1's half, which can only
be shadowed when the maps are combined across the ranks. Checks, with numbers:
  1. the render of the split plane equals the render of the same plane kept whole on rank 0
     (share of pixels off by more than PIXEL_TOLERANCE);
  2. the split render shows the shadow: at least MIN_DARKENED pixels darker than with shadows
     off by more than DARKEN_LEVELS.
Exit status 0 on success; every failure prints one line starting with "FAIL".
"""
import os
import sys

import paraview.simple
from paraview.simple import *
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
import numpy

SIZE = [640, 480]
PIXEL_TOLERANCE = 24
MAX_DIFFERENT_SHARE = 0.005
DARKEN_LEVELS = 40
MIN_DARKENED = 4000  # the box's shadow darkens about 5900 pixels

plugin, outdir = sys.argv[1], sys.argv[2]
os.makedirs(outdir, exist_ok=True)
failures = []


def fail(message):
    print("FAIL: " + message)
    failures.append(message)


def screenshot(view, name):
    path = os.path.join(outdir, name)
    Render(view)
    SaveScreenshot(path, view, ImageResolution=SIZE)
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    return pixels.reshape(SIZE[1], SIZE[0], -1)[:, :, :3].astype(numpy.int32)


def luminance(rgb):
    return 0.299 * rgb[:, :, 0] + 0.587 * rgb[:, :, 1] + 0.114 * rgb[:, :, 2]


ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
if ranks != 2:
    fail("running on %d rank(s), not 2: start with mpiexec -np 2 pvbatch --mpi" % ranks)
    sys.exit(1)

LoadPlugin(plugin, remote=False, ns=globals())
paraview.simple._DisableFirstRenderCameraReset()
plane = Plane(Origin=[-6, 0, -6], Point1=[6, 0, -6], Point2=[-6, 0, 6],
              XResolution=40, YResolution=40)
split = RedistributeDataSet(Input=plane)
box = Box(XLength=2, YLength=2, ZLength=2, Center=[2.5, 1.8, 2.5])

view = CreateView("CascadedShadowsView")
view.ViewSize = SIZE
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0.32, 0.34, 0.43]
view.CameraPosition = [9.0, 8.0, 13.0]
view.CameraFocalPoint = [0.0, 0.8, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraViewAngle = 30.0
Show(box, view)

# The plane whole, on rank 0 (where the box is): no combination needed.
Show(plane, view)
whole = screenshot(view, "mpi-whole.png")
Hide(plane, view)
# The plane split between the ranks.
Show(split, view)
shared = screenshot(view, "mpi-split.png")
view.CascadedShadows = 0
unshadowed = screenshot(view, "mpi-split-off.png")

off = numpy.abs(whole - shared).max(axis=2) > PIXEL_TOLERANCE
print("2 ranks: split plane against whole plane: %d pixels (%.4f%%) differ by more than %d levels"
      " (allowed %.2f%%)" % (off.sum(), 100 * off.mean(), PIXEL_TOLERANCE, 100 * MAX_DIFFERENT_SHARE))
if off.mean() > MAX_DIFFERENT_SHARE:
    fail("the split plane's shadows differ from the whole plane's in %.3f%% of the pixels"
         % (100 * off.mean()))
darkened = int((luminance(unshadowed) - luminance(shared) > DARKEN_LEVELS).sum())
print("2 ranks: %d pixels darker by more than %d levels with shadows (need >= %d)"
      % (darkened, DARKEN_LEVELS, MIN_DARKENED))
if darkened < MIN_DARKENED:
    fail("only %d pixels are shadowed on 2 ranks (need >= %d)" % (darkened, MIN_DARKENED))

Delete(view)
if failures:
    print("FAIL: %d check(s) failed" % len(failures))
    sys.exit(1)
print("PASS")
