//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// The vertex stage of the program that tries whether the shaders which keep a frame's shadow
// factors compile (csmScreenProbeFS.glsl).
in vec4 vertexMC;

void main()
{
  gl_Position = vertexMC;
}
