// SPDX-License-Identifier: BSD-3-Clause
// Checks of scene files before and after VTK's readers see them: a damaged or hostile file gets
// one clear message instead of a crash, a hang or a blank image. Also whether an output path
// can be written, before the work that fills it.
#pragma once

#include <string>

class vtkDataObject;

namespace csmScenes
{

/// Structure of the risky formats against the file size, before any reader runs: the counts
/// in .ply and legacy .vtk headers, a binary .stl's triangle count, a .gltf's JSON and the
/// buffers it refers to. Returns an empty string when the file may be read, else why not.
std::string CheckFileStructure(const std::string& path, const std::string& extension);

/// Whether a program can write the file: an existing file it may write, or a new one in a
/// folder that exists and it may write in. Empty when it can, else why not; checked before any
/// rendering, so that a bad path is found before the work, not after.
std::string CheckOutputFile(const std::string& path);

/// Whether a program can write files in the folder: it exists, is a folder and may be written
/// in. Empty when it can, else why not.
std::string CheckOutputFolder(const std::string& path);

/// What a reader produced, before any filter runs: every cell's point indices within the point
/// count, every point finite. Composite data is checked leaf by leaf. Empty when valid.
std::string CheckReaderOutput(vtkDataObject* data);

} // namespace csmScenes
