// SPDX-License-Identifier: BSD-3-Clause
// Cascaded shadow-map lookup, injected into VTK's polydata fragment shaders by
// vtkCascadedShadowMapPass. Cascade selection by view depth (Lloyd et al. 2006, §6.3);
// texel-space PCF whose taps are virtual samples on the receiver's tangent plane
// (Barroso & Celes 2007, §2.2); the per-pixel aliasing error m (Lloyd et al., Eq. 1).

// Compile-time choices, #defined by the pass (vtkCascadedShadowMapPass): CSM_KERNEL
// (CSM_KERNEL_GRID or CSM_KERNEL_JITTERED), CSM_DEBUG (0 off, or CSM_DEBUG_CASCADES, _ERROR,
// _FACTOR), CSM_SCREEN (below), CSM_LIGHTS, CSM_MAX_CASCADES, and CSM_PCF_RADIUS when few
// lights are shadowed; in a build with the comparison techniques, CSM_FACES and
// CSM_CAMERA_SPACE where a light's maps need their lookup (csmComparisonFS.glsl, which the pass
// puts before this file); CSM_PLANE_TAPS 1 in the shaders of surfaces (each texel compared at its
// own receiver-plane depth), 0 or undefined in impostors' (hardware bilinear compares);
// CSM_SINGLE_MAP 1 while every shadowed light has at most one map (csmShadow). Every
// fragment makes one map lookup: a software rasterizer runs both sides of a branch, so options
// that a uniform would switch at run time are compiled in or out instead. The kernel radius is a
// constant where it can be (the loops unroll, the tap weights fold); with many shadowed lights the
// unrolled taps would make a shader too large to compile, so there it stays a uniform.
#ifndef CSM_PLANE_TAPS
#define CSM_PLANE_TAPS 0
#endif
#ifndef CSM_SINGLE_MAP
#define CSM_SINGLE_MAP 0
#endif
// CSM_GATHER 1 where the pass reads the per-texel compares' texels with one gather of their raw
// depths (GL_ARB_texture_gather, which it enables; the atlas on a second unit with a sampler that
// does not compare): csmTexelSampler is then a sampler2D; else a sampler2DShadow whose nearest
// compares read one texel each.
#ifndef CSM_GATHER
#define CSM_GATHER 0
#endif
#if CSM_GATHER
#define csmTexelSampler sampler2D
#else
#define csmTexelSampler sampler2DShadow
#endif

// The factors at the fragment's pixel (csmScreenCache.h), CSM_SCREEN: CSM_SCREEN_OFF the lookup
// alone; CSM_SCREEN_STORE the lookup, each light's factor written at the pixel (the fragment is
// shaded only once it passed the depth test, so the last one written at a pixel is the surface
// the frame shows); CSM_SCREEN_READ the factors the last frame wrote there, no lookup (a frame
// drawn as that one). The pass enables GL_ARB_shader_image_load_store where it is not OFF.
// In a framebuffer of CSM_SCREEN_SAMPLES > 1 samples a pixel is shaded once for the samples of
// several surfaces: each fragment writes its factors and its depth at the pixel's centre (its
// identity there) into the samples it covers after the depth test (GL_ARB_post_depth_coverage),
// so each sample ends with the surface it shows, and reads them back from a sample that holds
// its own depth (the pass enables GL_ARB_post_depth_coverage and GL_ARB_gpu_shader5 there).
#ifndef CSM_SCREEN
#define CSM_SCREEN CSM_SCREEN_OFF
#endif
#ifndef CSM_SCREEN_SAMPLES
#define CSM_SCREEN_SAMPLES 1
#endif
#if CSM_SCREEN != CSM_SCREEN_OFF
#if CSM_SCREEN_SAMPLES > 1
layout(early_fragment_tests) in;
layout(post_depth_coverage) in;
#define csmScreenImage image2DMS
#elif CSM_SCREEN == CSM_SCREEN_STORE
layout(early_fragment_tests) in;
#define csmScreenImage image2D
#else
#define csmScreenImage image2D
#endif
#if CSM_SCREEN == CSM_SCREEN_STORE
layout(rgba32f) writeonly uniform csmScreenImage csmScreen;
#else
layout(rgba32f) readonly uniform csmScreenImage csmScreen;
#endif
uniform ivec2 csmScreenOrigin; // the viewport's lower left, in window pixels
ivec2 csmScreenPixel()
{
  return ivec2(gl_FragCoord.xy) - csmScreenOrigin;
}
#endif

