// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowBlockMapper.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkRenderer.h"
#include "vtk_glew.h"

vtkStandardNewMacro(vtkCascadedShadowBlockMapper);

void vtkCascadedShadowBlockMapper::SetBlocks(
  std::vector<std::uint32_t>&& corners, std::vector<std::pair<std::size_t, std::size_t>> blocks)
{
  this->Corners = std::move(corners);
  this->Blocks = std::move(blocks);
  this->Drawn.clear();
  this->Modified(); // the index buffer is built again
}

void vtkCascadedShadowBlockMapper::SetDrawnBlocks(const std::vector<std::size_t>& blocks)
{
  // Neighbouring blocks are one draw.
  this->Drawn.clear();
  for (const std::size_t b : blocks)
  {
    if (b >= this->Blocks.size())
    {
      continue;
    }
    const auto& block = this->Blocks[b];
    if (!this->Drawn.empty() && this->Drawn.back().first + this->Drawn.back().second == block.first)
    {
      this->Drawn.back().second += block.second;
    }
    else
    {
      this->Drawn.push_back(block);
    }
  }
}

void vtkCascadedShadowBlockMapper::BuildIBO(vtkRenderer*, vtkActor*, vtkPolyData*)
{
  // Buffers are built again for a new property or new point positions too: the triangles
  // uploaded before still hold (the baker gives new ones when the cells change).
  if (this->Corners.empty())
  {
    return;
  }
  for (auto& primitive : this->Primitives)
  {
    primitive.IBO->IndexCount = 0;
  }
  vtkOpenGLIndexBufferObject* triangles = this->Primitives[PrimitiveTris].IBO;
  if (triangles->Upload(this->Corners, vtkOpenGLBufferObject::ElementArrayBuffer))
  {
    triangles->IndexCount = this->Corners.size();
  }
  // The GL holds them now.
  std::vector<std::uint32_t>().swap(this->Corners);
}

bool vtkCascadedShadowBlockMapper::HasTriangles() const
{
  return !this->Corners.empty() || this->Primitives[PrimitiveTris].IBO->IndexCount > 0;
}

void vtkCascadedShadowBlockMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* actor)
{
  vtkOpenGLHelper& triangles = this->Primitives[PrimitiveTris];
  const int vertices = this->VBOs->GetNumberOfTuples("vertexMC");
  if (triangles.IBO->IndexCount == 0 || this->Drawn.empty() || vertices < 1)
  {
    return;
  }
  this->DrawingVertices = false;
  this->UpdateShaders(triangles, ren, actor);
  triangles.IBO->Bind();
  for (const auto& run : this->Drawn)
  {
    glDrawRangeElements(GL_TRIANGLES, 0, static_cast<GLuint>(vertices - 1),
      static_cast<GLsizei>(3 * run.second), GL_UNSIGNED_INT,
      reinterpret_cast<const GLvoid*>(3 * run.first * sizeof(GLuint)));
  }
  triangles.IBO->Release();
}

void vtkCascadedShadowBlockMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Blocks: " << this->Blocks.size() << "\n";
}
