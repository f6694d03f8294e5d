// SPDX-License-Identifier: BSD-3-Clause
// Cascaded shadow-map lookup, injected into VTK's polydata fragment shaders by
// vtkCascadedShadowMapPass. Cascade selection by view depth (Lloyd et al. 2006, §6.3);
// texel-space PCF whose taps are virtual samples on the receiver's tangent plane
// (Barroso & Celes 2007, §2.2); the per-pixel aliasing error m (Lloyd et al., Eq. 1).

uniform float csmTileTexel;    // one texel of a cascade, in the cascade's [0,1] coordinates
uniform int csmPCFSize;        // kernel width in texels: 1, 3, 5 or 7
uniform int csmKernel;         // CSM_KERNEL_GRID: regular grid; otherwise jittered circular
uniform float csmConstantBias; // in the map's [0,1] depth
uniform float csmSlopeBias;    // times the receiver-plane depth change over one texel
uniform float csmBlendBand;    // share of a cascade's depth range blended into the next
uniform int csmDebug;          // 0 off, or CSM_DEBUG_CASCADES, _ERROR, _FACTOR

// Map coordinates ([0,1]^3 inside the cascade) of a view-space point.
vec3 csmProject(mat4 vcToMap, vec4 vc)
{
  vec4 h = vcToMap * vc;
  return h.xyz / h.w;
}

// Screen derivatives of the map coordinates, from those of the view-space position (exact for
// the projective map, and the same on both sides of a cascade boundary).
void csmDerivatives(mat4 vcToMap, vec4 vc, vec4 dvcdx, vec4 dvcdy, out vec3 dx, out vec3 dy)
{
  vec4 h = vcToMap * vc;
  vec3 p = h.xyz / h.w;
  vec4 hx = vcToMap * dvcdx;
  vec4 hy = vcToMap * dvcdy;
  dx = (hx.xyz - p * hx.w) / h.w;
  dy = (hy.xyz - p * hy.w) / h.w;
}



float csmHash(vec2 p)
{
  return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453);
}

float csmTap(sampler2DShadow map, vec4 tile, vec2 uv, float z)
{
  vec2 inside = clamp(uv, vec2(0.5 * csmTileTexel), vec2(1.0 - 0.5 * csmTileTexel));
  return textureLod(map, vec3(tile.xy + inside * tile.zw, z), 0.0);
}

// Texel-space PCF over (2r+1) x (2r+1) texels: the mean of (2r+1)^2 hardware bilinear compares
// one texel apart around uv, taken with (r+1)^2 taps. Along each axis those compares weigh the
// 2r+2 texels they touch [1-f, 1, ..., 1, f] (f: uv's fraction between texel centres); each
// adjacent pair of texels is one bilinear tap of weight w0 + w1 placed w1/(w0+w1) past the first
// (the "optimized PCF" of The Witness / Castano 2013, exact for the box of bilinear compares).
// Every tap keeps its own receiver-plane depth (Barroso & Celes 2007, §2.2).
float csmGridPCF(sampler2DShadow map, vec4 tile, vec2 uv, float zRef, vec2 dz, int r)
{
  float maxStep = 0.05; // keep grazing receivers from throwing the taps far off their plane
  vec2 texel = uv / csmTileTexel - 0.5; // in texel-centre units
  vec2 base = floor(texel);
  vec2 f = texel - base;
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
      vec2 tap = (vec2(px, py) + 0.5) * csmTileTexel;
      vec2 o = tap - uv;
      sum += wx * wy * csmTap(map, tile, tap, zRef + clamp(dot(dz, o), -maxStep, maxStep));
    }
  }
  float n = float(2 * r + 1);
  return sum / (n * n);
}

// Jittered circular kernel of radius r + 0.5 texels: as many bilinear taps as the grid kernel,
// on a spiral rotated per pixel, so that the taps stay unaligned (Barroso & Celes 2007, §2.2).
float csmJitteredPCF(sampler2DShadow map, vec4 tile, vec2 uv, float zRef, vec2 dz, int r)
{
  float maxStep = 0.05;
  int n = (r + 1) * (r + 1);
  float turn = 6.2831853 * csmHash(gl_FragCoord.xy);
  float sum = 0.0;
  for (int i = 0; i < n; ++i)
  {
    float radius = sqrt((float(i) + 0.5) / float(n)) * (float(r) + 0.5);
    float angle = float(i) * 2.3999632 + turn;
    vec2 o = radius * vec2(cos(angle), sin(angle)) * csmTileTexel;
    sum += csmTap(map, tile, uv + o, zRef + clamp(dot(dz, o), -maxStep, maxStep));
  }
  return sum / float(n);
}

// Is a view-space point inside a cascade's map (its xy square and in front of its far plane)?
bool csmInside(mat4 vcToMap, vec4 vc)
{
  vec4 h = vcToMap * vc;
  vec3 p = h.xyz / h.w;
  return h.w > 0.0 && all(greaterThanEqual(p.xy, vec2(0.0))) && all(lessThanEqual(p.xy, vec2(1.0))) &&
    p.z <= 1.0;
}

