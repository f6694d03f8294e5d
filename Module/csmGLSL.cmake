# SPDX-License-Identifier: BSD-3-Clause
# GLSL lives in its own files and is embedded at build time (Module/CMakeLists.txt; the
# ParaView plugin builds the same module file).
set(csm_glsl_files csmShadowFS csmCaster csmCasterLineGS csmScreenProbeVS csmScreenProbeFS)

# csm_encode_glsl_files(<Module dir> <names> <sources var> <headers var>): glsl/<name>.glsl each
function(csm_encode_glsl_files module_dir names sources_var headers_var)
  set(sources)
  set(headers)
  foreach(glsl IN LISTS names)
    vtk_encode_string(
      INPUT "${module_dir}/glsl/${glsl}.glsl"
      HEADER_OUTPUT glsl_header
      SOURCE_OUTPUT glsl_source)
    list(APPEND sources ${glsl_source})
    list(APPEND headers ${glsl_header})
  endforeach()
  set(${sources_var} ${sources} PARENT_SCOPE)
  set(${headers_var} ${headers} PARENT_SCOPE)
endfunction()

# csm_encode_glsl(<Module dir> <sources var> <headers var>): the files every build has
function(csm_encode_glsl module_dir sources_var headers_var)
  csm_encode_glsl_files("${module_dir}" "${csm_glsl_files}" sources headers)
  set(${sources_var} ${sources} PARENT_SCOPE)
  set(${headers_var} ${headers} PARENT_SCOPE)
endfunction()