#if CSM_SCREEN == CSM_SCREEN_STORE
// Each light's factor (x, y, z, w: lights 0-3; 0-2 with samples, w then the depth) at the pixel.
void csmScreenStore(vec4 factors)
{
#if CSM_SCREEN_SAMPLES > 1
  vec4 held = vec4(factors.xyz, gl_FragCoord.z);
  for (int s = 0; s < CSM_SCREEN_SAMPLES; ++s)
  {
    if ((gl_SampleMaskIn[0] & (1 << s)) != 0)
    {
      imageStore(csmScreen, csmScreenPixel(), s, held);
    }
  }
#else
  imageStore(csmScreen, csmScreenPixel(), factors);
#endif
}
#elif CSM_SCREEN == CSM_SCREEN_READ
// The factors the last frame stored at the pixel for this fragment's surface.
vec4 csmScreenRead()
{
#if CSM_SCREEN_SAMPLES > 1
  // The covered samples from the first: inside a surface the first holds it, and a software
  // rasterizer leaves the loop once every pixel of a block found its own.
  int covered = gl_SampleMaskIn[0];
  vec4 held = vec4(1.0);
  for (int k = 0; k < CSM_SCREEN_SAMPLES && covered != 0; ++k)
  {
    held = imageLoad(csmScreen, csmScreenPixel(), findLSB(covered));
    covered &= covered - 1;
    if (held.w == gl_FragCoord.z)
    {
      break; // (a fragment that shows in no sample is drawn over: any value serves)
    }
  }
  return held;
#else
  return imageLoad(csmScreen, csmScreenPixel());
#endif
}

// Light j's shadow as csmShadow gives it, from the factors read at the pixel (no cascade index,
// no error m: those are for the debug views, which make the lookup).
vec4 csmShadowRead(vec4 factors, int j)
{
  return vec4(factors[j], -1.0, 0.0, 1.0);
}
#endif
#ifndef CSM_PCF_RADIUS
uniform int csmPCFRadius;      // kernel of 2 r + 1 texels a side
#define CSM_PCF_RADIUS csmPCFRadius
#endif

uniform float csmConstantBias; // in the map's [0,1] depth
uniform float csmSlopeBias;    // times the receiver-plane depth change over one texel
// 1 for a surface drawn into the maps from behind (a closed surface, only its faces turned away
// from the light: vtkCascadedShadowMapBakerPass::DrawsFromBehind), 0 for every other surface.
uniform int csmFromBehind;
// Share of the constant bias for the faces of such a surface turned toward the light, which take
// no slope-scaled bias (vtkCascadedShadowMapPass::ClosedSurfaceBiasFactor).
uniform float csmClosedBiasShare;
uniform float csmBlendBand;    // share of a cascade's depth range blended into the next

float csmHash(vec2 p)
{
  return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453);
}

// One hardware bilinear compare at uv in a cascade's [0,1]^2, kept half a texel inside its tile.
float csmTap(sampler2DShadow map, vec4 tile, vec2 texel, vec2 uv, float z)
{
  vec2 inside = clamp(uv, vec2(0.5 * texel), vec2(1.0 - 0.5 * texel));
  return textureLod(map, vec3(tile.xy + inside * tile.zw, z), 0.0);
}

// The four texels of a tile from index n to n + 1 ((n.x, n.y), (n.x + 1, n.y), (n.x, n.y + 1),
// (n.x + 1, n.y + 1)), each compared with its own reference depth: 1 where the reference is not
// behind the texel's depth. A texel outside the tile reads the edge texel, as a clamped compare
// does.
vec4 csmCompareTexels(csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 n, vec4 reference)
{
#if CSM_GATHER
  // The four in one gather at the corner they share, kept a texel inside the tile; along each
  // axis the lower texel is the footprint's upper one past the last texel, the upper its lower
  // one before the first. The gather returns (lower x, upper y), (upper, upper), (upper, lower),
  // (lower, lower).
  vec2 last = floor(1.0 / texel + 0.5) - 1.0; // (an index: 1 / texel is not exact)
  vec4 d = textureGather(nearest, tile.xy + clamp(n + 1.0, vec2(1.0), last) * texel * tile.zw);
  bvec2 pastLast = greaterThan(n, last - 1.0);
  bvec2 beforeFirst = lessThan(n, vec2(0.0));
  vec2 lowerRow = vec2(pastLast.x ? d.z : d.w, beforeFirst.x ? d.w : d.z);
  vec2 upperRow = vec2(pastLast.x ? d.y : d.x, beforeFirst.x ? d.x : d.y);
  vec4 texels = vec4(pastLast.y ? upperRow : lowerRow, beforeFirst.y ? lowerRow : upperRow);
  return vec4(lessThanEqual(reference, texels));
#else
  vec4 lit;
  for (int k = 0; k < 4; ++k)
  {
    lit[k] = csmTap(nearest, tile, texel, (n + vec2(float(k & 1), float(k >> 1)) + 0.5) * texel,
      reference[k]);
  }
  return lit;
#endif
}

