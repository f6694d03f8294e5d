// SPDX-License-Identifier: BSD-3-Clause
// Scene generators and loaders for the demo, the image tests and the benchmarks.
#pragma once

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkActor;
class vtkRenderer;
class vtkPolyData;

namespace csmScenes
{

struct Scene
{
  std::string Name;
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  long long Triangles = 0;
  long long Lines = 0; ///< line cells (drawn as tubes where the actor says so)
  // A default view: camera position, focal point, view-up, and a clipping range (0: automatic).
  double CameraPosition[3] = { 0, 0, 1 };
  double FocalPoint[3] = { 0, 0, 0 };
  double ViewUp[3] = { 0, 1, 0 };
  double ClippingRange[2] = { 0, 0 };
  double ViewAngle = 30.0;
};

/// A procedural offshore platform (sea plane, jacket legs and X-braces, two decks, handrails,
/// a lattice derrick, a crane boom, a flare boom, gratings): thin bars and lattices. About
/// targetTriangles triangles (the bar tessellation scales with it), at least ~40k.
/// offset moves the whole scene (points stored in double precision) far from the origin.
Scene Platform(long long targetTriangles = 250000, double offset = 0.0);

/// The same platform as a beam model: its bars (the same list) are line cells drawn as tubes
/// (vtkProperty RenderLinesAsTubes) of a width in pixels, heavy and thin bars in two actors;
/// sea, decks and modules stay triangles. The default widths look like the solid platform's
/// bars at its default view in 800x600. Named "platform-beams".
Scene PlatformBeams(double offset = 0.0, double heavyPixels = 7.0, double thinPixels = 2.0);

/// The most triangles Platform() builds (its bars' finest tessellation).
long long PlatformMaxTriangles();

/// A row of lattice towers along -z every 40 m to the horizon, over a long ground strip; the
/// default view starts next to the first tower with near 0.25 and far 6000 (f/n > 10^4).
Scene Towers(int count = 125);

/// A machined L-bracket seen from close up (metres): legs 14 and 10 cm long, 2 cm thick and
/// 10 cm wide, a fillet of 1.2 cm radius (8 facets) on the inside bend, a through hole in each
/// leg; one closed, consistently oriented surface (normals split at 30 degrees: the fillet
/// smooth, the edges sharp). Its default view looks into the bend; a light from outside the
/// upright leg, low over the horizon, puts the bend and the lower leg's top in its shadow, with
/// concave creases (the fillet's facets, the fillet's ends) inside it. Named "bracket".
Scene Bracket();

/// A model read from .vtp .vtk .stl .ply .obj .glb .gltf, standing on a ground plane. Returns
/// false with a message when the file cannot be read or holds no surface.
bool FromFile(const std::string& path, Scene& scene, std::string& error);

/// Does a scene name given on a command line name a model file (a path with an extension
/// FromFile reads) rather than a built-in scene?
bool NamesAFile(const std::string& name);

/// Adds the scene's actors to the renderer and sets the default camera (and clipping range).
void Install(const Scene& scene, vtkRenderer* renderer, double aspect);

/// The direction a light travels at gammaDeg from the view direction eye -> focal (0: from
/// behind the viewer, 90: overhead, 180: facing it), in the plane of the view and the world's
/// +y made orthogonal to the view.
void LightAtGamma(const double eye[3], const double focal[3], double gammaDeg, double light[3]);

/// Number of triangles of a polydata (polys and strips, after triangulation).
long long CountTriangles(vtkPolyData* data);

} // namespace csmScenes
