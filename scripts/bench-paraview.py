# SPDX-License-Identifier: BSD-3-Clause
"""ParaView playing a time series: the Render View (Cascaded Shadows) against ParaView's own.

    LD_LIBRARY_PATH=build/paraview/prefix/usr/lib/x86_64-linux-gnu \\
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" build/paraview/prefix/usr/bin/pvbatch \\
        scripts/bench-paraview.py build/paraview/lib/paraview-5.11/plugins/CascadedShadows/CascadedShadows.so \\
        [--steps N] [--rounds N]

(build/paraview is what `bash scripts/paraview.sh` or the tests build.) A reader's time series
(a field of 400 thin columns over a ground whose heights change every step, one .vtp file a
step, read as a file series) shown in ParaView's Render View and in ours with its defaults
(the light kit's key light shadowed), with ReuseShadowFactors off (every frame makes the
lookup) and with ShadowedLights = All Lights (the key, fill and two back lights of the light kit); the animation played step by step in each, the views
alternated over rounds in one process; prints each one's median frame a step, a still frame
(the same step again) and its ratio to ParaView's view.
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

from paraview.simple import *
import paraview.simple
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def write_series(folder, steps):
    """One file a step: 20 x 20 columns and a ground; the columns' heights change each step."""
    files = []
    for step in range(steps):
        append = vtkAppendPolyData()
        ground = vtkPlaneSource()
        ground.SetOrigin(-2, 0, -2)
        ground.SetPoint1(22, 0, -2)
        ground.SetPoint2(-2, 0, 22)
        append.AddInputConnection(ground.GetOutputPort())
        for i in range(20):
            for j in range(20):
                column = vtkCubeSource()
                height = 2.0 + 1.5 * (1 + ((i * 7 + j * 3 + step) % 5)) / 5.0
                column.SetBounds(i, i + 0.2, 0, height, j, j + 0.2)
                append.AddInputConnection(column.GetOutputPort())
        append.Update()
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(os.path.join(folder, "columns_%03d.vtp" % step))
        writer.SetInputData(append.GetOutput())
        writer.Write()
        files.append(writer.GetFileName())
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("plugin")
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    if args.steps < 2 or args.rounds < 1:
        parser.error("--steps must be at least 2 and --rounds at least 1")
    if not os.path.isfile(args.plugin):
        parser.error("no plugin at %s" % args.plugin)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    paraview.simple._DisableFirstRenderCameraReset()
    folder = tempfile.mkdtemp(prefix="csm-bench-paraview-")
    reader = OpenDataFile(write_series(folder, args.steps))
    times = list(reader.TimestepValues)
    views = {}
    for kind in ("paraview", "ours", "ours, no reuse", "ours, all lights"):
        view = CreateView("RenderView" if kind == "paraview" else "CascadedShadowsView")
        view.ViewSize = [800, 600]
        view.OrientationAxesVisibility = 0
        view.CameraPosition = [10, 14, -8]
        view.CameraFocalPoint = [10, 0, 10]
        view.CameraViewUp = [0, 1, 0]
        if kind == "ours, all lights":
            view.ShadowedLights = "All Lights"
        if kind == "ours, no reuse":
            view.ReuseShadowFactors = 0  # every frame makes the lookup
        Show(reader, view)
        views[kind] = view
    steps = {kind: [] for kind in views}
    still = {kind: [] for kind in views}
    for _ in range(args.rounds):
        for kind, view in views.items():
            view.ViewTime = times[0]
            Render(view)
            for t in times[1:]:
                view.ViewTime = t
                start = time.perf_counter()
                Render(view)
                steps[kind].append(time.perf_counter() - start)
            for _ in range(3):
                view.StillRender()  # the same step again
                start = time.perf_counter()
                view.StillRender()
                still[kind].append(time.perf_counter() - start)
    base_step = statistics.median(steps["paraview"])
    base_still = statistics.median(still["paraview"])
    print("%-18s %12s %12s %12s %12s" % ("view", "a step", "/ ParaView", "still", "/ ParaView"))
    for kind in views:
        a = statistics.median(steps[kind])
        b = statistics.median(still[kind])
        print("%-18s %9.1f ms %11.2fx %9.1f ms %11.2fx" % (kind, 1000 * a, a / base_step,
                                                          1000 * b, b / base_still))
    for view in views.values():
        Delete(view)
    Delete(reader)
    for name in os.listdir(folder):
        os.remove(os.path.join(folder, name))
    os.rmdir(folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