// The receiver plane's depth at the centres of the texels n to n + 1 (in csmCompareTexels'
// order), given its depth toN at n's centre and its change per texel along s and t: within
// maxStep of the depth at the kernel's centre, so that grazing receivers keep their taps close.
vec4 csmPlaneDepths(float z, float toN, vec2 perTexel, float maxStep)
{
  return z + clamp(toN + vec4(0.0, perTexel.x, perTexel.y, perTexel.x + perTexel.y), -maxStep,
               maxStep);
}

// A bilinear compare at uv whose four texels each compare the receiver plane's depth at their own
// centre (z at uv, dz its change per unit of uv). One hardware compare takes z for all four and
// misses the plane's change over the half texel to each centre: enough, on a face nearly along
// the light, to light it where the face shadowing it meets it (a concave crease) or to shadow it
// where its own solid's far side meets it (a convex edge).
float csmPlaneTap(csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 uv, float z, vec2 dz,
  float maxStep)
{
  vec2 t = uv / texel - 0.5;
  vec2 base = floor(t);
  vec2 f = t - base;
  vec4 lit = csmCompareTexels(nearest, tile, texel, base,
    csmPlaneDepths(z, dot(dz, (base + 0.5) * texel - uv), dz * texel, maxStep));
  return mix(mix(lit.x, lit.y, f.x), mix(lit.z, lit.w, f.x), f.y);
}

// One compare of a kernel's tap: the hardware's bilinear compare at the tap's own depth, or, for
// a face whose own depth is not in the map (exact), the compare with each texel's own depth.
float csmKernelTap(sampler2DShadow map, csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 uv,
  float z, vec2 dz, float maxStep, bool exact)
{
  return exact ? csmPlaneTap(nearest, tile, texel, uv, z, dz, maxStep)
               : csmTap(map, tile, texel, uv, z);
}

// The grid kernel below for a face whose own depth is not in the map: the (2r+2)^2 texels its
// bilinear compares touch, each compared once with the receiver plane at its own centre and
// weighed as the box of compares weighs it ([1-f, 1, ..., 1, f] along each axis), four at a time.
float csmGridPCFTexels(csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 uv, float zRef, vec2 dz)
{
  int r = CSM_PCF_RADIUS;
  float maxStep = 0.05;
  vec2 t = uv / texel - 0.5;
  vec2 base = floor(t);
  vec2 f = t - base;
  vec2 first = base - float(r); // the footprint's first texel
  vec2 perTexel = dz * texel;
  float toFirst = dot(dz, (first + 0.5) * texel - uv);
  float sum = 0.0;
  for (int i = 0; i <= r; ++i)
  {
    vec2 wx = vec2(i == 0 ? 1.0 - f.x : 1.0, i == r ? f.x : 1.0);
    for (int k = 0; k <= r; ++k)
    {
      vec2 wy = vec2(k == 0 ? 1.0 - f.y : 1.0, k == r ? f.y : 1.0);
      vec2 block = vec2(float(2 * i), float(2 * k));
      vec4 lit = csmCompareTexels(nearest, tile, texel, first + block,
        csmPlaneDepths(zRef, toFirst + dot(block, perTexel), perTexel, maxStep));
      sum += dot(lit, vec4(wx.x * wy.x, wx.y * wy.x, wx.x * wy.y, wx.y * wy.y));
    }
  }
  float n = float(2 * r + 1);
  return sum / (n * n);
}

