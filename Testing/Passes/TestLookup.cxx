// SPDX-License-Identifier: BSD-3-Clause
// The lookup's filter on a synthetic shadow map, in a real GL context: the (r+1)^2-tap grid
// kernel (csmGridPCF in Module/glsl/csmShadowFS.glsl) equals the (2r+1)^2 hardware bilinear
// compares one texel apart that it stands for, within 1/255; with a tilted receiver plane and
// each texel compared at its own depth (a face whose own depth is not in the map), it equals
// the same compares made texel by texel at the plane's depth at each texel's centre.
#include "csmShadowFS.h" // the GLSL under test

#include "vtkCascadedShadowMapPass.h"
#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace
{
// Synthetic map, texels along s and t (not square: the maps of five to seven cascades are not).
constexpr int kMapWidth = 64;
constexpr int kMapHeight = 40;
constexpr int kSamples = 96; // sample positions per side (the quad's pixels)

// constantRadius >= 0: the kernel radius compiled in, as the pass does for few lights;
// otherwise the uniform csmPCFRadius.
std::string fragmentShader(int constantRadius)
{
  // The definitions the pass prepends, from the pass itself.
  return std::string("//VTK::System::Dec\n"
                     "in vec2 texCoord;\n"
                     "//VTK::Output::Dec\n") +
    vtkCascadedShadowMapPass::GetShaderDefinitions(1, vtkCascadedShadowMapPass::KERNEL_GRID,
      vtkCascadedShadowMapPass::DEBUG_OFF, constantRadius) +
    csmShadowFS +
    "\nuniform sampler2DShadow map;\n"
    "void main()\n"
    "{\n"
    "  // Sample positions inside the map, away from its border (the taps clamp there).\n"
    "  vec2 uv = mix(vec2(0.15), vec2(0.85), texCoord);\n"
    "  vec4 tile = vec4(0.0, 0.0, 1.0, 1.0);\n"
    "  float zRef = 0.5;\n"
    "  int r = CSM_PCF_RADIUS;\n"
    "  vec2 texel = vec2(1.0 / " +
    std::to_string(kMapWidth) + ".0, 1.0 / " + std::to_string(kMapHeight) +
    ".0);\n"
    "  float fast = csmGridPCF(map, map, tile, texel, uv, zRef, vec2(0.0), false);\n"
    "  // A receiver plane across the kernel: each texel compared with the plane at its centre.\n"
    "  vec2 dz = vec2(0.25, -0.15);\n"
    "  float exact = csmGridPCF(map, map, tile, texel, uv, zRef, dz, true);\n"
    "  float shared = csmGridPCF(map, map, tile, texel, uv, zRef, dz, false);\n"
    "  float perTexel = 0.0;\n"
    "  for (int i = -r; i <= r; ++i)\n"
    "    for (int k = -r; k <= r; ++k)\n"
    "    {\n"
    "      vec2 t = (uv + vec2(i, k) * texel) / texel - 0.5;\n"
    "      vec2 f = t - floor(t);\n"
    "      for (int c = 0; c < 4; ++c)\n"
    "      {\n"
    "        vec2 corner = vec2(float(c & 1), float(c >> 1));\n"
    "        vec2 centre = (floor(t) + corner + 0.5) * texel;\n"
    "        vec2 w = mix(vec2(1.0) - f, f, corner);\n"
    "        perTexel += w.x * w.y * csmTap(map, tile, texel, centre, zRef + dot(dz, centre - "
    "uv));\n"
    "      }\n"
    "    }\n"
    "  perTexel /= float((2 * r + 1) * (2 * r + 1));\n"
    "  float reference = 0.0;\n"
    "  for (int i = -r; i <= r; ++i)\n"
    "    for (int k = -r; k <= r; ++k)\n"
    "      reference += csmTap(map, tile, texel, uv + vec2(i, k) * texel, zRef);\n"
    "  reference /= float((2 * r + 1) * (2 * r + 1));\n"
    "  gl_FragData[0] = vec4(fast, reference, exact - perTexel, shared - perTexel);\n"
    "}\n";
}
}

