# fldsim_add_plugin(<name> KIND <shape|hydro|force|observer> SOURCES ... [LIBRARIES ...])
#
# Builds one plugin as a MODULE library named fldsim-<kind>-<name>.so and installs it into the
# plugin directory. The same function serves the fldsim tree and third-party projects (it is
# installed next to fldsimConfig.cmake and included by find_package(fldsim)).
#
# - hidden visibility: only the FLDSIM_PLUGIN descriptor and entry points are exported, so two
#   plugins never see each other's symbols (Boost.DLL FAQ, "symbol shadowing");
# - -Wl,--no-undefined: a missing symbol is a link error here, not a load failure at run time;
# - links fldsim::core, which brings the include path, C++20, BOOST_DLL_USE_STD_FS and Eigen,
#   i.e. everything that must match the core for the build tag check to pass.
#
# Variables (set them before the call to override):
#   FLDSIM_PLUGIN_BUILD_DIR    where the .so is written in the build tree; point
#                              FLDSIM_PLUGIN_PATH here to use plugins without installing
#                              (default: <build>/plugins)
#   FLDSIM_PLUGIN_INSTALL_DIR  install destination, relative to CMAKE_INSTALL_PREFIX or absolute
#                              (default: <libdir>/fldsim/plugins; the fldsim found by
#                              find_package keeps its own in fldsim_PLUGIN_DIR)
include_guard(GLOBAL)
include(GNUInstallDirs)

function(fldsim_add_plugin name)
  cmake_parse_arguments(P "" "KIND" "SOURCES;LIBRARIES" ${ARGN})
  if(NOT P_KIND MATCHES "^(shape|hydro|force|observer)$")
    message(FATAL_ERROR "fldsim_add_plugin(${name}): KIND must be shape, hydro, force or observer, got '${P_KIND}'")
  endif()
  if(NOT P_SOURCES)
    message(FATAL_ERROR "fldsim_add_plugin(${name}): no SOURCES given")
  endif()
  if(NOT TARGET fldsim::core)
    message(FATAL_ERROR "fldsim_add_plugin(${name}): target fldsim::core not found; call find_package(fldsim) first")
  endif()
  set(build_dir ${CMAKE_BINARY_DIR}/plugins)
  if(DEFINED FLDSIM_PLUGIN_BUILD_DIR)
    set(build_dir ${FLDSIM_PLUGIN_BUILD_DIR})
  endif()
  set(install_dir ${CMAKE_INSTALL_LIBDIR}/fldsim/plugins)
  if(DEFINED FLDSIM_PLUGIN_INSTALL_DIR)
    set(install_dir ${FLDSIM_PLUGIN_INSTALL_DIR})
  endif()

  set(target fldsim-${P_KIND}-${name})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE fldsim::core ${P_LIBRARIES})
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${build_dir})
  target_link_options(${target} PRIVATE -Wl,--no-undefined)

  # Where the installed plugin finds libfldsim when something other than the fldsim executable
  # loads it (ldd, a test program): relative to itself, so a prefix can be moved. Installed in
  # fldsim's own prefix (the default layout) the core sits at <libdir>, i.e. $ORIGIN/../.. from
  # <libdir>/fldsim/plugins. A third-party plugin installed elsewhere also keeps, after that, the
  # directory of the core it linked with.
  if(IS_ABSOLUTE "${install_dir}")
    set_target_properties(${target} PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
  else()
    file(RELATIVE_PATH to_core /${install_dir} /${CMAKE_INSTALL_LIBDIR})
    set(rpath "$ORIGIN/${to_core}")
    get_target_property(core_imported fldsim::core IMPORTED)
    if(core_imported)
      get_target_property(core_file fldsim::core LOCATION)
      get_filename_component(core_dir "${core_file}" DIRECTORY)
      list(APPEND rpath "${core_dir}")
    endif()
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "${rpath}")
  endif()

  install(TARGETS ${target} LIBRARY DESTINATION ${install_dir})
  set_property(GLOBAL APPEND PROPERTY FLDSIM_PLUGIN_TARGETS ${target})
endfunction()
