# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch test: a README's pvpython snippet, run exactly as written, saves a picture with a shadow.

    pvbatch TestReadmeSnippet.py <README.md> <plugin build dir> <output dir>

Reads the README at test time (so the README cannot drift from what is tested), takes its
```python block that creates the "CascadedShadowsView", and runs it unchanged with exec() in a
fresh directory <output dir>/README or <output dir>/ParaView-README, where "build-paraview" is
a link to <plugin build dir> (the snippet loads the plugin by that relative path, as from the
repository root). Then it checks, with numbers:
  1. the snippet wrote the picture its SaveScreenshot names (a PNG of at least 100x100 pixels);
  2. the same view saved again (nothing changed) is the same picture, to the pixel: the light
     kit's key light follows the camera, and the first screenshot is shadowed from that
     frame's light and fitted to that frame's view, not the one before;
  3. the picture shows a shadow: the same view saved again with the view's CascadedShadows off
     (nothing else changed), compared pixel by pixel, has at least MIN_SHADOWED pixels at least
     DARKER_SHARE darker, and at most MAX_BRIGHTENED pixels that much brighter.
Exit status 0 on success; every failure prints one line starting with "FAIL".
"""
import os
import re
import shutil
import sys
import traceback

from paraview.simple import Delete, GetActiveView, GetViews, SaveScreenshot
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
import numpy

namespace = {"__name__": "__main__"}  # the snippet's globals

DARKER_SHARE = 0.15  # a pixel is shadowed when its luminance drops by at least 15%
MIN_LUMINANCE = 20  # levels (of 255) a pixel needs with shadows off to count (not the black ones)
# The box's shadow on the ground covers 1311 pixels of the 400x400 picture (measured, both
# READMEs; cast by the key light, it drops the luminance by 84% on average).
MIN_SHADOWED = 800
MAX_BRIGHTENED = 20  # shadows never brighten (measured 0)

readme, plugin_build, outdir = (os.path.abspath(a) for a in sys.argv[1:4])
failures = []


def fail(message):
    print("FAIL: " + message)
    failures.append(message)


def finish():
    # pvbatch 5.11 crashes in sys.exit() while views are alive: delete them first.
    namespace.clear()
    for view in GetViews():
        Delete(view)
    if failures:
        print("FAIL: %d check(s) failed for %s" % (len(failures), readme))
        sys.exit(1)
    print("PASS")
    sys.exit(0)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    if width * height <= 1 or image.GetPointData().GetScalars() is None:
        return None
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return pixels.reshape(height, width, -1)[:, :, :3].astype(numpy.float64)


def luminance(rgb):
    return 0.299 * rgb[:, :, 0] + 0.587 * rgb[:, :, 1] + 0.114 * rgb[:, :, 2]


with open(readme, encoding="utf-8") as f:
    blocks = re.findall(r"^```python\n(.*?)^```", f.read(), re.S | re.M)
snippets = [b for b in blocks if 'CreateView("CascadedShadowsView")' in b]
if len(snippets) != 1:
    fail("%s has %d ```python blocks creating the CascadedShadowsView (need exactly 1)"
         % (readme, len(snippets)))
    finish()
snippet = snippets[0]
saved = re.findall(r"SaveScreenshot\(\s*[\"']([^\"']+)[\"']", snippet)
if len(saved) != 1:
    fail("the snippet of %s saves %d pictures by a literal file name (need 1)" % (readme, len(saved)))
    finish()

# README.md -> <output dir>/README, ParaView/README.md -> <output dir>/ParaView-README
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))))
tag = os.path.relpath(readme, root)
tag = os.path.splitext(os.path.basename(readme) if tag.startswith("..") else tag)[0]
tag = tag.replace(os.sep, "-")
workdir = os.path.join(outdir, tag)
shutil.rmtree(workdir, ignore_errors=True)
os.makedirs(workdir)
os.symlink(plugin_build, os.path.join(workdir, "build-paraview"))
with open(os.path.join(workdir, "snippet.py"), "w", encoding="utf-8") as f:
    f.write(snippet)
os.chdir(workdir)
print("running the snippet of %s in %s:\n%s" % (readme, workdir, snippet.rstrip()))

try:
    exec(compile(snippet, readme + " (```python block)", "exec"), namespace)
except Exception:  # the snippet as written fails: say so in one FAIL line, after the traceback
    traceback.print_exc()
    fail("the snippet of %s raises %s" % (readme, sys.exc_info()[1].__class__.__name__))
    finish()

# 1. The picture exists.
picture = os.path.join(workdir, saved[0])
if not os.path.isfile(picture):
    fail("the snippet wrote no %s" % picture)
    finish()
shadowed = read_png(picture)
if shadowed is None or min(shadowed.shape[:2]) < 100:
    fail("%s is not a PNG of at least 100x100 pixels" % picture)
    finish()
print("picture: %s, %dx%d" % (picture, shadowed.shape[1], shadowed.shape[0]))

view = namespace.get("view") or GetActiveView()
if view is None or view.GetXMLName() != "CascadedShadowsView":
    fail("the snippet leaves no CascadedShadowsView")
    finish()

# 2. The same view saved again: the same picture.
again_path = os.path.join(workdir, "again.png")
SaveScreenshot(again_path, view)
again = read_png(again_path)
if again is None or again.shape != shadowed.shape:
    fail("the second picture is %s, the first %s"
         % (None if again is None else again.shape, shadowed.shape))
    finish()
differing = int((numpy.abs(again - shadowed) > 0).any(axis=2).sum())
print("second screenshot: %d pixels differ from the first (need 0)" % differing)
if differing:
    fail("the second screenshot of the same view differs from the first in %d pixels" % differing)

# 3. The same view with the view's shadows off, saved the same way.
view.CascadedShadows = 0
unshadowed_path = os.path.join(workdir, "shadows-off.png")
SaveScreenshot(unshadowed_path, view)
unshadowed = read_png(unshadowed_path)
if unshadowed is None or unshadowed.shape != shadowed.shape:
    fail("the picture with shadows off is %s, with shadows %s"
         % (None if unshadowed is None else unshadowed.shape, shadowed.shape))
    finish()
on, off = luminance(shadowed), luminance(unshadowed)
lit = off >= MIN_LUMINANCE
darker = int((lit & (on <= (1 - DARKER_SHARE) * off)).sum())
brighter = int((lit & (on >= (1 + DARKER_SHARE) * off)).sum())
if darker:
    mask = lit & (on <= (1 - DARKER_SHARE) * off)
    print("shadowed pixels: mean luminance drop %.0f%%, rows %d-%d, columns %d-%d"
          % (100 * (1 - on[mask] / off[mask]).mean(), *numpy.nonzero(mask.any(axis=1))[0][[0, -1]],
             *numpy.nonzero(mask.any(axis=0))[0][[0, -1]]))
print("shadow: %d pixels at least %d%% darker than with shadows off (need >= %d), "
      "%d that much brighter (allowed <= %d)"
      % (darker, 100 * DARKER_SHARE, MIN_SHADOWED, brighter, MAX_BRIGHTENED))
if darker < MIN_SHADOWED:
    fail("the picture shows %d shadowed pixels (need >= %d)" % (darker, MIN_SHADOWED))
if brighter > MAX_BRIGHTENED:
    fail("%d pixels are brighter with shadows (allowed <= %d)" % (brighter, MAX_BRIGHTENED))
finish()
