# cmake --install of the build tree into a fresh prefix; checks every promised file is there and
# that the installed program starts (its RPATH finds the installed core).
include(${CMAKE_CURRENT_LIST_DIR}/sdk_common.cmake)
file(REMOVE_RECURSE ${WORK})
sdk_run("install into ${PREFIX}" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})

set(expected bin/fldsim ${LIBDIR}/libfldsim.so include/fldsim/api.hpp include/fldsim/plugin.hpp
    ${LIBDIR}/cmake/fldsim/fldsimConfig.cmake ${LIBDIR}/cmake/fldsim/fldsimConfigVersion.cmake
    ${LIBDIR}/cmake/fldsim/fldsimTargets.cmake ${LIBDIR}/cmake/fldsim/FldsimPlugin.cmake)
string(REPLACE "," ";" plugins "${PLUGINS}")
foreach(p ${plugins})
  list(APPEND expected ${LIBDIR}/fldsim/plugins/${p}.so)
endforeach()
foreach(f ${expected})
  if(NOT EXISTS ${PREFIX}/${f})
    message(FATAL_ERROR "missing from the install: ${PREFIX}/${f}")
  endif()
endforeach()
list(LENGTH plugins n)
message(STATUS "ok: ${n} plugins and the package files installed")

# Private headers must not leak into the install.
file(GLOB_RECURSE headers RELATIVE ${PREFIX}/include ${PREFIX}/include/*)
foreach(h ${headers})
  if(NOT h MATCHES "^fldsim/[a-z_]+\\.hpp$")
    message(FATAL_ERROR "unexpected installed header: ${h}")
  endif()
endforeach()

sdk_plugin_path("")
sdk_run("installed fldsim starts" OUT out COMMAND ${FLDSIM} --help)
sdk_expect("fldsim --help" "${out}" "summary RUN.h5")
