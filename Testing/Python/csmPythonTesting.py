# SPDX-License-Identifier: BSD-3-Clause
"""What the Python tests share: grabbing a window's picture and counting shadowed pixels."""
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter


def grab(window):
    """Renders the window and returns its picture as a (rows, columns, 3) float array."""
    window.Render()
    grabber = vtkWindowToImageFilter()
    grabber.SetInput(window)
    grabber.ReadFrontBufferOff()
    grabber.Update()
    image = grabber.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return pixels.reshape(height, width, -1)[:, :, :3].astype(float)


def darkened(image, reference, mask=None):
    """Pixels whose luminance (sum of R, G, B) is below 85 % of the reference's, less 6 levels
    (the measure of Testing/Common and the install test), outside mask where one is given."""
    darker = image.sum(axis=2) < 0.85 * reference.sum(axis=2) - 6.0
    if mask is not None:
        darker &= ~mask
    return int(darker.sum())
