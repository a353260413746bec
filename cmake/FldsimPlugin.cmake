# fldsim_add_plugin(<name> KIND <shape|hydro|force|observer> SOURCES ... [LIBRARIES ...])
# Builds one plugin as a MODULE library named fldsim-<kind>-<name>.so in the build's plugin
# directory, with hidden visibility and no undefined symbols (a missing symbol is a link error
# here rather than a crash at run time).
function(fldsim_add_plugin name)
  cmake_parse_arguments(P "" "KIND" "SOURCES;LIBRARIES" ${ARGN})
  set(target fldsim-${P_KIND}-${name})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE fldsim::core ${P_LIBRARIES})
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${FLDSIM_PLUGIN_BUILD_DIR})
  target_link_options(${target} PRIVATE -Wl,--no-undefined)
  install(TARGETS ${target} LIBRARY DESTINATION ${FLDSIM_PLUGIN_INSTALL_DIR})
  set_property(GLOBAL APPEND PROPERTY FLDSIM_PLUGIN_TARGETS ${target})
endfunction()
