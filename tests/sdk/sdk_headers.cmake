# Each installed public header compiles alone (twice included, -Werror) with only the installed
# prefix on the include path: no framework/src includes, nothing missing.
include(${CMAKE_CURRENT_LIST_DIR}/sdk_common.cmake)
set(build ${WORK}/header_check)
sdk_run("configure header_check against ${PREFIX}" COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/header_check
        -B ${build} -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_CXX_COMPILER=${CXX}
        -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
# Keep going after a failure so the output names every header that does not compile alone.
set(keep_going)
if(GENERATOR MATCHES "Makefiles")
  set(keep_going -- -k)
elseif(GENERATOR MATCHES "Ninja")
  set(keep_going -- -k 0)
endif()
sdk_run("every public header compiles alone" COMMAND ${CMAKE_COMMAND} --build ${build} -j2 ${keep_going})
