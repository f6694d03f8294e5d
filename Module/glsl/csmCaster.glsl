// SPDX-License-Identifier: BSD-3-Clause
// Screen-sized casters in the shadow maps: lines drawn as tubes (or wide lines) and points drawn
// as spheres (or big points). VTK sizes them in the main view's pixels, so their world radius
// grows with their depth in the main view; the maps draw them with that world radius, seen from
// the light. Injected into the map pass's shaders by vtkCascadedShadowMapBakerPass; the map's
// depth stays the centre line's (or centre's), which the impostor's lit side lies in front of.
// The same pass draws the view's depth before the frame (CSM_CASTER_VIEW_DEPTH, below).

uniform mat4 csmMapToView;   // this cascade's light clip coordinates -> main camera view space
uniform mat4 csmViewToMap;   // main camera view space -> this cascade's light clip coordinates
uniform vec4 csmLightView;   // main view space: toward a directional light (w = 0), or the
                             // light's position (w = 1)
uniform vec2 csmPixelWorld;  // world size of one main-view pixel at view depth d: x + y d
uniform vec2 csmCasterWidth; // the prop's line width and point size, in main-view pixels
uniform vec4 csmMapViewport; // this cascade's tile in the atlas, in texels: x, y, width, height

// Main-view position of a light clip position.
vec3 csmViewOf(vec4 clip)
{
  vec4 v = csmMapToView * clip;
  return v.xyz / v.w;
}

// Radius in world units of a caster whose main-view diameter is `pixels`, at a view position.
float csmRadius(float pixels, vec3 view)
{
  return 0.5 * pixels * (csmPixelWorld.x + csmPixelWorld.y * max(-view.z, 0.0));
}

// Unit direction toward the light from a view position.
vec3 csmTowardLight(vec3 view)
{
  vec3 l = csmLightView.w == 0.0 ? csmLightView.xyz : csmLightView.xyz - view;
  return normalize(l);
}

// A unit vector perpendicular to both a and the unit vector l (any one if a is along l).
vec3 csmAcross(vec3 a, vec3 l)
{
  vec3 e = cross(a, l);
  if (dot(e, e) <= 1e-12 * max(dot(a, a), 1e-30))
  {
    e = cross(abs(l.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0), l);
  }
  return normalize(e);
}

// Light clip position of a view-space displacement from a light clip position (exact: the
// map is projective, and the displacement has w = 0).
vec4 csmDisplace(vec4 clip, vec3 viewOffset)
{
  return clip + csmViewToMap * vec4(viewOffset, 0.0);
}

// Side of the square sprite, in texels, that holds the silhouette of a sphere of radius r
// (seen from the light) centred at a light clip position.
float csmSpriteTexels(vec4 clip, vec3 view, float r)
{
  vec3 l = csmTowardLight(view);
  vec3 a = csmAcross(vec3(0.0, 0.0, 1.0), l);
  vec3 b = cross(l, a);
  vec2 centre = clip.xy / clip.w;
  vec4 ca = csmDisplace(clip, a * r);
  vec4 cb = csmDisplace(clip, b * r);
  vec2 da = (ca.xy / ca.w - centre) * 0.5 * csmMapViewport.zw;
  vec2 db = (cb.xy / cb.w - centre) * 0.5 * csmMapViewport.zw;
  // Half extents of the ellipse spanned by da and db along the map's axes.
  vec2 extent = sqrt(da * da + db * db);
  return 2.0 * max(extent.x, extent.y) + 1.0;
}

#ifdef CSM_CASTER_VERTEX
// Points: the sprite that holds the sphere's silhouette (big points: its square), and the
// sphere (view-space centre, radius) for the fragment shader. Points of size 1 stay 1 texel.
flat out vec4 csmSphereView;
void csmSizePoint(vec4 clip)
{
  csmSphereView = vec4(0.0);
  gl_PointSize = 1.0;
  if (csmCasterWidth.y > 1.0)
  {
    vec3 view = csmViewOf(clip);
    float r = csmRadius(csmCasterWidth.y, view);
    csmSphereView = vec4(view, r);
    gl_PointSize = csmSpriteTexels(clip, view, r);
  }
}
#endif

#ifdef CSM_CASTER_SPHERE_FRAGMENT
flat in vec4 csmSphereView;
// Is this map fragment outside the silhouette of the sphere, seen from the light?
bool csmOutsideSphere()
{
  if (csmSphereView.w <= 0.0)
  {
    return false;
  }
  vec4 centreClip = csmViewToMap * vec4(csmSphereView.xyz, 1.0);
  vec2 ndc = (gl_FragCoord.xy - csmMapViewport.xy) / csmMapViewport.zw * 2.0 - 1.0;
  vec3 q = csmViewOf(vec4(ndc, centreClip.z / centreClip.w, 1.0));
  vec3 l = csmTowardLight(q);
  vec3 d = csmSphereView.xyz - q;
  vec3 offAxis = d - dot(d, l) * l; // the centre's distance from the light ray through q
  return dot(offAxis, offAxis) > csmSphereView.w * csmSphereView.w;
}
#endif

#ifdef CSM_CASTER_VIEW_DEPTH
uniform float csmViewDepthNudge; // window depth: a few steps of the depth buffer
// The view's depth pass (vtkCascadedShadowCasterPass::SetViewDepthNudge): a surface's depth
// written behind its depth at every sample the fragment covers (which differs from the pixel
// centre's by at most half the fwidth), so that the frame's own geometry passes it.
float csmViewDepth(float depth)
{
  return depth + fwidth(gl_FragCoord.z) + csmViewDepthNudge;
}
#endif