// A GL context, a random depth map of kMapWidth x kMapHeight around the reference depth 0.5
// (within the receiver plane's change over the kernel: each texel in front of or behind it, and
// for a tilted receiver so per texel) and a float target of the quad's size for the results.
class Lookup : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(kSamples, kSamples);
    this->Window->Render();
    this->GL = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    ASSERT_NE(this->GL, nullptr);
    this->GL->MakeCurrent();
    std::mt19937 random(7);
    std::vector<float> depth(kMapWidth * kMapHeight);
    for (float& d : depth)
      d = 0.47f + 0.06f * static_cast<float>(random() % 1000) / 999.0f;
    vtkTextureObject* map = this->Map;
    map->SetContext(this->GL);
    map->SetWrapS(vtkTextureObject::ClampToEdge);
    map->SetWrapT(vtkTextureObject::ClampToEdge);
    map->SetMinificationFilter(vtkTextureObject::Linear);
    map->SetMagnificationFilter(vtkTextureObject::Linear);
    map->SetDepthTextureCompare(true);
    map->SetDepthTextureCompareFunction(vtkTextureObject::Lequal);
    ASSERT_TRUE(map->CreateDepthFromRaw(
      kMapWidth, kMapHeight, vtkTextureObject::Float32, VTK_FLOAT, depth.data()));
    this->Results->SetContext(this->GL);
    ASSERT_TRUE(this->Results->Allocate2D(kSamples, kSamples, 4, VTK_FLOAT));
    this->Target->SetContext(this->GL);
    this->GL->GetState()->PushFramebufferBindings();
    this->Pushed = true;
    this->Target->Bind();
    this->Target->AddColorAttachment(0, this->Results);
    this->Target->ActivateDrawBuffer(0);
    this->Target->ActivateReadBuffer(0);
    ASSERT_TRUE(this->Target->CheckFrameBufferStatus(GL_FRAMEBUFFER));
  }
  void TearDown() override
  {
    if (this->Pushed)
    {
      this->GL->GetState()->PopFramebufferBindings();
    }
  }
  /// The quad drawn over the target, and its pixels read back (RGBA floats).
  std::vector<float> Draw(vtkOpenGLQuadHelper& quad)
  {
    this->GL->GetState()->vtkglViewport(0, 0, kSamples, kSamples);
    this->GL->GetState()->vtkglDisable(GL_DEPTH_TEST);
    this->GL->GetState()->vtkglDisable(GL_BLEND);
    quad.Render();
    std::vector<float> pixels(4 * kSamples * kSamples);
    glReadPixels(0, 0, kSamples, kSamples, GL_RGBA, GL_FLOAT, pixels.data());
    return pixels;
  }
  vtkNew<vtkRenderWindow> Window;
  vtkOpenGLRenderWindow* GL = nullptr;
  vtkNew<vtkTextureObject> Map;
  vtkNew<vtkTextureObject> Results;
  vtkNew<vtkOpenGLFramebufferObject> Target;
  bool Pushed = false;
};

