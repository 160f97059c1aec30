# GLSL sources are compiled to SPIR-V at build time and embedded as byte arrays, so the binary
# needs no shader files at run time and the build fails when a shader does not compile.
#
#   vp_embed_shaders(TARGET <target> INCLUDE_DIR <dir of the shared .glsl> SHADERS <file.comp|.vert|.frag>...)
# adds a generated header <name>_spv.h per shader (an `unsigned char` array and its size) to the
# include path of <target>.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(vp_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET;INCLUDE_DIR" "SHADERS" ${ARGN})
  set(outdir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${outdir})
  set(headers)
  # Shaders share code through #include; any change to it recompiles them all.
  file(GLOB includes ${ARG_INCLUDE_DIR}/*.glsl)
  foreach(shader ${ARG_SHADERS})
    get_filename_component(name ${shader} NAME)
    string(MAKE_C_IDENTIFIER ${name} ident)
    set(spv ${outdir}/${name}.spv)
    set(header ${outdir}/${ident}_spv.h)
    add_custom_command(OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -o ${spv} ${shader}
      COMMAND ${CMAKE_COMMAND} -DINPUT=${spv} -DOUTPUT=${header} -DIDENT=${ident}
              -P ${PROJECT_SOURCE_DIR}/CMake/EmbedBinary.cmake
      DEPENDS ${shader} ${includes} ${PROJECT_SOURCE_DIR}/CMake/EmbedBinary.cmake
      COMMENT "SPIR-V ${name}")
    list(APPEND headers ${header})
  endforeach()
  target_sources(${ARG_TARGET} PRIVATE ${headers})
  target_include_directories(${ARG_TARGET} PRIVATE ${outdir})
endfunction()
