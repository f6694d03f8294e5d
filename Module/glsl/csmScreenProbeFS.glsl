// SPDX-License-Identifier: BSD-3-Clause
// A fragment shader that stores (CSM_SCREEN_STORE) or reads (CSM_SCREEN_READ) the shadow
// factors at the pixel, as a prop's shader would: compiled once per window and sample count
// before any prop's shader has them (vtkCascadedShadowMapPass::ScreenShadersCompile). The pass
// puts the #version, the extensions, its #defines and csmShadowFS.glsl before it.
uniform sampler2DShadow csmMap0;
uniform csmTexelSampler csmNearest0;

//VTK::Output::Dec

void main()
{
#if CSM_SCREEN == CSM_SCREEN_STORE
  csmScreenStore(
    csmShadow(csmMap0, csmNearest0, 0, vec4(0.0, 0.0, -1.0, 1.0), vec4(0.0), vec4(0.0)));
  gl_FragData[0] = vec4(1.0);
#else
  gl_FragData[0] = csmScreenRead();
#endif
}
