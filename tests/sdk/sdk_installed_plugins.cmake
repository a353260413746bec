# The installed CLI must find the installed plugins (<prefix>/<libdir>/fldsim/plugins) by itself,
# with no FLDSIM_PLUGIN_PATH, wherever the prefix is (here a temporary one, not the configured
# CMAKE_INSTALL_PREFIX), and must not pick them up from the build tree instead.
include(${CMAKE_CURRENT_LIST_DIR}/sdk_common.cmake)
sdk_plugin_path("")
sdk_run("installed fldsim plugins" OUT out COMMAND ${FLDSIM} plugins)
string(REPLACE "," ";" plugins "${PLUGINS}")
foreach(p ${plugins})
  string(FIND "${out}" "file: ${PREFIX}/${LIBDIR}/fldsim/plugins/${p}.so" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the installed fldsim did not find ${p} in ${PREFIX}/${LIBDIR}/fldsim/plugins "
            "(the core must locate its install plugin directory relative to libfldsim.so, not "
            "from the configured CMAKE_INSTALL_PREFIX; docs/sdk.md section 7). It printed:\n${out}")
  endif()
endforeach()
message(STATUS "ok: all installed plugins found in ${PREFIX}/${LIBDIR}/fldsim/plugins")