// Texel-space PCF over (2r+1) x (2r+1) texels (r = CSM_PCF_RADIUS): the mean of (2r+1)^2 hardware
// bilinear compares one texel apart around uv, taken with (r+1)^2 taps. Along each axis those
// compares weigh the 2r+2 texels they touch [1-f, 1, ..., 1, f] (f: uv's fraction between texel
// centres); each adjacent pair of texels is one bilinear tap of weight w0 + w1 placed w1/(w0+w1)
// past the first (the "optimized PCF" of The Witness / Castano 2013, exact for the box of
// bilinear compares). Every tap keeps its own receiver-plane depth (Barroso & Celes 2007, §2.2);
// where each texel compares its own (exact), csmGridPCFTexels.
float csmGridPCF(
  sampler2DShadow map, csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 uv, float zRef,
  vec2 dz, bool exact)
{
  if (exact)
  {
    return csmGridPCFTexels(nearest, tile, texel, uv, zRef, dz);
  }
  int r = CSM_PCF_RADIUS;
  float maxStep = 0.05; // keep grazing receivers from throwing the taps far off their plane
  vec2 t = uv / texel - 0.5; // in texel-centre units
  vec2 base = floor(t);
  vec2 f = t - base;
  float sum = 0.0;
  for (int i = 0; i <= r; ++i)
  {
    float w0x = i == 0 ? 1.0 - f.x : 1.0;
    float w1x = i == r ? f.x : 1.0;
    float wx = w0x + w1x;
    float px = base.x - float(r) + 2.0 * float(i) + w1x / wx;
    for (int k = 0; k <= r; ++k)
    {
      float w0y = k == 0 ? 1.0 - f.y : 1.0;
      float w1y = k == r ? f.y : 1.0;
      float wy = w0y + w1y;
      float py = base.y - float(r) + 2.0 * float(k) + w1y / wy;
      vec2 tap = (vec2(px, py) + 0.5) * texel;
      vec2 o = tap - uv;
      float z = zRef + clamp(dot(dz, o), -maxStep, maxStep);
      sum += wx * wy * csmTap(map, tile, texel, tap, z);
    }
  }
  float n = float(2 * r + 1);
  return sum / (n * n);
}

// Jittered circular kernel of radius r + 0.5 texels: as many bilinear taps as the grid kernel,
// on a spiral rotated per pixel, so that the taps stay unaligned (Barroso & Celes 2007, §2.2).
float csmJitteredPCF(
  sampler2DShadow map, csmTexelSampler nearest, vec4 tile, vec2 texel, vec2 uv, float zRef,
  vec2 dz, bool exact)
{
  int r = CSM_PCF_RADIUS;
  int n = (r + 1) * (r + 1);
  float maxStep = 0.05;
  float turn = 6.2831853 * csmHash(gl_FragCoord.xy);
  float sum = 0.0;
  for (int i = 0; i < n; ++i)
  {
    float radius = sqrt((float(i) + 0.5) / float(n)) * (float(r) + 0.5);
    float angle = float(i) * 2.3999632 + turn;
    vec2 o = radius * vec2(cos(angle), sin(angle)) * texel;
    float z = zRef + clamp(dot(dz, o), -maxStep, maxStep);
    sum += csmKernelTap(map, nearest, tile, texel, uv + o, z, dz, maxStep, exact);
  }
  return sum / float(n);
}

// Is a point, in a cascade's homogeneous map coordinates, inside its map (its xy square and in
// front of its far plane)? Compared before the division: 0 <= x/w <= 1 is 0 <= x <= w for w > 0.
bool csmCovers(vec4 h)
{
  return h.w > 0.0 && all(greaterThanEqual(h.xy, vec2(0.0))) && all(lessThanEqual(h.xyz, h.www));
}

// The map-coordinate change of a view-space displacement d (w = 0): the matrix's first three
// columns only.
vec4 csmDisplacement(mat4 toMap, vec3 d)
{
  return toMap[0] * d.x + toMap[1] * d.y + toMap[2] * d.z;
}

