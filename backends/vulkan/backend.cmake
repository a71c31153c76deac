# voxray::vulkan — the portable kernels as GLSL compute shaders, compiled to SPIR-V at build
# time and embedded in generated headers, so users need no shader compiler at run time.
# Structure data, rays and hits are reached by buffer device address (Vulkan 1.2).
find_package(Vulkan 1.2 COMPONENTS glslangValidator)
# Vulkan_FOUND is false when either part is missing: say which one.
if(NOT Vulkan_FOUND OR NOT TARGET Vulkan::Vulkan OR NOT TARGET Vulkan::glslangValidator)
    if(NOT Vulkan_LIBRARY OR NOT Vulkan_INCLUDE_DIR)
        voxray_backend_missing(vulkan "Vulkan headers and loader not found (Debian: libvulkan-dev)")
    elseif(NOT Vulkan_GLSLANG_VALIDATOR_EXECUTABLE)
        voxray_backend_missing(vulkan "glslangValidator not found (Debian: glslang-tools)")
    else()
        voxray_backend_missing(vulkan "Vulkan headers ${Vulkan_VERSION} are older than 1.2")
    endif()
    return()
endif()
find_program(VOXRAY_SPIRV_VAL spirv-val)

set_property(GLOBAL PROPERTY VOXRAY_VULKAN_HEADERS "")

# glslang, spirv-val (when present) and the header that embeds the SPIR-V words. An
# optional fourth argument names the shader stage (comp when absent).
function(voxray_vulkan_compile comp name defines)
    set(stage comp)
    if(ARGC GREATER 3)
        set(stage ${ARGV3})
    endif()
    set(dir ${CMAKE_CURRENT_FUNCTION_LIST_DIR})
    set(spv ${VOXRAY_GENERATED}/vulkan/${name}.spv)
    set(header ${VOXRAY_GENERATED}/voxray/generated/spirv_${name}.hpp)
    set(validate "")
    if(VOXRAY_SPIRV_VAL)
        set(validate COMMAND ${VOXRAY_SPIRV_VAL} --target-env vulkan1.2 ${spv})
    endif()
    add_custom_command(OUTPUT ${header}
        COMMAND ${Vulkan_GLSLANG_VALIDATOR_EXECUTABLE} -V --target-env vulkan1.2 -S ${stage} ${defines} -o ${spv} ${comp}
        ${validate}
        COMMAND ${CMAKE_COMMAND} -DSPIRV=${spv} -DHEADER=${header} -DNAME=voxray_spirv_${name}
                -P ${dir}/cmake/spirv_header.cmake
        DEPENDS ${comp} ${dir}/cmake/spirv_header.cmake
        COMMENT "Compiling ${name} to SPIR-V"
        VERBATIM)
    set_property(GLOBAL APPEND PROPERTY VOXRAY_VULKAN_HEADERS ${header})
endfunction()

# One shader source per structure (preamble, dialect, kernel, the shared entry point),
# compiled once: the trace mode is a specialization constant (shaders/entry.glsl). PASSES: one more
# module, <name>_passes, with the frame passes (and 64-bit atomics, shaders/dialect.glsl).
function(voxray_vulkan_add_program name)
    cmake_parse_arguments(arg "" "" "FILES;PASSES" ${ARGN})
    set(dir ${CMAKE_CURRENT_FUNCTION_LIST_DIR})
    set(comp ${VOXRAY_GENERATED}/vulkan/${name}.comp)
    voxray_flatten(OUTPUT ${comp} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl ${arg_FILES}
        ${dir}/shaders/entry.glsl)
    voxray_vulkan_compile(${comp} ${name}_trace "-DVX_TRACE=vx_${name}_trace")
    if(arg_PASSES)
        set(passes ${VOXRAY_GENERATED}/vulkan/${name}_passes.comp)
        voxray_flatten(OUTPUT ${passes} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl
            ${arg_FILES} ${arg_PASSES} ${dir}/shaders/pass_entry.glsl)
        voxray_vulkan_compile(${passes} ${name}_passes "-DVX_INT64_ATOMICS=1;-DVX_PASS=vx_${name}_pass")
        set_property(GLOBAL APPEND PROPERTY VOXRAY_VULKAN_PASSES ${name})
    endif()
endfunction()

# The compositing walk over structure `name` (voxray_add_appearance_walk): one module,
# <name>_appearance, from the dialect `files` and shaders/appearance_entry.glsl.
function(voxray_vulkan_add_walk name files)
    set(dir ${CMAKE_CURRENT_FUNCTION_LIST_DIR})
    set(comp ${VOXRAY_GENERATED}/vulkan/${name}_appearance.comp)
    voxray_flatten(OUTPUT ${comp} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl ${files}
        ${dir}/shaders/appearance_entry.glsl)
    voxray_vulkan_compile(${comp} ${name}_appearance "")
endfunction()

