# A third-party plugin end to end: build examples/plugin_template against the installed prefix,
# run its own test (the force of `yukawa` between two spheres against the closed form), install
# it, and use it through the installed CLI: listed by `fldsim plugins`, accepted and rejected by
# `fldsim check` with the plugin's own schema, and run from YAML.
include(${CMAKE_CURRENT_LIST_DIR}/sdk_common.cmake)
set(template ${SOURCE_DIR}/examples/plugin_template)
set(build ${WORK}/template)
set(plugin_prefix ${WORK}/yukawa_prefix)
file(REMOVE_RECURSE ${build} ${plugin_prefix} ${WORK}/yukawa_run)

sdk_run("configure the template against ${PREFIX}" COMMAND ${CMAKE_COMMAND} -S ${template} -B ${build}
        -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
sdk_run("build the template" COMMAND ${CMAKE_COMMAND} --build ${build} -j2)
sdk_run("the template's test: yukawa force = closed form" OUT out
        COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${build} --output-on-failure)
sdk_expect("yukawa_test passed" "${out}" "100% tests passed")

sdk_run("install the plugin" COMMAND ${CMAKE_COMMAND} --install ${build} --prefix ${plugin_prefix})
set(installed ${plugin_prefix}/${LIBDIR}/fldsim/plugins/fldsim-force-yukawa.so)
if(NOT EXISTS ${installed})
  message(FATAL_ERROR "the template did not install ${installed}")
endif()

# Relocatable: the installed plugin finds the core relative to itself first ($ORIGIN/../.. in
# fldsim's layout), not only through an absolute path.
find_program(READELF readelf)
if(READELF)
  execute_process(COMMAND ${READELF} -d ${installed} OUTPUT_VARIABLE dynamic)
  sdk_expect("RUNPATH relative to the plugin" "${dynamic}" "[$ORIGIN/../..")
endif()

# Found through FLDSIM_PLUGIN_PATH, with its parameters.
sdk_plugin_path(${plugin_prefix}/${LIBDIR}/fldsim/plugins)
sdk_run("fldsim plugins" OUT out COMMAND ${FLDSIM} plugins)
sdk_expect("yukawa listed" "${out}" "force yukawa 1.0.0")
sdk_expect("yukawa from the install" "${out}" "file: ${installed}")
sdk_expect("yukawa's schema" "${out}" "debye_length: a number > 0 [a], default 0.05")
sdk_expect("no library failed" "${out}" "search path:")
string(FIND "${out}" "not loaded:" failed)
if(NOT failed EQUAL -1)
  message(FATAL_ERROR "a library failed to load:\n${out}")
endif()

# The experiment file of the template validates; a value outside the plugin's range is refused
# with the documented one-line error and exit code 2.
set(yaml ${template}/examples/yukawa.yaml)
sdk_run("fldsim check yukawa.yaml" OUT out COMMAND ${FLDSIM} check ${yaml})
sdk_expect("check says valid" "${out}" "valid (27 x sphere, hydro free_draining, 1 force(s)")
file(MAKE_DIRECTORY ${WORK}/yukawa_run)
file(READ ${yaml} text)
string(REPLACE "debye_length: 0.1" "debye_length: -0.1" text "${text}")
file(WRITE ${WORK}/yukawa_run/bad.yaml "${text}")
sdk_run("fldsim check bad.yaml" OUT out RESULT rc COMMAND ${FLDSIM} check ${WORK}/yukawa_run/bad.yaml)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "fldsim check bad.yaml: expected exit code 2, got ${rc}:\n${out}")
endif()
sdk_expect("range error" "${out}" "debye_length: expected a number > 0, got -0.1")

# A short run: the plugin's object is made, asked for its range and used at every step.
sdk_run("fldsim run yukawa.yaml" COMMAND ${FLDSIM} run ${yaml} -o ${WORK}/yukawa_run/yukawa.h5 -q)
sdk_run("fldsim summary" OUT out COMMAND ${FLDSIM} summary ${WORK}/yukawa_run/yukawa.h5)
message(STATUS "${out}")
