# bvhlab_add_plugin(NAME SOURCES src... [LINK_LIBRARIES lib...]): a bvhlab plugin (docs/install.md,
# framework/plugin/plugin_api.h) as a MODULE library NAME.so that links bvhlab::plugin_api, its
# symbols hidden but for the two entry points BVHLAB_PLUGIN exports. Called from bvhlab's own
# CMake files it builds into <build>/plugins/ and installs into lib/bvhlab/plugins/; called from
# another project (find_package(bvhlab) or add_subdirectory) it builds into that project's folder.
include_guard(GLOBAL)

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
  if(PROJECT_NAME STREQUAL "bvhlab")
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/plugins)
    include(GNUInstallDirs)
    install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/bvhlab/plugins)
  endif()
endfunction()
