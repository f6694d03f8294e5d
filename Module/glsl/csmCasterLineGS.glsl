//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause

// The map pass's geometry shader for lines that VTK widens (tubes, and wide lines the GL cannot
// draw): each segment becomes the quad the tube shows the light, as wide as the tube the main
// view draws at each end (csmCaster.glsl). The tags are those of VTK's wide-line template, so
// the mapper passes its varyings through as it would there.

//VTK::PositionVC::Dec
//VTK::PrimID::Dec
//VTK::Color::Dec
//VTK::Normal::Dec
//VTK::Light::Dec
//VTK::TCoord::Dec
//VTK::Picking::Dec
//VTK::DepthPeeling::Dec
//VTK::Clip::Dec
//VTK::Output::Dec

//CSM::Caster::Dec

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

void main()
{
  // The segment's direction in the map (VTK's tube code builds its basis from it).
  vec2 normal = gl_in[1].gl_Position.xy / gl_in[1].gl_Position.w -
    gl_in[0].gl_Position.xy / gl_in[0].gl_Position.w;
  normal = dot(normal, normal) > 0.0 ? normalize(vec2(-normal.y, normal.x)) : vec2(1.0, 0.0);

  vec3 end0 = csmViewOf(gl_in[0].gl_Position);
  vec3 end1 = csmViewOf(gl_in[1].gl_Position);

  //VTK::Normal::Start

  for (int j = 0; j < 4; j++)
  {
    int i = j / 2;
    float side = (j % 2 == 0) ? 1.0 : -1.0;

    //VTK::PrimID::Impl
    //VTK::Clip::Impl
    //VTK::Color::Impl
    //VTK::Normal::Impl
    //VTK::Light::Impl
    //VTK::TCoord::Impl
    //VTK::DepthPeeling::Impl
    //VTK::Picking::Impl
    //VTK::PositionVC::Impl

    vec3 end = i == 0 ? end0 : end1;
    vec3 across = csmAcross(end1 - end0, csmTowardLight(end));
    gl_Position =
      csmDisplace(gl_in[i].gl_Position, across * side * csmRadius(csmCasterWidth.x, end));
    EmitVertex();
  }
  EndPrimitive();
}