// Visibility (1 lit, 0 shadowed) of one cascade, or -1 when the point is outside its map; the
// aliasing error m there when the error view asks for it.
float csmVisibility(sampler2DShadow map, mat4 vcToMap, vec4 tile, vec4 vc, vec4 dvcdx,
  vec4 dvcdy, out float m)
{
  m = 0.0;
  if (!csmInside(vcToMap, vc))
  {
    return -1.0;
  }
  vec3 p = csmProject(vcToMap, vc);
  vec3 dx, dy;
  csmDerivatives(vcToMap, vc, dvcdx, dvcdy, dx, dy);
  if (csmDebug == CSM_DEBUG_ERROR)
  {
    // Lloyd Eq. 1: a texel's footprint in pixels, 1 / smallest singular value of d(texel)/d(pixel).
    mat2 j = mat2(dx.xy, dy.xy) / csmTileTexel;
    float e = dot(j[0], j[0]) + dot(j[1], j[1]);
    float d = abs(determinant(j));
    float smin2 = 0.5 * (e - sqrt(max(e * e - 4.0 * d * d, 0.0)));
    m = 1.0 / sqrt(max(smin2, 1e-12));
  }
  // Receiver plane: depth change per unit of map u and v (Barroso & Celes §2.2 virtual samples).
  float det = dx.x * dy.y - dx.y * dy.x;
  vec2 dz = abs(det) > 1e-24
    ? vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det
    : vec2(0.0);
  float zSlopePerTexel = min((abs(dz.x) + abs(dz.y)) * csmTileTexel, 0.05);
  float zRef = p.z - csmConstantBias - csmSlopeBias * zSlopePerTexel;
  int r = csmPCFSize / 2;
  return csmKernel == CSM_KERNEL_GRID || r == 0 ? csmGridPCF(map, tile, p.xy, zRef, dz, r)
                                  : csmJitteredPCF(map, tile, p.xy, zRef, dz, r);
}

// Per shadowed light j (CSM_LIGHTS of them, defined by the pass), its cascades at
// [j * CSM_MAX_CASCADES, ...): view space -> map matrices, atlas tiles, far split depths.
uniform mat4 csmToMap[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform vec4 csmTile[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform float csmSplitFar[CSM_LIGHTS * CSM_MAX_CASCADES];
uniform float csmSplitNear[CSM_LIGHTS];
uniform int csmCount[CSM_LIGHTS];
uniform float csmAttenuation[CSM_LIGHTS];

// Shadow of light j: x = light factor (1 lit .. 1 - attenuation), y = cascade index (-1: none),
// z = aliasing error m (error view only), w = visibility.
vec4 csmShadow(sampler2DShadow map, int j, vec4 vc, vec4 dvcdx, vec4 dvcdy)
{
  int count = csmCount[j];
  int first = j * CSM_MAX_CASCADES;
  float depth = -vc.z;
  if (count <= 0 || depth < csmSplitNear[j] || depth > csmSplitFar[first + count - 1])
  {
    return vec4(1.0, -1.0, 0.0, 1.0); // outside every cascade: lit as without shadows
  }
  int c = 0;
  while (c < count - 1 && depth > csmSplitFar[first + c])
  {
    ++c;
  }
  float m;
  float visibility =
    csmVisibility(map, csmToMap[first + c], csmTile[first + c], vc, dvcdx, dvcdy, m);
  // A map kept from an earlier frame that misses this point: the next one that covers it.
  while (visibility < 0.0 && c + 1 < count)
  {
    ++c;
    visibility = csmVisibility(map, csmToMap[first + c], csmTile[first + c], vc, dvcdx, dvcdy, m);
  }
  if (visibility < 0.0)
  {
    return vec4(1.0, -1.0, 0.0, 1.0);
  }
  float cascadeNear = c == 0 ? csmSplitNear[j] : csmSplitFar[first + c - 1];
  float band = csmBlendBand * (csmSplitFar[first + c] - cascadeNear);
  if (c + 1 < count && band > 0.0 && depth > csmSplitFar[first + c] - band &&
    csmInside(csmToMap[first + c + 1], vc))
  {
    // Blend into the next cascade only where its map covers the point.
    float mNext;
    float next = csmVisibility(
      map, csmToMap[first + c + 1], csmTile[first + c + 1], vc, dvcdx, dvcdy, mNext);
    visibility = mix(visibility, next, (depth - (csmSplitFar[first + c] - band)) / band);
  }
  return vec4(1.0 - csmAttenuation[j] * (1.0 - visibility), float(c), m, visibility);
}

#ifdef CSM_IMPOSTOR
// Receivers drawn as impostors (VTK's tubes and spheres): the fragment's vertexVC is the point on
// the tube's axis (or the sphere's centre), its normal the impostor's. The surface the viewer
// sees is r along that normal (r: the radius VTK draws, from its ZCalcR: the radius itself for a
// parallel camera, per unit of depth for a perspective one), and its tangent plane is the
// receiver plane (screen derivatives of the axis point say nothing across the tube). The maps
// hold the casters' centre depth, which the lit side of this surface lies in front of.
uniform vec2 csmImpostorPixels; // the diameters VTK draws, in pixels: line width, point size
vec4 csmImpostorShadow(sampler2DShadow map, int j, vec4 vc, vec3 normalVC)
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
  return csmShadow(map, j, vec4(vc.xyz + r * n, vc.w), vec4(t1 * pixel, 0.0),
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
  if (csmDebug == CSM_DEBUG_CASCADES) return vec4(csmCascadeColor(r.y) * (0.35 + 0.65 * r.x), shaded.a);
  if (csmDebug == CSM_DEBUG_ERROR) return vec4(r.y < -0.5 ? vec3(0.0) : csmErrorColor(r.z) * (0.4 + 0.6 * r.x), shaded.a);
  if (csmDebug == CSM_DEBUG_FACTOR) return vec4(vec3(r.w), shaded.a);
  return shaded;
}
