# The SDK support libraries from a third party's side: examples/sdk_observer, an observer plugin
# that links fldsim::lubrication (LubricationPair's Jeffrey-Onishi scalars) and fldsim::statistics
# (BlockAverage, write_blocked), is built against the installed prefix only; the installed CLI
# loads it and runs two unit spheres held at a surface gap of 0.05 a (examples/two_spheres.yaml).
# Reference: the singular terms of X^A_11 for equal spheres, 1/(4 xi) + (9/40) ln(1/xi)
# (Jeffrey & Onishi 1984, J. Fluid Mech. 139, 261), at xi = 0.05: 5 + 0.225 ln 20 = 5.6740398.
# Every sample sees the same gap, so the mean is that value to round-off; `fldsim summary` prints
# at least 6 significant digits, hence the tolerance 1e-5 (a wrong coefficient, e.g. the log term
# dropped, is off by 0.67).
include(${CMAKE_CURRENT_LIST_DIR}/sdk_common.cmake)
set(source ${SOURCE_DIR}/examples/sdk_observer)
set(build ${WORK}/sdk_observer)
set(run ${WORK}/sdk_observer_run)
file(REMOVE_RECURSE ${build} ${run})
file(MAKE_DIRECTORY ${run})

sdk_run("configure examples/sdk_observer against ${PREFIX}" COMMAND ${CMAKE_COMMAND} -S ${source} -B ${build}
        -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
sdk_run("build the plugin (links fldsim::lubrication, fldsim::statistics)" COMMAND ${CMAKE_COMMAND} --build ${build} -j2)

sdk_plugin_path(${build}/plugins)
sdk_run("fldsim plugins" OUT out COMMAND ${FLDSIM} plugins)
sdk_expect("squeeze listed" "${out}" "observer squeeze 1.0.0")
sdk_expect("squeeze from its build tree" "${out}" "file: ${build}/plugins/fldsim-observer-squeeze.so")

sdk_run("fldsim run two_spheres.yaml" COMMAND ${FLDSIM} run ${source}/examples/two_spheres.yaml -o ${run}/two_spheres.h5 -q)
sdk_run("fldsim summary" OUT out COMMAND ${FLDSIM} summary ${run}/two_spheres.h5)
message(STATUS "${out}")

# The one near pair at every sample, and its X^A_11 against the closed form.
if(NOT out MATCHES "squeeze/near_pairs +([^ ]+) ")
  message(FATAL_ERROR "no squeeze/near_pairs in the summary:\n${out}")
endif()
if(NOT CMAKE_MATCH_1 STREQUAL "1")
  message(FATAL_ERROR "squeeze/near_pairs = ${CMAKE_MATCH_1}, expected 1 (the two spheres)")
endif()
if(NOT out MATCHES "squeeze/X_A +([^ ]+) ")
  message(FATAL_ERROR "no squeeze/X_A in the summary:\n${out}")
endif()
set(x_a ${CMAKE_MATCH_1})
set(reference 5.6740398)
if(NOT (x_a GREATER 5.6740298 AND x_a LESS 5.6740498))
  message(FATAL_ERROR "squeeze/X_A = ${x_a}, expected ${reference} +- 1e-5 "
          "(Jeffrey-Onishi X^A_11 at xi = 0.05, computed with fldsim::lubrication)")
endif()
message(STATUS "ok: X^A_11 = ${x_a} (closed form ${reference}) from the out-of-tree plugin")
