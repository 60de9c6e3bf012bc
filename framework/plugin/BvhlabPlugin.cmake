# bvhlab_add_plugin(NAME SOURCES src... [LINK_LIBRARIES lib...]): a bvhlab plugin (docs/install.md,
# <bvhlab/plugin.h>) as a MODULE library NAME.so that links bvhlab::plugin_api, its
# symbols hidden but for the three entry points BVHLAB_PLUGIN exports, its compile flags recorded
# (bvhlab_record_plugin_flags). Called from bvhlab's own CMake files it builds into
# <build>/plugins/ and installs into lib/bvhlab/plugins/; called from another project
# (find_package(bvhlab) or add_subdirectory) it builds into that project's folder.
include_guard(GLOBAL)

# bvhlab_record_plugin_flags(TARGET): passes the flags TARGET's sources are compiled with to the
# build info BVHLAB_PLUGIN records (<bvhlab/plugin.h>), which bvhlab puts in the
# provenance of every run: CMAKE_CXX_FLAGS, those of the build's configuration and the target's
# compile options, its own and those of the libraries it links. The flags CMake adds by itself
# (-std, -fPIC, -fvisibility) and per-source options are not among them.
function(bvhlab_record_plugin_flags target)
  set(configs Debug Release RelWithDebInfo MinSizeRel ${CMAKE_CONFIGURATION_TYPES} ${CMAKE_BUILD_TYPE})
  list(TRANSFORM configs TOUPPER)
  list(REMOVE_DUPLICATES configs)
  # The flags as a list of generator expressions, in which a literal `,` must be $<COMMA>.
  string(STRIP "${CMAKE_CXX_FLAGS}" flags)
  string(REPLACE "," "$<COMMA>" pieces "${flags}")
  foreach(config IN LISTS configs)
    string(STRIP "${CMAKE_CXX_FLAGS_${config}}" flags)
    string(REPLACE "," "$<COMMA>" flags "${flags}")
    list(APPEND pieces "$<$<CONFIG:${config}>:${flags}>")
  endforeach()
  # Once each, as CMake passes them.
  list(APPEND pieces "$<REMOVE_DUPLICATES:$<TARGET_PROPERTY:${target},COMPILE_OPTIONS>>")
  set(flags "$<JOIN:$<FILTER:${pieces},EXCLUDE,^$>, >")
  # A C string literal: quotes and backslashes escaped.
  string(REPLACE "\\" "\\\\" flags "${flags}")
  string(REPLACE "\"" "\\\"" flags "${flags}")
  target_compile_definitions(${target} PRIVATE "BVHLAB_PLUGIN_CXX_FLAGS=\"${flags}\"")
endfunction()

function(bvhlab_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK_LIBRARIES" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "bvhlab_add_plugin(${name}): unknown arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "bvhlab_add_plugin(${name}): no SOURCES")
  endif()
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE bvhlab::plugin_api ${ARG_LINK_LIBRARIES})
  set_target_properties(${name} PROPERTIES PREFIX "" CXX_EXTENSIONS OFF CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  bvhlab_record_plugin_flags(${name})
  if(PROJECT_NAME STREQUAL "bvhlab")
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/plugins)
    include(GNUInstallDirs)
    install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/bvhlab/plugins)
  endif()
endfunction()
