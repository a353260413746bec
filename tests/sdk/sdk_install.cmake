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

# The SDK support libraries: each exported by the package (fldsim::<name>) with its headers
# under include/fldsim-sdk/<name>/; the static archive unless header only.
string(REPLACE "," ";" sdk_libraries "${SDK_LIBRARIES}")
file(READ ${PREFIX}/${LIBDIR}/cmake/fldsim/fldsimTargets.cmake targets)
foreach(lib ${sdk_libraries})
  string(FIND "${targets}" "add_library(fldsim::${lib} " at)
  if(at EQUAL -1)
    message(FATAL_ERROR "fldsim::${lib} is not exported: not in ${PREFIX}/${LIBDIR}/cmake/fldsim/fldsimTargets.cmake")
  endif()
  file(GLOB lib_headers ${PREFIX}/include/fldsim-sdk/${lib}/*.hpp)
  if(NOT lib_headers)
    message(FATAL_ERROR "no headers installed for fldsim::${lib} in ${PREFIX}/include/fldsim-sdk/${lib}")
  endif()
endforeach()
foreach(f ${LIBDIR}/libfldsim-lubrication.a ${LIBDIR}/libfldsim-statistics.a
          include/fldsim-sdk/lubrication/LubricationPair.hpp include/fldsim-sdk/statistics/BlockAverage.hpp)
  if(NOT EXISTS ${PREFIX}/${f})
    message(FATAL_ERROR "missing from the install: ${PREFIX}/${f}")
  endif()
endforeach()

# Private headers must not leak into the install: include/fldsim holds the plugin API only,
# include/fldsim-sdk/<name> the SDK libraries, and their headers include nothing but the two.
list(JOIN sdk_libraries "|" sdk_alternatives)
file(GLOB_RECURSE headers RELATIVE ${PREFIX}/include ${PREFIX}/include/*)
foreach(h ${headers})
  if(NOT h MATCHES "^fldsim/[a-z_]+\\.hpp$" AND NOT h MATCHES "^fldsim-sdk/(${sdk_alternatives})/[A-Za-z]+\\.hpp$")
    message(FATAL_ERROR "unexpected installed header: ${h}")
  endif()
  file(STRINGS ${PREFIX}/include/${h} quoted REGEX "^#include \"")
  foreach(line ${quoted})
    string(REGEX REPLACE "^#include \"([^\"]*)\".*" "\\1" included "${line}")
    if(NOT included MATCHES "^fldsim(-sdk)?/" OR NOT EXISTS ${PREFIX}/include/${included})
      message(FATAL_ERROR "${h} includes a header that is not installed: ${line}")
    endif()
  endforeach()
endforeach()

sdk_plugin_path("")
sdk_run("installed fldsim starts" OUT out COMMAND ${FLDSIM} --help)
sdk_expect("fldsim --help" "${out}" "summary RUN.h5")
