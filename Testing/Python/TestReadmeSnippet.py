# SPDX-License-Identifier: BSD-3-Clause
"""README.md's Python snippet, run exactly as written, writes a picture with a shadow.

    python3 TestReadmeSnippet.py <README.md> <output dir>

Reads the README at test time (so it cannot drift from what is tested), takes the ```python
block of its section "## Python" that imports cascadedshadows, and runs it unchanged with exec()
in <output dir>. Then checks, with numbers:
  1. the snippet wrote the picture it names ("shadows.png", at least 100x100 pixels);
  2. the picture shows a shadow: the snippet's window rendered again with the renderer's pass
     removed (nothing else changed) has at least MIN_SHADOWED pixels darker in the snippet's
     picture, and at most MAX_BRIGHTENED brighter (edge pixels: the snippet's window keeps
     VTK's multisampling, whose edges resolve slightly differently with the pass).
Prints "FAIL: ..." and exits 1 on a failure.
"""
import os
import re
import sys

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from csmPythonTesting import darkened, grab

MIN_SHADOWED = 1000  # the box's shadow darkens about 6300 pixels of the 640x480 picture
MAX_BRIGHTENED = 600  # the box's and the ground's outlines: about 230 pixels

readme, outdir = (os.path.abspath(a) for a in sys.argv[1:3])
text = open(readme, encoding="utf-8").read()
section = re.search(r"^## Python\n(.*?)(?=^## )", text, re.S | re.M)
if not section:
    print("FAIL: no section '## Python' in " + readme)
    sys.exit(1)
blocks = [b for b in re.findall(r"```python\n(.*?)```", section.group(1), re.S)
          if "cascadedshadows" in b]
if len(blocks) != 1:
    print("FAIL: %d python blocks importing cascadedshadows in README's Python section"
          % len(blocks))
    sys.exit(1)

os.makedirs(outdir, exist_ok=True)
os.chdir(outdir)
if os.path.exists("shadows.png"):
    os.remove("shadows.png")
namespace = {"__name__": "__main__"}
exec(compile(blocks[0], readme + " (## Python)", "exec"), namespace)

failures = []
if not os.path.exists("shadows.png"):
    print("FAIL: the snippet wrote no shadows.png")
    sys.exit(1)
reader = vtkPNGReader()
reader.SetFileName("shadows.png")
reader.Update()
width, height, _ = reader.GetOutput().GetDimensions()
if width < 100 or height < 100:
    failures.append("shadows.png is %dx%d" % (width, height))
written = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
written = written.reshape(height, width, -1)[:, :, :3].astype(float)

window, renderer = namespace["window"], namespace["renderer"]
renderer.SetPass(None)
plain = grab(window)
if plain.shape != written.shape:
    failures.append("picture %s against window %s" % (written.shape, plain.shape))
else:
    shadowed = darkened(written, plain)
    brightened = darkened(plain, written)
    print("shadowed_pixels: %d, brightened_pixels: %d" % (shadowed, brightened))
    if shadowed < MIN_SHADOWED:
        failures.append("%d shadowed pixels (at least %d expected)" % (shadowed, MIN_SHADOWED))
    if brightened > MAX_BRIGHTENED:
        failures.append("%d pixels brighter with shadows (at most %d expected)"
                        % (brightened, MAX_BRIGHTENED))
for failure in failures:
    print("FAIL: " + failure)
if failures:
    sys.exit(1)
print("PASS")
