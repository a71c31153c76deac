# voxray::opencl — the portable kernels as OpenCL C 1.2, built at run time from source
# embedded in a generated header (PoCL cannot ingest SPIR-V, so source is the portable
# choice). Users need only an OpenCL ICD and a driver; no kernel compiler at build time.
find_package(OpenCL 1.2 QUIET)
if(OpenCL_FOUND)
    add_library(voxray_opencl INTERFACE)
    add_library(voxray::opencl ALIAS voxray_opencl)
    set_target_properties(voxray_opencl PROPERTIES EXPORT_NAME opencl)

    # The kernel files flattened into one OpenCL program, as a C++ string constant.
    set(voxray_opencl_generated ${PROJECT_BINARY_DIR}/generated/voxray/generated/opencl_kernels.hpp)
    voxray_flatten(OUTPUT ${voxray_opencl_generated}
        CPP_STRING voxray_opencl_kernel_source
        PREAMBLE ${CMAKE_CURRENT_LIST_DIR}/kernels/preamble.cl
        EPILOGUE ${CMAKE_CURRENT_LIST_DIR}/kernels/entry.cl)
    # ALL: the header must exist before `cmake --install`, even if no test was built.
    add_custom_target(voxray_opencl_kernels ALL DEPENDS ${voxray_opencl_generated})
    # Interface libraries pass their dependencies on to whoever links them.
    add_dependencies(voxray_opencl voxray_opencl_kernels)

    target_include_directories(voxray_opencl INTERFACE
        $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
        $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(voxray_opencl INTERFACE voxray::voxray OpenCL::OpenCL)
    # The host code uses the 1.2 API only (clCreateCommandQueue, no SVM): say so, which
    # also silences the headers' "defaulting to 3.0" message and 2.0 deprecations.
    target_compile_definitions(voxray_opencl INTERFACE CL_TARGET_OPENCL_VERSION=120)

    install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    install(FILES ${voxray_opencl_generated} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxray/generated)
    voxray_backend_added(opencl voxray_opencl)
else()
    voxray_backend_missing(opencl
        "find_package(OpenCL 1.2) failed (Debian: ocl-icd-opencl-dev opencl-headers, plus a driver such as pocl-opencl-icd)")
endif()
