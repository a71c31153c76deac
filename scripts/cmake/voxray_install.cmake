# Installs the headers and exports voxray::voxray and the backend targets that were
# configured, so that find_package(voxray) works in another project.
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS voxray ${VOXRAY_BACKEND_TARGETS} EXPORT voxray-targets)
install(EXPORT voxray-targets NAMESPACE voxray:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxray)

configure_package_config_file(${PROJECT_SOURCE_DIR}/scripts/cmake/voxray-config.cmake.in
    ${PROJECT_BINARY_DIR}/voxray-config.cmake
    INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxray)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/voxray-config-version.cmake
    COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/voxray-config.cmake ${PROJECT_BINARY_DIR}/voxray-config-version.cmake
    DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxray)