# The commit shader and the table of every module by name.
function(voxray_vulkan_finish)
    set(dir ${CMAKE_CURRENT_FUNCTION_LIST_DIR})
    set(comp ${VOXRAY_GENERATED}/vulkan/commit.comp)
    voxray_flatten(OUTPUT ${comp} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl
        ${PROJECT_SOURCE_DIR}/include/voxray/kernels/prelude.h ${PROJECT_SOURCE_DIR}/include/voxray/sync/commit.h
        ${dir}/shaders/commit.glsl)
    voxray_vulkan_compile(${comp} commit "")
    # The mesher kernel (meshing/kernel.h, voxray/vulkan/chunk_mesher.hpp): passes only.
    voxray_kernel_files(mesher_files meshing/kernel.h)
    set(mesher ${VOXRAY_GENERATED}/vulkan/mesher_passes.comp)
    voxray_flatten(OUTPUT ${mesher} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl
        ${mesher_files} ${dir}/shaders/pass_entry.glsl)
    voxray_vulkan_compile(${mesher} mesher_passes "-DVX_PASS=vx_mesher_pass")
    # The raster paths (voxray/vulkan/chunk_raster.hpp, triangle_raster.hpp): a vertex and a
    # fragment shader each, over the dialect, the vertex side of meshing/pop.h and the
    # frame's push constants (shaders/raster_frame.glsl).
    voxray_kernel_files(dialect_files meshing/pop.h)
    foreach(program chunk_raster triangle_raster)
        foreach(stage vert frag)
            set(source ${VOXRAY_GENERATED}/vulkan/${program}_${stage}.glsl)
            voxray_flatten(OUTPUT ${source} LINE_MARKERS FILES ${dir}/shaders/preamble.glsl ${dir}/shaders/dialect.glsl
                ${dialect_files} ${dir}/shaders/raster_frame.glsl ${dir}/shaders/${program}_${stage}.glsl)
            voxray_vulkan_compile(${source} ${program}_${stage} "" ${stage})
        endforeach()
    endforeach()
    set(includes "")
    set(rows "")
    get_property(with_passes GLOBAL PROPERTY VOXRAY_VULKAN_PASSES)
    get_property(with_walk GLOBAL PROPERTY VOXRAY_APPEARANCE_KERNELS)
    foreach(name ${ARGN})
        string(APPEND includes "#include \"voxray/generated/spirv_${name}_trace.hpp\"\n")
        set(passes "{}")
        if(name IN_LIST with_passes)
            string(APPEND includes "#include \"voxray/generated/spirv_${name}_passes.hpp\"\n")
            set(passes "voxray_spirv_${name}_passes")
        endif()
        set(walk "{}")
        if(name IN_LIST with_walk)
            string(APPEND includes "#include \"voxray/generated/spirv_${name}_appearance.hpp\"\n")
            set(walk "voxray_spirv_${name}_appearance")
        endif()
        string(APPEND rows "    {\"${name}\", voxray_spirv_${name}_trace, ${passes}, ${walk}},\n")
    endforeach()
    file(CONFIGURE OUTPUT ${VOXRAY_GENERATED}/voxray/generated/vulkan_modules.hpp CONTENT
"// Generated from the voxray_add_structure calls (backends/vulkan/backend.cmake): do not edit.
#pragma once
@includes@#include \"voxray/vulkan/spirv_module.hpp\"

namespace voxray::vulkan_detail {

inline constexpr spirv_modules registered_modules[] = {
@rows@};

}  // namespace voxray::vulkan_detail
" @ONLY)
    get_property(headers GLOBAL PROPERTY VOXRAY_VULKAN_HEADERS)
    add_custom_target(voxray_vulkan_shaders ALL DEPENDS ${headers})
    add_dependencies(voxray_vulkan voxray_vulkan_shaders)
    if(VOXRAY_INSTALL)
        install(FILES ${headers} ${VOXRAY_GENERATED}/voxray/generated/vulkan_modules.hpp
                DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxray/generated)
    endif()
endfunction()

add_library(voxray_vulkan INTERFACE)
add_library(voxray::vulkan ALIAS voxray_vulkan)
set_target_properties(voxray_vulkan PROPERTIES EXPORT_NAME vulkan)
target_include_directories(voxray_vulkan ${VOXRAY_SYSTEM} INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
    $<BUILD_INTERFACE:${VOXRAY_GENERATED}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(voxray_vulkan INTERFACE voxray::voxray Vulkan::Vulkan)
# VOXRAY_LINKED_VULKAN (voxray_tracer_backend, below): voxray/vulkan.hpp refuses to compile
# without it, so a program that includes the header but does not link voxray::vulkan
# fails with one clear message, not dozens of undefined symbols.

if(VOXRAY_INSTALL)
    install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
voxray_tracer_backend(vulkan voxray_vulkan HEADER voxray/vulkan.hpp TYPES voxray::vulkan)