TEST_F(Lookup, GridKernelEqualsTheBoxOfBilinearCompares)
{
  vtkOpenGLRenderWindow* gl = this->GL;
  vtkTextureObject* map = this->Map;
  // Each radius with the kernel size as a uniform (many lights) and compiled in (few lights).
  for (int variant = 0; variant < 6; ++variant)
  {
    const int r = 1 + variant / 2;
    const bool constant = variant % 2 == 1;
    vtkOpenGLQuadHelper quad(gl, nullptr, fragmentShader(constant ? r : -1).c_str(), "");
    ASSERT_NE(quad.Program, nullptr) << "r = " << r;
    ASSERT_EQ(quad.Program->IsUniformUsed("csmPCFRadius"), !constant) << "r = " << r;
    gl->GetShaderCache()->ReadyShaderProgram(quad.Program);
    map->Activate();
    quad.Program->SetUniformi("map", map->GetTextureUnit());
    if (!constant)
    {
      quad.Program->SetUniformi("csmPCFRadius", r);
    }
    const std::vector<float> pixels = this->Draw(quad);
    map->Deactivate();
    long differing = 0, penumbra = 0, differingExact = 0, differingShared = 0;
    double worst = 0.0;
    for (int i = 0; i < kSamples * kSamples; ++i)
    {
      const double difference = std::abs(pixels[4 * i] - pixels[4 * i + 1]);
      worst = std::max(worst, difference);
      differing += difference > 1.0 / 255.0;
      differingExact += std::abs(pixels[4 * i + 2]) > 1.0 / 255.0;
      differingShared += std::abs(pixels[4 * i + 3]) > 1.0 / 255.0;
      penumbra +=
        pixels[4 * i + 1] > 0.05f && pixels[4 * i + 1] < 0.95f; // neither lit nor shadowed
    }
    std::printf("r = %d (%s): largest difference %.2e, %ld of %d samples in a penumbra, %ld "
                "with a tilted receiver differ at the taps' own depths\n",
      r, constant ? "compiled in" : "uniform", worst, penumbra, kSamples * kSamples,
      differingShared);
    EXPECT_EQ(differing, 0) << "r = " << r;
    EXPECT_EQ(differingExact, 0) << "r = " << r;
    // The hardware's compares at each tap's own depth miss the plane's change within a texel.
    EXPECT_GT(differingShared, kSamples * kSamples / 10) << "r = " << r;
    // The map is random: most samples see both depths (the comparison is not of constants).
    EXPECT_GT(penumbra, kSamples * kSamples / 2) << "r = " << r;
  }
}

