// SPDX-License-Identifier: BSD-3-Clause
// What the caster collection's worker threads do with a big mesh (internal): its copy of the
// mesh's arrays, made on the rendering thread, and from that copy its compact blocks and its
// closed-surface classification. The functions read only the polydata they are given.
#ifndef csmCasterPreparation_h
#define csmCasterPreparation_h

#include "csmClosedSurface.h" // for csm::SurfaceClosure, csm::SurfaceTopology

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

class vtkCellArray;
class vtkDataArray;
class vtkPolyData;

/// A big caster's triangles in compact blocks (csm::orderIntoBlocks), for
/// vtkCascadedShadowBlockMapper: the corners block after block, each block's triangles and its
/// box in the data's coordinates. Empty where the mesh has no usable triangle.
struct csmPreparedBlocks
{
  vtkIdType Points = 0; ///< of the data the corners index
  std::vector<std::uint32_t> Corners;
  std::vector<std::pair<std::size_t, std::size_t>> Blocks;
  std::vector<std::array<double, 6>> Bounds;
  /// Per triangle of the data (csmPrepareBlocks' order: polygons as fans, then strips), its
  /// block (kNoBlock: left out, no area or a bad index): the blocks' boxes for new positions.
  std::vector<std::uint16_t> BlockOf;
  static constexpr std::uint16_t kNoBlock = 0xffff;
};

/// The cells a polydata's triangles come from: its polygon and strip arrays (which ones, when
/// they last changed, how many cells, a digest of their point ids: a cell replaced in place
/// changes no count and no time) and its number of points. Equal keys: the same triangles of
/// the same points, wherever the points are now.
struct csmCellsKey
{
  const void* Polys = nullptr;
  const void* Strips = nullptr;
  vtkMTimeType PolysTime = 0, StripsTime = 0;
  vtkIdType PolyCount = 0, StripCount = 0, Points = 0;
  std::uint64_t Digest = 0;
  bool operator==(const csmCellsKey& other) const;
  /// The same counts and digest, whichever arrays hold them (another polydata's cells).
  bool SameCells(const csmCellsKey& other) const;
};
csmCellsKey csmCellsOf(vtkPolyData* data);

/// The blocks' boxes (in the data's coordinates) for the data's points where they are now, from
/// the block of each triangle that csmPrepareBlocks gave (its BlockOf). False where the data's
/// triangles are not as many as blockOf holds, or a corner is not finite.
bool csmBlockBounds(vtkPolyData* data, const std::vector<std::uint16_t>& blockOf,
  std::size_t blocks, std::vector<std::array<double, 6>>& bounds);

/// A big caster's closed-surface classification.
struct csmPreparedClosure
{
  csm::SurfaceClosure Closure;
};

/// A copy of an array of the same type, or of a cell array, copied as memory on this thread
/// (vtkDataArray::DeepCopy may copy on VTK's SMP threads, which a worker's reads would then race
/// with in the eyes of a thread sanitizer).
vtkSmartPointer<vtkDataArray> csmOwnCopy(vtkDataArray* source);
vtkSmartPointer<vtkCellArray> csmOwnCopy(vtkCellArray* source);

/// Triangles of a polydata (polygons as fans, strips) without traversing them.
double csmTriangleCount(vtkPolyData* data);

/// When a polydata's points or cells last changed (or the polydata itself was modified): what
/// its blocks and its classification are prepared from. New scalars, normals or fields of a
/// time step, set on its point or cell data, prepare nothing again.
vtkMTimeType csmGeometryTime(vtkPolyData* data);

/// The polydata's triangles in blocks of at least perBlock triangles; stops early (an empty
/// result) once `stop` is set.
std::shared_ptr<csmPreparedBlocks> csmPrepareBlocks(
  vtkPolyData* data, std::size_t perBlock, const std::atomic<bool>* stop);

/// csm::classifySurface of a polydata (open where it stopped early, once `stop` is set), with
/// the topology of its last classification where given.
csm::SurfaceClosure csmClassifyPolyData(
  vtkPolyData* data, const std::atomic<bool>* stop, csm::SurfaceTopology* topology = nullptr);

#endif
