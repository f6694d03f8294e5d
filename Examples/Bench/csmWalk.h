// SPDX-License-Identifier: BSD-3-Clause
// csm-bench --walk: smooth camera paths close to the geometry, every frame a normal render.
#pragma once

#include "vtkImageData.h"    // for GrabFrame
#include "vtkSmartPointer.h" // for GrabFrame

#include <string>

class vtkRenderWindow;

namespace csmWalk
{
/// Runs the walk benchmark with csm-bench's arguments (--walk and its options); the engine
/// model's path comes from the build. Returns the exit status.
int Run(int argc, char** argv, const std::string& engineModel);
/// The walk's usage: its options with their defaults.
std::string Usage();
/// The image of the frame the window just rendered (not rendered again), as both modes of
/// csm-bench measure it against the truth.
vtkSmartPointer<vtkImageData> GrabFrame(vtkRenderWindow* window);
}
