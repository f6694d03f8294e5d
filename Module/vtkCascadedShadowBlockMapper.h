// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowBlockMapper
 * @brief   Draws chosen blocks of a big caster's triangles into the shadow maps (internal).
 *
 * Its input shares the prop's own points (and so, through the window's buffer cache, the
 * vertex buffer the prop's mapper uploads); its triangles are an index list grouped into
 * compact spatial blocks (csm::orderIntoBlocks), uploaded once and not kept on the CPU. Each
 * cascade draws only the blocks whose boxes reach its light volume (SetDrawnBlocks).
 */
#ifndef vtkCascadedShadowBlockMapper_h
#define vtkCascadedShadowBlockMapper_h

#include "vtkOpenGLPolyDataMapper.h"

#include <cstdint> // for std::uint32_t
#include <utility> // for std::pair
#include <vector>  // for members

class vtkCascadedShadowBlockMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkCascadedShadowBlockMapper* New();
  vtkTypeMacro(vtkCascadedShadowBlockMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The triangles (three point ids each), block after block, and each block's first triangle
  /// and count. The ids are uploaded at the next draw and then released.
  void SetBlocks(
    std::vector<std::uint32_t>&& corners, std::vector<std::pair<std::size_t, std::size_t>> blocks);
  std::size_t GetNumberOfBlocks() const { return this->Blocks.size(); }
  std::size_t GetNumberOfBlockTriangles(std::size_t block) const
  {
    return block < this->Blocks.size() ? this->Blocks[block].second : 0;
  }
  /// False once the GL lost the uploaded triangles (ReleaseGraphicsResources): new blocks needed.
  bool HasTriangles() const;
  /// The blocks the next draws draw (indices into the blocks).
  void SetDrawnBlocks(const std::vector<std::size_t>& blocks);

protected:
  vtkCascadedShadowBlockMapper() = default;
  ~vtkCascadedShadowBlockMapper() override = default;

  void BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;

  std::vector<std::uint32_t> Corners; // until uploaded
  std::vector<std::pair<std::size_t, std::size_t>> Blocks;
  std::vector<std::pair<std::size_t, std::size_t>> Drawn; // merged runs of triangles

private:
  vtkCascadedShadowBlockMapper(const vtkCascadedShadowBlockMapper&) = delete;
  void operator=(const vtkCascadedShadowBlockMapper&) = delete;
};

#endif
