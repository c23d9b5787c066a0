# Installs the library, its headers and a CMake package so that
# find_package(bounce) gives the bounce::bounce target. The layers (src/CMakeLists.txt) are
# installed as bounce::core, bounce::scene, ...; bounce::bounce links them all. Installed headers
# share one include directory: the layering is enforced where the library is built.
include(CMakePackageConfigHelpers)
get_property(BOUNCE_LAYER_TARGETS GLOBAL PROPERTY BOUNCE_LAYER_TARGETS)
install(TARGETS bounce ${BOUNCE_LAYER_TARGETS} bounce_app EXPORT bounceTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY src/bounce DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h"
  PATTERN "*_internal.h" EXCLUDE)  # private to one layer
install(EXPORT bounceTargets NAMESPACE bounce:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bounce)
configure_package_config_file(cmake/bounceConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/bounceConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bounce)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/bounceConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/bounceConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/bounceConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bounce)
