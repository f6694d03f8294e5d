# SPDX-License-Identifier: BSD-3-Clause
"""A big mesh whose points move while the camera orbits: compact casters on against off.

    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \\
        scripts/bench-moving-mesh.py [--resolution N] [--frames N] [--every K] [--rounds N]

A sphere of 2 N (N - 2) triangles (N = 1000: 2 M) over a ground, 640x480, one scene light; the
camera orbits 2 degrees a frame and the sphere's points move every K-th frame. Prints the median
frame time with the baker's CompactCasters on and off, alternated over rounds in one process:
a big mesh that keeps changing must cost no more with them on (its preparations given up, not
waited for).
"""
import argparse
import statistics
import time

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

from cascadedshadows import vtkCascadedShadowMapPass
from csm_bench_scene import ground_and_light, offscreen_window


def run(compact, resolution, frames, every):
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(resolution)
    sphere.SetPhiResolution(resolution)
    sphere.SetRadius(2)
    sphere.SetCenter(0, 3, 0)
    sphere.Update()
    data = sphere.GetOutput()
    points = vtk_to_numpy(data.GetPoints().GetData())
    start = points.copy()
    renderer = vtkRenderer()
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(data)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    ground_and_light(renderer, -10, 10, (3, 10, 2))
    window = offscreen_window(renderer, 640, 480)
    baker = vtkCascadedShadowMapPass.UseShadowsOn(renderer).GetShadowMapBakerPass()
    baker.SetCompactCasters(compact)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Dolly(1.5)
    renderer.ResetCameraClippingRange()
    window.Render()
    times = []
    for frame in range(frames):
        if frame % every == 0:
            points[:, 1] = start[:, 1] + 0.05 * (frame % 5)
            data.GetPoints().Modified()
        renderer.GetActiveCamera().Azimuth(2)
        begin = time.perf_counter()
        window.Render()
        times.append(time.perf_counter() - begin)
    vtkCascadedShadowMapPass.UseShadowsOff(renderer)
    window.Finalize()
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--resolution", type=int, default=1000)
    parser.add_argument("--frames", type=int, default=16)
    parser.add_argument("--every", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    if args.resolution < 8 or args.frames < 2 or args.every < 1 or args.rounds < 1:
        parser.error("--resolution >= 8, --frames >= 2, --every >= 1, --rounds >= 1")
    medians = {True: [], False: []}
    for _ in range(args.rounds):
        for compact in (True, False):
            medians[compact].append(run(compact, args.resolution, args.frames, args.every))
    for compact in (True, False):
        print("compact casters %-3s: median frame %s ms" % (
            "on" if compact else "off", " / ".join("%.0f" % (1000 * m) for m in medians[compact])))
    print("on / off: %.2f" % (statistics.median(medians[True]) / statistics.median(medians[False])))


if __name__ == "__main__":
    main()