// Visibility (1 lit, 0 shadowed) of a point given in a cascade's homogeneous map coordinates h,
// with the screen derivatives hx, hy of those coordinates (exact for the projective map); the
// aliasing error m there for the error view (Lloyd et al. 2006, Eq. 1).
float csmVisibility(sampler2DShadow map, csmTexelSampler nearest, vec4 tile, vec2 texel, vec4 h,
  vec4 hx, vec4 hy, float biasScale, float handedness, out float m)
{
  vec3 p = h.xyz / h.w;
  vec3 dx = (hx.xyz - p * hx.w) / h.w;
  vec3 dy = (hy.xyz - p * hy.w) / h.w;
  m = 0.0;
#if CSM_DEBUG == CSM_DEBUG_ERROR
  // A texel's footprint in pixels, 1 / smallest singular value of d(texel)/d(pixel).
  mat2 j = mat2(dx.xy / texel, dy.xy / texel);
  float e = dot(j[0], j[0]) + dot(j[1], j[1]);
  float d = abs(determinant(j));
  float smin2 = 0.5 * (e - sqrt(max(e * e - 4.0 * d * d, 0.0)));
  m = 1.0 / sqrt(max(smin2, 1e-12));
#endif
  // Receiver plane: depth change per unit of map u and v (Barroso & Celes §2.2 virtual samples).
  float det = dx.x * dy.y - dx.y * dy.x;
  vec2 dz = abs(det) > 1e-24
    ? vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det
    : vec2(0.0);
  float zSlopePerTexel = min(dot(abs(dz), texel), 0.05);
  // Which way the face turns: the light travels along +z in map space, and the screen
  // derivatives span the face as the camera sees it (its normal toward the camera, which is
  // outward on a closed surface), so cross(dx, dy).z = det is the outward normal's z times the
  // sign of the map's Jacobian, which is the sign of the map matrix's determinant (handedness).
  // A face turned toward the light on a surface drawn from behind never meets its own depth in
  // the map, only the far side of its solid (behind it, meeting it at a convex edge) or the face
  // that shadows it (in front of it, meeting it along a concave crease or where parts touch):
  // a bias would light the crease, so it takes no slope bias and csmClosedBiasShare of the
  // constant one (coplanar contact against rounding). A face turned away (lit by an
  // interpolated normal at the terminator) meets its own depth as it is and takes both biases.
  // Every face of any other surface (open: both sides in the maps) meets its own depth pushed
  // back by the polygon offset the maps are drawn with, which scales with its slope, so it takes
  // the constant bias only: a slope-scaled one would light a strip along every edge where another
  // face meets it in shadow (a sheet wall's foot, an inner corner of sheets: Results.md,
  // "Open sheets"). Each texel is compared with the plane at its own centre (exact), on every
  // surface but impostors (CSM_PLANE_TAPS: a software rasterizer pays for both sides of a
  // branch in every fragment).
  bool facesLight = det * handedness < 0.0 && csmFromBehind != 0;
  float zRef = p.z - (facesLight ? csmClosedBiasShare * biasScale * csmConstantBias
                                 : biasScale * csmConstantBias +
                      (csmFromBehind != 0 ? csmSlopeBias * zSlopePerTexel : 0.0));
  bool exact = CSM_PLANE_TAPS != 0;
#if CSM_KERNEL == CSM_KERNEL_GRID
  return csmGridPCF(map, nearest, tile, texel, p.xy, zRef, dz, exact);
#else
  return CSM_PCF_RADIUS == 0 ? csmGridPCF(map, nearest, tile, texel, p.xy, zRef, dz, exact)
                           : csmJitteredPCF(map, nearest, tile, texel, p.xy, zRef, dz, exact);
#endif
}

// A threshold in [0, 1) per pixel that tiles the screen without visible pattern (interleaved
// gradient noise, Jimenez 2014): which pixels of a blend band take the next cascade.
float csmDither()
{
  return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}

