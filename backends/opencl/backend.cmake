# voxray::opencl — the portable kernels as OpenCL C 1.2, built at run time from source
# embedded in generated headers (PoCL cannot ingest SPIR-V, so source is the portable
# choice). Users need only an OpenCL ICD and a driver; no kernel compiler at build time.
# Each structure is its own program (voxray_add_structure calls voxray_opencl_add_program),
# so a kernel that fails to build on a device breaks that structure only.
find_package(OpenCL 1.2 QUIET)
if(NOT OpenCL_FOUND)
    voxray_backend_missing(opencl
        "find_package(OpenCL 1.2) failed (Debian: ocl-icd-opencl-dev opencl-headers, plus a driver such as pocl-opencl-icd)")
    return()
endif()

add_library(voxray_opencl INTERFACE)
add_library(voxray::opencl ALIAS voxray_opencl)
set_target_properties(voxray_opencl PROPERTIES EXPORT_NAME opencl)
target_include_directories(voxray_opencl ${VOXRAY_SYSTEM} INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(voxray_opencl INTERFACE voxray::voxray OpenCL::OpenCL)
# The host code uses the 1.2 API only (clCreateCommandQueue, no SVM): say so, which
# also silences the headers' "defaulting to 3.0" message and 2.0 deprecations.
# VOXRAY_LINKED_OPENCL (voxray_tracer_backend, below): voxray/opencl.hpp refuses to compile without it.
target_compile_definitions(voxray_opencl INTERFACE CL_TARGET_OPENCL_VERSION=120)
if(VOXRAY_INSTALL)
    install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
set_property(GLOBAL PROPERTY VOXRAY_OPENCL_HEADERS "")

# One embedded program: the flattened source `cl` as voxray/generated/opencl_<name>.hpp.
function(voxray_opencl_embed name cl)
    set(header ${VOXRAY_GENERATED}/voxray/generated/opencl_${name}.hpp)
    voxray_flatten(OUTPUT ${header} CPP_STRING voxray_opencl_${name} FILES ${cl})
    set_property(GLOBAL APPEND PROPERTY VOXRAY_OPENCL_HEADERS ${header})
endfunction()

function(voxray_opencl_add_program name cl)
    voxray_opencl_embed(${name} ${cl})
endfunction()

# The commit program (incremental updates) and the table of every program by name.
function(voxray_opencl_finish)
    set(dir ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/kernels)
    set(commit_cl ${VOXRAY_GENERATED}/opencl/commit.cl)
    voxray_flatten(OUTPUT ${commit_cl} LINE_MARKERS FILES ${dir}/preamble.cl
        ${PROJECT_SOURCE_DIR}/include/voxray/kernels/prelude.h ${PROJECT_SOURCE_DIR}/include/voxray/sync/commit.h
        ${dir}/commit.cl)
    voxray_opencl_embed(commit ${commit_cl})
    # The mesher kernel (meshing/kernel.h, voxray/opencl/chunk_mesher.hpp): passes only.
    set(mesher_cl ${VOXRAY_GENERATED}/opencl/mesher.cl)
    set(mesher_entry ${VOXRAY_GENERATED}/opencl/mesher_entry.cl)
    file(CONFIGURE OUTPUT ${mesher_entry} CONTENT "VX_OPENCL_PASS_ENTRY(mesher)\n")
    voxray_kernel_files(mesher_files meshing/kernel.h)
    voxray_flatten(OUTPUT ${mesher_cl} LINE_MARKERS FILES ${dir}/preamble.cl ${mesher_files} ${dir}/entry.cl ${mesher_entry})
    voxray_opencl_embed(mesher ${mesher_cl})
    voxray_opencl_check(mesher ${mesher_cl} mesher_checked)
    set(includes "")
    set(rows "")
    set(walk_rows "")
    get_property(with_walk GLOBAL PROPERTY VOXRAY_APPEARANCE_KERNELS)
    foreach(name ${with_walk})
        string(APPEND includes "#include \"voxray/generated/opencl_${name}_appearance.hpp\"\n")
        string(APPEND walk_rows "    {\"${name}_appearance\", voxray_opencl_${name}_appearance},\n")
    endforeach()
    foreach(name ${ARGN})
        string(APPEND includes "#include \"voxray/generated/opencl_${name}.hpp\"\n")
        get_property(staged GLOBAL PROPERTY VOXRAY_KERNEL_STAGED_${name})
        if(staged)
            string(APPEND rows "    {\"${name}\", voxray_opencl_${name}, true},\n")
        else()
            string(APPEND rows "    {\"${name}\", voxray_opencl_${name}},\n")
        endif()
    endforeach()
    file(CONFIGURE OUTPUT ${VOXRAY_GENERATED}/voxray/generated/opencl_programs.hpp CONTENT
"// Generated from the voxray_add_structure calls (backends/opencl/backend.cmake): do not edit.
#pragma once
#include \"voxray/generated/opencl_commit.hpp\"
#include \"voxray/generated/opencl_mesher.hpp\"
@includes@#include \"voxray/opencl/program_source.hpp\"

namespace voxray::opencl_detail {

inline constexpr program_source registered_programs[] = {
@rows@};
// The compositing walk over each structure (voxray_add_appearance_walk), as <name>_appearance.
inline constexpr program_source appearance_programs[] = {
@walk_rows@};
inline constexpr program_source commit_program{\"commit\", voxray_opencl_commit};
inline constexpr program_source mesher_program{\"mesher\", voxray_opencl_mesher};

}  // namespace voxray::opencl_detail
" @ONLY)
    get_property(headers GLOBAL PROPERTY VOXRAY_OPENCL_HEADERS)
    # ALL: the headers must exist before `cmake --install`, even if no test was built.
    add_custom_target(voxray_opencl_programs ALL DEPENDS ${headers} ${mesher_checked})
    # Interface libraries pass their dependencies on to whoever links them.
    add_dependencies(voxray_opencl voxray_opencl_programs)
    if(VOXRAY_INSTALL)
        install(FILES ${headers} ${VOXRAY_GENERATED}/voxray/generated/opencl_programs.hpp
                DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxray/generated)
    endif()
endfunction()

voxray_tracer_backend(opencl voxray_opencl HEADER voxray/opencl.hpp TYPES voxray::opencl)