// The per-texel compares read the four texels of their footprint with one gather where the
// context can (CSM_GATHER): the same answer as four clamped compares, inside a tile of the map and
// where the footprint reaches past the tile's edges (each texel outside reads the edge's); the
// grid kernel's sixteen texels, four to a gather, the same as its nine bilinear taps.
TEST_F(Lookup, PlaneTapsReadTheirFourTexelsWithOneGather)
{
  vtkOpenGLRenderWindow* gl = this->GL;
  vtkTextureObject* map = this->Map;
  if (!vtkCascadedShadowMapPass::GatherTexels())
  {
    GTEST_SKIP() << "no GL_ARB_texture_gather here: the compares read a texel each";
  }
  // A tile of 32 x 30 texels at texel (16, 5) of the map; samples from a tenth of it before its
  // first texel to a tenth past its last, the receiver plane tilted.
  const std::string shader = std::string("//VTK::System::Dec\n") +
    vtkCascadedShadowMapPass::GatherDeclarations(true) +
    "in vec2 texCoord;\n"
    "//VTK::Output::Dec\n" +
    vtkCascadedShadowMapPass::GetShaderDefinitions(
      1, vtkCascadedShadowMapPass::KERNEL_GRID, vtkCascadedShadowMapPass::DEBUG_OFF, 1) +
    csmShadowFS +
    "\nuniform sampler2DShadow map;\n"
    "uniform csmTexelSampler texels;\n"
    "void main()\n"
    "{\n"
    "  vec2 size = vec2(" +
    std::to_string(kMapWidth) + ".0, " + std::to_string(kMapHeight) +
    ".0);\n"
    "  vec4 tile = vec4(vec2(16.0, 5.0) / size, vec2(32.0, 30.0) / size);\n"
    "  vec2 texel = vec2(1.0 / 32.0, 1.0 / 30.0);\n"
    "  vec2 uv = mix(vec2(-0.1), vec2(1.1), texCoord);\n"
    "  vec2 dz = vec2(0.25, -0.15);\n"
    "  float z = 0.5;\n"
    "  float gathered = csmPlaneTap(texels, tile, texel, uv, z, dz, 0.05);\n"
    "  vec2 t = uv / texel - 0.5;\n"
    "  vec2 f = t - floor(t);\n"
    "  float compared = 0.0;\n"
    "  for (int c = 0; c < 4; ++c)\n"
    "  {\n"
    "    vec2 corner = vec2(float(c & 1), float(c >> 1));\n"
    "    vec2 centre = (floor(t) + corner + 0.5) * texel;\n"
    "    vec2 w = mix(vec2(1.0) - f, f, corner);\n"
    "    compared += w.x * w.y * csmTap(map, tile, texel, centre,\n"
    "      z + clamp(dot(dz, centre - uv), -0.05, 0.05));\n"
    "  }\n"
    "  // The 3x3 kernel's sixteen texels, four to a gather, against its nine taps' compares.\n"
    "  float kernel = csmGridPCF(map, texels, tile, texel, uv, z, dz, true);\n"
    "  float kernelCompared = 0.0;\n"
    "  for (int i = -1; i <= 1; ++i)\n"
    "    for (int k = -1; k <= 1; ++k)\n"
    "    {\n"
    "      vec2 tap = uv + vec2(i, k) * texel;\n"
    "      vec2 s = tap / texel - 0.5;\n"
    "      vec2 g = s - floor(s);\n"
    "      for (int c = 0; c < 4; ++c)\n"
    "      {\n"
    "        vec2 corner = vec2(float(c & 1), float(c >> 1));\n"
    "        vec2 centre = (floor(s) + corner + 0.5) * texel;\n"
    "        vec2 w = mix(vec2(1.0) - g, g, corner);\n"
    "        kernelCompared += w.x * w.y * csmTap(map, tile, texel, centre, z + dot(dz, centre - "
    "uv));\n"
    "      }\n"
    "    }\n"
    "  gl_FragData[0] = vec4(gathered, compared, kernel, kernelCompared / 9.0);\n"
    "}\n";
  vtkOpenGLQuadHelper quad(gl, nullptr, shader.c_str(), "");
  ASSERT_NE(quad.Program, nullptr);
  gl->GetShaderCache()->ReadyShaderProgram(quad.Program);
  map->Activate();
  quad.Program->SetUniformi("map", map->GetTextureUnit());
  // The same texture on a unit of its own, through a sampler that does not compare (the pass's).
  vtkTextureUnitManager* units = gl->GetTextureUnitManager();
  const int unit = units->Allocate();
  ASSERT_GE(unit, 0);
  GLuint sampler = 0;
  glGenSamplers(1, &sampler);
  glSamplerParameteri(sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, map->GetHandle());
  glBindSampler(static_cast<GLuint>(unit), sampler);
  quad.Program->SetUniformi("texels", unit);
  const std::vector<float> pixels = this->Draw(quad);
  glBindSampler(static_cast<GLuint>(unit), 0);
  glDeleteSamplers(1, &sampler);
  glBindTexture(GL_TEXTURE_2D, 0);
  units->Free(unit);
  map->Deactivate();
  long differing = 0, penumbra = 0, differingKernel = 0, kernelPenumbra = 0;
  for (int i = 0; i < kSamples * kSamples; ++i)
  {
    differing += std::abs(pixels[4 * i] - pixels[4 * i + 1]) > 1.0 / 255.0;
    penumbra += pixels[4 * i + 1] > 0.05f && pixels[4 * i + 1] < 0.95f;
    differingKernel += std::abs(pixels[4 * i + 2] - pixels[4 * i + 3]) > 1.0 / 255.0;
    kernelPenumbra += pixels[4 * i + 3] > 0.05f && pixels[4 * i + 3] < 0.95f;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(penumbra, kSamples * kSamples / 4); // (the compares are not of constants)
  EXPECT_EQ(differingKernel, 0);
  EXPECT_GT(kernelPenumbra, kSamples * kSamples / 2);
}
