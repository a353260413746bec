# Installs the CMake package (lib/cmake/fldsim): exported targets, config and version files,
# and the plugin function, so that a third-party project can write
#   find_package(fldsim 0.1 REQUIRED)
#   fldsim_add_plugin(yukawa KIND force SOURCES ... [LIBRARIES fldsim::lubrication ...])
# The targets themselves are installed where they are defined (framework/, sdk/, plugins/).
include(CMakePackageConfigHelpers)

set(FLDSIM_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fldsim)

# The plugin API version, read from the header so there is one source of truth.
file(STRINGS ${PROJECT_SOURCE_DIR}/framework/include/fldsim/api.hpp api_lines REGEX "^#define FLDSIM_API_M")
string(REGEX REPLACE ".*FLDSIM_API_MAJOR ([0-9]+).*" "\\1" FLDSIM_API_MAJOR "${api_lines}")
string(REGEX REPLACE ".*FLDSIM_API_MINOR ([0-9]+).*" "\\1" FLDSIM_API_MINOR "${api_lines}")

install(EXPORT fldsimTargets NAMESPACE fldsim:: DESTINATION ${FLDSIM_CMAKE_INSTALL_DIR})

# The SDK support libraries (sdk/CMakeLists.txt), for the config file's COMPONENTS check.
get_property(FLDSIM_SDK_LIBRARIES GLOBAL PROPERTY FLDSIM_SDK_LIBRARIES)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/fldsimConfig.cmake.in
  ${PROJECT_BINARY_DIR}/fldsimConfig.cmake
  INSTALL_DESTINATION ${FLDSIM_CMAKE_INSTALL_DIR}
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR FLDSIM_PLUGIN_INSTALL_DIR)
# 0.x: a minor release may change the plugin API, so only the same major.minor is compatible
# (the loader checks the API version and build tag again at run time).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/fldsimConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)

install(FILES
  ${PROJECT_BINARY_DIR}/fldsimConfig.cmake
  ${PROJECT_BINARY_DIR}/fldsimConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FldsimPlugin.cmake
  DESTINATION ${FLDSIM_CMAKE_INSTALL_DIR})
