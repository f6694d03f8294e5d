# SPDX-License-Identifier: BSD-3-Clause
"""Structures that none of the bench scenes is: thin bars and lattices to measure on.

    /usr/bin/python3 scripts/make-structures.py OUTPUT_FOLDER
    build/Examples/csm-bench --walk --scenes OUTPUT_FOLDER/scaffold.vtp,...

Writes four .vtp files, each one closed surface per bar (capped tubes) and boxes:
bridge.vtp, a Warren truss bridge (60 m span, 10 panels, bars of 0.3 m) on two piers;
bridge-far.vtp, the same 3,000 km from the origin; scaffold.vtp, a scaffold of 6 x 5 x 3 bays of
2 m in tubes of 48 mm with planks; piperack.vtp, twelve frames carrying six pipes of 0.3-1 m.
"""
import sys

from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTubeFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkCylinderSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def bars(segments, radius, sides=8):
    """Capped tubes along the segments ((a, b) point pairs)."""
    points, lines = vtkPoints(), vtkCellArray()
    for a, b in segments:
        lines.InsertNextCell(2)
        lines.InsertCellPoint(points.InsertNextPoint(a))
        lines.InsertCellPoint(points.InsertNextPoint(b))
    polydata = vtkPolyData()
    polydata.SetPoints(points)
    polydata.SetLines(lines)
    tubes = vtkTubeFilter()
    tubes.SetInputData(polydata)
    tubes.SetRadius(radius)
    tubes.SetNumberOfSides(sides)
    tubes.CappingOn()
    tubes.Update()
    return tubes.GetOutput()


def box(centre, size):
    source = vtkCubeSource()
    source.SetCenter(centre)
    source.SetXLength(size[0])
    source.SetYLength(size[1])
    source.SetZLength(size[2])
    source.Update()
    return source.GetOutput()


def moved(polydata, translate=(0, 0, 0), rotate_z=0.0):
    transform = vtkTransform()
    transform.Translate(translate)
    transform.RotateZ(rotate_z)
    apply = vtkTransformPolyDataFilter()
    apply.SetTransform(transform)
    apply.SetInputData(polydata)
    apply.Update()
    return apply.GetOutput()


def write(path, parts, offset=(0, 0, 0)):
    append = vtkAppendPolyData()
    for part in parts:
        append.AddInputData(part)
    append.Update()
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(moved(append.GetOutput(), offset))
    if not writer.Write():
        sys.exit("cannot write " + path)
    print(path)


def bridge():
    panels, span, height, width = 10, 60.0, 6.0, 8.0
    step = span / panels
    segments = []
    for z in (0.0, width):
        for i in range(panels):
            x0, x1, xm = i * step, (i + 1) * step, (i + 0.5) * step
            segments += [((x0, 0, z), (x1, 0, z)), ((x0, 0, z), (xm, height, z)),
                         ((xm, height, z), (x1, 0, z))]
            if i < panels - 1:
                segments.append(((xm, height, z), (xm + step, height, z)))
    for i in range(panels + 1):
        segments.append(((i * step, 0, 0), (i * step, 0, width)))
    for i in range(panels):
        xm = (i + 0.5) * step
        segments += [((xm, height, 0), (xm, height, width)),
                     ((xm - step / 2, 0, 0), (xm + step / 2, 0, width))]
    parts = [bars(segments, 0.15), box((span / 2, -0.3, width / 2), (span, 0.3, width - 1))]
    parts += [box((x, -5, width / 2), (2, 10, width + 2)) for x in (0.0, span)]
    return parts


def scaffold():
    nx, ny, nz, bay = 6, 5, 3, 2.0
    segments = []
    for i in range(nx + 1):
        for k in range(nz + 1):
            segments.append(((i * bay, 0, k * bay), (i * bay, ny * bay, k * bay)))
    for j in range(1, ny + 1):
        y = j * bay
        for i in range(nx):
            for k in range(nz + 1):
                segments.append(((i * bay, y, k * bay), ((i + 1) * bay, y, k * bay)))
            segments.append(((i * bay, y - bay, 0), ((i + 1) * bay, y, 0)))
        for i in range(nx + 1):
            for k in range(nz):
                segments.append(((i * bay, y, k * bay), (i * bay, y, (k + 1) * bay)))
    parts = [bars(segments, 0.024)]
    parts += [box(((i + 0.5) * bay, j * bay + 0.03, bay / 2), (bay * 0.95, 0.05, bay * 0.9))
              for j in range(1, ny + 1) for i in range(nx)]
    return parts


def piperack():
    segments = []
    for f in range(12):
        x = f * 6.0
        segments += [((x, 0, 0), (x, 8, 0)), ((x, 0, 6), (x, 8, 6)), ((x, 4, 0), (x, 4, 6)),
                     ((x, 8, 0), (x, 8, 6))]
    parts = [bars(segments, 0.2, 4)]
    for radius, y, z in ((0.3, 4.5, 1), (0.2, 4.4, 2), (0.5, 4.7, 3.2), (0.15, 4.35, 4.5),
                         (0.4, 8.6, 1.5), (0.25, 8.45, 4)):
        pipe = vtkCylinderSource()
        pipe.SetRadius(radius)
        pipe.SetHeight(70)
        pipe.SetResolution(24)
        pipe.CappingOn()
        pipe.Update()
        parts.append(moved(pipe.GetOutput(), (33, y, z), 90.0))
    return parts


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1].rstrip("/")
    write(folder + "/bridge.vtp", bridge())
    write(folder + "/bridge-far.vtp", bridge(), (3.0e6, 1.0e5, -2.0e6))
    write(folder + "/scaffold.vtp", scaffold())
    write(folder + "/piperack.vtp", piperack())


if __name__ == "__main__":
    main()
