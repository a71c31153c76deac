# Installs the headers, the voxray tool and the CMake package (when VOXRAY_INSTALL is on).
# The package has one export per component (core, then cpu, opencl, vulkan, embree,
# nanovdb, kernels: those configured here), so find_package(voxray COMPONENTS ...) loads, and looks
# for the dependencies of, only the components a project asks for (voxray-config.cmake.in).
include(CMakePackageConfigHelpers)
set(VOXRAY_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/voxray)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${VOXRAY_GENERATED}/voxray/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxray)
# Includable traversal sources for users' own GLSL shaders and OpenCL kernels.
install(DIRECTORY ${VOXRAY_GENERATED}/voxray/shaders DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxray)
install(TARGETS voxray EXPORT voxray-targets)
install(EXPORT voxray-targets NAMESPACE voxray:: DESTINATION ${VOXRAY_CMAKE_DIR})
foreach(name target IN ZIP_LISTS VOXRAY_BACKENDS VOXRAY_BACKEND_TARGETS)
    install(TARGETS ${target} EXPORT voxray-${name}-targets)
    install(EXPORT voxray-${name}-targets NAMESPACE voxray:: DESTINATION ${VOXRAY_CMAKE_DIR})
endforeach()
# The compiled kernels (voxray::kernels): a component of its own, after cpu, which it needs.
if(TARGET voxray_kernels)
    install(TARGETS voxray_kernels EXPORT voxray-kernels-targets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
    install(EXPORT voxray-kernels-targets NAMESPACE voxray:: DESTINATION ${VOXRAY_CMAKE_DIR})
    set(VOXRAY_COMPONENTS ${VOXRAY_BACKENDS} kernels)
else()
    set(VOXRAY_COMPONENTS ${VOXRAY_BACKENDS})
endif()
if(TARGET voxray_tool)
    install(TARGETS voxray_tool RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/voxray-config.cmake.in
    ${PROJECT_BINARY_DIR}/voxray-config.cmake
    INSTALL_DESTINATION ${VOXRAY_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/voxray-config-version.cmake
    COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/voxray-config.cmake ${PROJECT_BINARY_DIR}/voxray-config-version.cmake
    DESTINATION ${VOXRAY_CMAKE_DIR})
