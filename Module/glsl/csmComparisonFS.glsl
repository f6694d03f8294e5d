// SPDX-License-Identifier: BSD-3-Clause
// The comparison techniques' part of the shadow lookup (csmShadowFS.glsl), in a build with
// CSM_COMPARISON_TECHNIQUES only: vtkCascadedShadowMapPass puts it between its #defines and
// csmShadowFS.glsl where a light's maps are face partitions (CSM_FACES: selected by their
// half-spaces) or camera space maps (CSM_CAMERA_SPACE: a depth bias that follows each ray's w).

#ifdef CSM_CAMERA_SPACE
uniform float csmDepthW[CSM_LIGHTS * CSM_MAX_CASCADES];
// Scale of the constant depth bias of cascade `cascade` at map coordinates h: a camera space
// map's depth spans wMin / w on a ray of w (csm::computeCameraSpaceMap); 1 for other maps.
float csmDepthBiasScale(int cascade, vec4 h)
{
  return csmDepthW[cascade] > 0.0 ? csmDepthW[cascade] / max(h.w, 1e-30) : 1.0;
}
#endif

#ifdef CSM_FACES
// Face partitions (Lloyd et al. 2006, §5.1): each map's piece of the frustum as 4 view-space
// half-spaces; the pieces tile the frustum, so a point belongs to the one whose smallest plane
// distance is largest (inside it, up to rounding; the same rule as csm::partitionAt).
uniform vec4 csmPlanes[CSM_LIGHTS * CSM_MAX_CASCADES * 4];
int csmPartitionAt(int j, int count, vec4 vc)
{
  int first = j * CSM_MAX_CASCADES;
  int best = 0;
  float bestDistance = -3.4e38;
  for (int i = 0; i < count; ++i)
  {
    int p = 4 * (first + i);
    vec4 v = vec4(vc.xyz, 1.0);
    float d = min(min(dot(csmPlanes[p], v), dot(csmPlanes[p + 1], v)),
      min(dot(csmPlanes[p + 2], v), dot(csmPlanes[p + 3], v)));
    best = d > bestDistance ? i : best;
    bestDistance = max(d, bestDistance);
  }
  return best;
}
#endif
