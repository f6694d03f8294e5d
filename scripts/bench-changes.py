# SPDX-License-Identifier: BSD-3-Clause
"""Data that changes while the camera stays: frame times and texels drawn a step.

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/bench-changes.py [--steps N] [--rounds N]

A field of 1,600 thin columns (16 actors of 10 x 10, 19k triangles) over a ground, 800x600, one
scene light, the camera still. Each kind of change (nothing, new scalars on every actor, a new
colour on every actor, one actor of 16 moved, every point moved) is timed in one process with
the unshadowed frame, VTK's shadow pass as it comes (vtkRenderer::UseShadowsOn), ours
(vtkCascadedShadowMapPass::UseShadowsOn) and ours with ReuseShadowFactors off (every frame makes
the lookup), alternated over rounds; prints each one's median
frame time a step and, for ours, the texels drawn into maps a step against its first frame's.
"""
import argparse
import statistics
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

from cascadedshadows import vtkCascadedShadowMapPass
from csm_bench_scene import ground_and_light, offscreen_window

CHANGES = ("nothing", "scalars", "colour", "one part moved", "every point moved")
KINDS = ("unshadowed", "vtk", "ours", "no reuse")


def build_scene():
    renderer = vtkRenderer()
    parts, fields = [], []
    for p in range(16):
        append = vtkAppendPolyData()
        for i in range(10):
            for j in range(10):
                x, z = (p % 4) * 10 + i, (p // 4) * 10 + j
                column = vtkCubeSource()
                column.SetBounds(x, x + 0.15, 0, 3 + (x * 7 + z * 3) % 5, z, z + 0.15)
                append.AddInputConnection(column.GetOutputPort())
        append.Update()
        data = append.GetOutput()
        field = numpy_to_vtk(np.zeros(data.GetNumberOfPoints(), dtype=np.float32), deep=1)
        field.SetName("field")
        data.GetPointData().SetScalars(field)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(data)
        mapper.SetScalarRange(0, 1)
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
        parts.append((actor, data, field))
    ground_and_light(renderer, -2, 42, (-3, 10, 2))
    window = offscreen_window(renderer, 800, 600)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(20, 30, -15)
    camera.SetFocalPoint(20, 0, 20)
    renderer.ResetCameraClippingRange()
    return renderer, window, parts


def change(kind, step, parts, rng):
    if kind == "scalars":
        for _, _, field in parts:
            vtk_to_numpy(field)[:] = rng.random(field.GetNumberOfTuples()).astype(np.float32)
            field.Modified()
    elif kind == "colour":
        for actor, _, _ in parts:
            actor.GetProperty().SetColor(rng.random(), rng.random(), rng.random())
    elif kind == "one part moved":
        parts[5][0].SetPosition(0.1 * (step % 2), 0, 0.1 * (step % 3))
    elif kind == "every point moved":
        for _, data, _ in parts:
            points = vtk_to_numpy(data.GetPoints().GetData())
            points[:, 1] *= 1.0 + 0.001 * ((step % 2) * 2 - 1)
            data.GetPoints().Modified()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    if args.steps < 2 or args.rounds < 1:
        parser.error("--steps must be at least 2 and --rounds at least 1")
    renderer, window, parts = build_scene()
    rng = np.random.default_rng(1)
    times = {(c, k): [] for c in CHANGES for k in KINDS}
    texels = {c: [] for c in CHANGES}
    first = 0.0
    for _ in range(args.rounds):
        for c in CHANGES:
            for kind in KINDS:
                vtkCascadedShadowMapPass.UseShadowsOff(renderer)
                renderer.UseShadowsOff()
                baker = None
                if kind == "vtk":
                    renderer.UseShadowsOn()
                elif kind in ("ours", "no reuse"):
                    shadows = vtkCascadedShadowMapPass.UseShadowsOn(renderer)
                    shadows.SetReuseShadowFactors(kind == "ours")
                    baker = shadows.GetShadowMapBakerPass() if kind == "ours" else None
                window.Render()
                if baker:
                    first = baker.GetLastFrameTexelsRendered()
                window.Render()
                for step in range(args.steps):
                    change(c, step, parts, rng)
                    start = time.perf_counter()
                    window.Render()
                    times[(c, kind)].append(time.perf_counter() - start)
                    if baker:
                        texels[c].append(baker.GetLastFrameTexelsRendered())
    print("%-18s %12s %10s %10s %9s %9s %10s %16s" % ("change a step", "unshadowed", "vtk", "ours",
                                                        "ours/vtk", "ours/un", "no reuse",
                                                        "texels a step"))
    for c in CHANGES:
        ms = {k: 1000 * statistics.median(times[(c, k)]) for k in KINDS}
        print("%-18s %9.1f ms %7.1f ms %7.1f ms %8.2fx %8.2fx %7.1f ms %7.2f M of %.2f M"
              % (c, ms["unshadowed"], ms["vtk"], ms["ours"], ms["ours"] / ms["vtk"],
                 ms["ours"] / ms["unshadowed"], ms["no reuse"], statistics.mean(texels[c]) / 1e6,
                 first / 1e6))


if __name__ == "__main__":
    main()