// Per shadowed light j (CSM_LIGHTS of them), its cascades at [j * CSM_MAX_CASCADES, ...): view
// space -> map matrices and the signs of their determinants, atlas tiles, texel sizes along s
// and t (in the cascade's [0,1]), far split depths.
uniform mat4 csmToMap[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform float csmHandedness[CSM_LIGHTS * CSM_MAX_CASCADES];
// Of the constant bias; negative on a spot light's perspective map: minus its f n, the bias
// there scaled by f n / w^2, the map depth's change per unit of w (csm::perspectiveBiasFactor).
uniform float csmBiasShare[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform vec4 csmTile[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform vec2 csmTexel[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform float csmSplitFar[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform float csmSplitNear[CSM_LIGHTS];
uniform int csmCount[CSM_LIGHTS];
uniform float csmAttenuation[CSM_LIGHTS];

// Light j's cascade for a point at view depth `depth`: the one whose view-depth interval holds
// it (c; Lloyd et al. 2006, §6.3), the next one, and whether this pixel of c's blend band goes
// to the next: in the last BlendBand of a cascade's depth range a share of the pixels growing
// from 0 to 1 across the band takes the next cascade, so that the seam becomes a dithered
// transition at the cost of one lookup, where a blend would take two. False outside every
// cascade.
bool csmCascadeAt(int j, vec4 vc, out int c, out int next, out bool blend)
{
  int count = csmCount[j];
#ifdef CSM_FACES
  // Face partitions (csmComparisonFS.glsl): the piece the point lies in; no blend band (the
  // pieces meet along planes through the light, where their maps agree).
  c = csmPartitionAt(j, count, vc);
  next = c;
  blend = false;
  return count > 0;
#endif
  float depth = -vc.z;
  int first = j * CSM_MAX_CASCADES;
  c = 0;
  float cascadeNear = csmSplitNear[j];
  for (int i = 0; i + 1 < count; ++i)
  {
    if (depth > csmSplitFar[first + i])
    {
      c = i + 1;
      cascadeNear = csmSplitFar[first + i];
    }
  }
  float cascadeFar = csmSplitFar[first + c];
  float band = csmBlendBand * (cascadeFar - cascadeNear);
  blend = c + 1 < count && band > 0.0 && (depth - (cascadeFar - band)) / band > csmDither();
  next = min(c + 1, max(count - 1, 0));
  return count > 0 && depth >= csmSplitNear[j] && depth <= csmSplitFar[first + max(count, 1) - 1];
}

// Of the cascade c and the next one (their map coordinates hThis, hNext): the next one where it
// covers the point and c's map does not (a map kept from an earlier frame may miss points on
// its edge; the baker re-renders one that misses its slice), or where the dither gives this
// pixel of the band to it; else c where it covers the point; else -1. Two candidates, not a
// search, because a software rasterizer pays for every candidate in every fragment.
int csmChoose(int c, int next, bool blend, vec4 hThis, vec4 hNext)
{
  bool thisCovers = csmCovers(hThis);
  bool nextCovers = next > c && csmCovers(hNext);
  bool takeNext = nextCovers && (blend || !thisCovers);
  return takeNext ? next : (thisCovers ? c : -1);
}

// Shadow of light j from the chosen cascade (-1: none), given the point's map coordinates there
// and their screen derivatives: x = light factor (1 lit .. 1 - attenuation), y = cascade index
// (-1: none), z = aliasing error m (error view only), w = visibility.
vec4 csmShadowIn(
  sampler2DShadow map, csmTexelSampler nearest, int j, int chosen, vec4 h, vec4 hx, vec4 hy)
{
  if (chosen < 0)
  {
    return vec4(1.0, -1.0, 0.0, 1.0); // outside every cascade: lit as without shadows
  }
  int cascade = j * CSM_MAX_CASCADES + chosen;
  float m;
  float share = csmBiasShare[cascade];
  float biasScale = share >= 0.0 ? share : -share / max(h.w * h.w, 1e-30);
#ifdef CSM_CAMERA_SPACE
  biasScale = csmDepthBiasScale(cascade, h); // camera space maps (csmComparisonFS.glsl)
#endif
  float visibility = csmVisibility(
    map, nearest, csmTile[cascade], csmTexel[cascade], h, hx, hy, biasScale,
    csmHandedness[cascade], m);
  return vec4(1.0 - csmAttenuation[j] * (1.0 - visibility), float(chosen), m, visibility);
}

// Shadow of light j at view position vc with screen derivatives dvcdx, dvcdy (w = 0): the map
// coordinates of the two candidate cascades by matrix products in the fragment. With
// CSM_SINGLE_MAP (#defined 1 by the pass while every shadowed light has at most one map) the
// one map's, and no choice: the same answer for less work a fragment.
vec4 csmShadow(sampler2DShadow map, csmTexelSampler nearest, int j, vec4 vc, vec4 dvcdx, vec4 dvcdy)
{
#if CSM_SINGLE_MAP
  int only = j * CSM_MAX_CASCADES;
  float depth = -vc.z;
  mat4 toMap = csmToMap[only];
  vec4 h = toMap * vc;
  bool inside = csmCount[j] > 0 && depth >= csmSplitNear[j] && depth <= csmSplitFar[only];
  return csmShadowIn(map, nearest, j, inside && csmCovers(h) ? 0 : -1, h,
    csmDisplacement(toMap, dvcdx.xyz), csmDisplacement(toMap, dvcdy.xyz));
#else
  int c, next;
  bool blend;
  bool inside = csmCascadeAt(j, vc, c, next, blend);
  int first = j * CSM_MAX_CASCADES;
  mat4 toThis = csmToMap[first + c];
  mat4 toNext = csmToMap[first + next];
  vec4 hThis = toThis * vc;
  vec4 hNext = toNext * vc;
  int chosen = inside ? csmChoose(c, next, blend, hThis, hNext) : -1;
  bool takeNext = chosen == next && next > c;
  mat4 toChosen = takeNext ? toNext : toThis;
  return csmShadowIn(map, nearest, j, chosen, takeNext ? hNext : hThis,
    csmDisplacement(toChosen, dvcdx.xyz), csmDisplacement(toChosen, dvcdy.xyz));
#endif
}


// Light-space pages (csmPages.h; vtkCascadedShadowMapBakerPass::LightSpacePages): light j's one
// map is the base, refined by levels of half its texel a level, of which the pages the view reads
// are drawn into the rest of the atlas. CSM_PAGE_TEXELS (a page's side with its border),
// CSM_PAGE_BORDER, CSM_PAGE_INTERIOR, CSM_PAGE_TABLE_SIDE and CSM_PAGE_BAND come from csmPages.h
// through the pass.
uniform int csmPageLevels[CSM_LIGHTS];   // levels finer than the base
uniform float csmPageDepth[CSM_LIGHTS];  // view depth from which the base meets the target
uniform vec2 csmPageVirtual[CSM_LIGHTS]; // the base's texels along s and t
uniform vec2 csmPageTile[CSM_LIGHTS];    // a page's side in the atlas's [0, 1]

// Shadow of a paged light j, as csmShadow: the level the point's view depth needs (log2 of the
// base's depth over it, rounded up; in the band before the next finer level a share of the
// pixels growing to 1 takes that one), its page by the table (an entry holds the page's slot in
// the pool, in pages, and the page it holds), and the lookup in that page's texels, its border
// holding the kernel; the base where the page is not in the pool. One matrix: every level shares
// the base's map coordinates (orthographic: w = 1). y: the level read (0 the base; -2 where the
// level's page is not in the pool and the base served: grey in the cascades' debug view).
vec4 csmPagedShadow(sampler2DShadow map, csmTexelSampler nearest, sampler2D pages, int j, vec4 vc,
  vec4 dvcdx, vec4 dvcdy)
{
  int base = j * CSM_MAX_CASCADES;
  mat4 toMap = csmToMap[base];
  vec4 h = toMap * vc;
  vec4 hx = csmDisplacement(toMap, dvcdx.xyz);
  vec4 hy = csmDisplacement(toMap, dvcdy.xyz);
  float depth = -vc.z;
  float fineness = log2(csmPageDepth[j] / max(depth, 1e-30));
  int levels = csmPageLevels[j];
  int k = clamp(int(ceil(fineness)), 0, levels);
  float into = fineness - (float(k) - CSM_PAGE_BAND);
  k += (k < levels && into > 0.0 && into / CSM_PAGE_BAND > csmDither()) ? 1 : 0;
  vec2 texels = csmPageVirtual[j] * exp2(float(k));
  vec2 u = h.xy * texels;
  vec2 page = floor(u / float(CSM_PAGE_INTERIOR));
  ivec2 entry = ivec2(page) & (CSM_PAGE_TABLE_SIDE - 1);
  vec4 held = texelFetch(pages, ivec2(entry.x, entry.y + CSM_PAGE_TABLE_SIDE * max(k - 1, 0)), 0);
  bool paged = k > 0 && held.x >= 0.0 && held.z == page.x && held.w == page.y;
  vec2 scale = paged ? texels / float(CSM_PAGE_TEXELS) : vec2(1.0);
  vec2 offset =
    paged ? (float(CSM_PAGE_BORDER) - page * float(CSM_PAGE_INTERIOR)) / float(CSM_PAGE_TEXELS)
          : vec2(0.0);
  vec4 hPage = vec4(h.xy * scale + offset, h.zw);
  vec4 tile = paged ? vec4(held.xy * csmPageTile[j], csmPageTile[j]) : csmTile[base];
  vec2 texel = paged ? vec2(1.0 / float(CSM_PAGE_TEXELS)) : csmTexel[base];
  bool inside = csmCount[j] > 0 && depth >= csmSplitNear[j] && depth <= csmSplitFar[base] &&
    csmCovers(h);
  if (!inside)
  {
    return vec4(1.0, -1.0, 0.0, 1.0); // outside the base: lit as without shadows
  }
  // The constant bias, in the base's depth (the whole scene along the light), follows the
  // texel: the base's share of it, halved a level (a level's texels meet the target at a view
  // 2^k times nearer).
  float m;
  float visibility = csmVisibility(map, nearest, tile, texel, hPage, vec4(hx.xy * scale, hx.zw),
    vec4(hy.xy * scale, hy.zw), csmBiasShare[base] * exp2(-float(paged ? k : 0)),
    csmHandedness[base], m);
  float read = paged ? float(k) : (k > 0 ? -2.0 : 0.0);
  return vec4(1.0 - csmAttenuation[j] * (1.0 - visibility), read, m, visibility);
}

#ifdef CSM_IMPOSTOR
// Receivers drawn as impostors (VTK's tubes and spheres): the fragment's vertexVC is the point on
// the tube's axis (or the sphere's centre), its normal the impostor's. The surface the viewer
// sees is r along that normal (r: the radius VTK draws, from its ZCalcR: the radius itself for a
// parallel camera, per unit of depth for a perspective one), and its tangent plane is the
// receiver plane (screen derivatives of the axis point say nothing across the tube). The maps
// hold the casters' centre depth, which the lit side of this surface lies in front of.
uniform vec2 csmImpostorPixels; // the diameters VTK draws, in pixels: line width, point size
vec4 csmImpostorShadow(sampler2DShadow map, csmTexelSampler nearest, int j, vec4 vc, vec3 normalVC)
{
  float r = ZCalcR * (cameraParallel == 1 ? 1.0 : -vc.z);
  vec3 n = normalize(normalVC);
  vec3 t1 = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 t2 = cross(n, t1);
#ifdef CSM_IMPOSTOR_SPHERE
  float pixel = 2.0 * r / max(csmImpostorPixels.y, 1.0); // one pixel, in view units
#else
  float pixel = 2.0 * r / max(csmImpostorPixels.x, 1.0);
#endif
  return csmShadow(map, nearest, j, vec4(vc.xyz + r * n, vc.w), vec4(t1 * pixel, 0.0),
    vec4(t2 * pixel, 0.0));
}
#endif

vec3 csmCascadeColor(float c)
{
  if (c < -0.5) return vec3(0.5);
  int i = int(c + 0.5);
  if (i == 0) return vec3(1.0, 0.25, 0.25);
  if (i == 1) return vec3(0.25, 1.0, 0.25);
  if (i == 2) return vec3(0.3, 0.45, 1.0);
  if (i == 3) return vec3(1.0, 1.0, 0.25);
  if (i == 4) return vec3(1.0, 0.25, 1.0);
  if (i == 5) return vec3(0.25, 1.0, 1.0);
  if (i == 6) return vec3(1.0, 0.6, 0.2);
  return vec3(0.7, 0.5, 1.0);
}

// Heat map of log2(m): blue oversampled (m <= 1/4), green m = 1, red undersampled (m >= 4).
vec3 csmErrorColor(float m)
{
  float t = clamp(log2(max(m, 1e-6)) / 4.0 + 0.5, 0.0, 1.0);
  return t < 0.5 ? mix(vec3(0.1, 0.2, 1.0), vec3(0.1, 0.9, 0.2), 2.0 * t)
                 : mix(vec3(0.1, 0.9, 0.2), vec3(1.0, 0.1, 0.1), 2.0 * t - 1.0);
}

// Debug output for a shadow result r (first shadowed light) over the shaded colour.
vec4 csmDebugColor(vec4 shaded, vec4 r)
{
  if (CSM_DEBUG == CSM_DEBUG_CASCADES) return vec4(csmCascadeColor(r.y) * (0.35 + 0.65 * r.x), shaded.a);
  if (CSM_DEBUG == CSM_DEBUG_ERROR) return vec4(r.y < -0.5 ? vec3(0.0) : csmErrorColor(r.z) * (0.4 + 0.6 * r.x), shaded.a);
  if (CSM_DEBUG == CSM_DEBUG_FACTOR) return vec4(vec3(r.w), shaded.a);
  return shaded;
}
