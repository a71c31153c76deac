# Structure registration and the portable kernels' build steps.
#
#   voxray_add_structure(<name> [TYPE <C++ type>...] [PASSES <file>...])
#
# registers the structure whose files are include/voxray/<name>/ (kernel.h, layout.h,
# <name>.hpp; TYPE defaults to voxray::<name>; several types share the one kernel, as the
# DAG's exact and colour-block attribute encodings do). One call per structure (top-level
# CMakeLists.txt) does everything a backend needs: it flattens the kernel into its own
# OpenCL C program and its own GLSL shaders (one per trace mode), compiles those to SPIR-V,
# checks the OpenCL C with clang where clang exists (a kernel error shows up without a
# device), and adds the structure to the type list the tool and the conformance tests
# iterate. PASSES (files under include/voxray/, e.g. world/frame/passes.h) adds the structure's
# frame passes: one more OpenCL entry (vx_pass_<name>) and SPIR-V module (<name>_passes),
# both calling vx_<name>_pass(blob, frame, pass, item).
# voxray_finish_structures() writes the tables that map names to programs.
# The CPU side needs no CMake: the host header includes kernels/kernel_tag.inc.

# The shared dialect every kernel builds on: the prelude, then the dialect's own list of
# its files (kernels/dialect.h, which the CPU lanes include too).
set(VOXRAY_KERNEL_COMMON kernels/prelude.h kernels/dialect.h)
set(VOXRAY_GENERATED ${PROJECT_BINARY_DIR}/generated)
file(MAKE_DIRECTORY ${VOXRAY_GENERATED}/voxray/generated ${VOXRAY_GENERATED}/voxray/shaders ${VOXRAY_GENERATED}/opencl ${VOXRAY_GENERATED}/vulkan)
find_program(VOXRAY_CLANG NAMES clang clang-16 clang-15 clang-14 DOC "clang, to check OpenCL C kernels at build time")

# voxray_flatten(OUTPUT <file> FILES <file>... [CPP_STRING <name>] [LINE_MARKERS])
# Writes FILES into OUTPUT at build time, resolving #include "voxray/..." once each; with
# LINE_MARKERS, #line directives so compiler errors name the original file and line;
# with CPP_STRING, as a C++ header holding the text in a constant of that name.
function(voxray_flatten)
    cmake_parse_arguments(arg "LINE_MARKERS" "OUTPUT;CPP_STRING" "FILES" ${ARGN})
    if(NOT TARGET voxray_flatten)
        add_executable(voxray_flatten ${PROJECT_SOURCE_DIR}/cmake/flatten.cpp)
        target_compile_features(voxray_flatten PRIVATE cxx_std_20)
        # A build step, not code under test: never sanitized (VOXRAY_SANITIZE).
        target_compile_options(voxray_flatten PRIVATE -fno-sanitize=all)
        target_link_options(voxray_flatten PRIVATE -fno-sanitize=all)
    endif()
    file(GLOB_RECURSE dialect_headers ${PROJECT_SOURCE_DIR}/include/voxray/*.h)
    set(options "")
    if(arg_CPP_STRING)
        list(APPEND options --cpp-string ${arg_CPP_STRING})
    endif()
    if(arg_LINE_MARKERS)
        list(APPEND options --line-markers)
    endif()
    add_custom_command(OUTPUT ${arg_OUTPUT}
        COMMAND voxray_flatten ${PROJECT_SOURCE_DIR}/include ${arg_OUTPUT} ${options} ${arg_FILES}
        DEPENDS voxray_flatten ${dialect_headers} ${arg_FILES}
        COMMENT "Flattening ${arg_OUTPUT}" VERBATIM)
endfunction()

# The absolute paths of the shared dialect followed by `extra` (paths under include/).
function(voxray_kernel_files out)
    set(files "")
    foreach(f ${VOXRAY_KERNEL_COMMON} ${ARGN})
        list(APPEND files ${PROJECT_SOURCE_DIR}/include/voxray/${f})
    endforeach()
    set(${out} ${files} PARENT_SCOPE)
endfunction()

# The includable sources for users' own shaders and kernels (installed as
# voxray/shaders/<name>.glsl and .cl): the dialect's head, the shared dialect, then FILES,
# without voxray's entry points and without #line markers. The shared dialect and FILES each
# sit inside an include guard, so that one shader or program may include several.
# voxray_shader_include(<name> <outputs variable> FILES <file>... [HEAD <folder>])
# HEAD: a folder of the heads (include_head.glsl, include_head.cl) other than the tracing
# kernels' (backends/vulkan/shaders/, backends/opencl/kernels/).
function(voxray_shader_include name out)
    cmake_parse_arguments(arg "" "HEAD" "FILES" ${ARGN})
    set(shaders ${VOXRAY_GENERATED}/voxray/shaders)
    set(backends_dir ${PROJECT_SOURCE_DIR}/backends)
    set(guards ${VOXRAY_GENERATED}/guards)
    string(TOUPPER ${name} upper)
    file(CONFIGURE OUTPUT ${guards}/dialect_begin.h CONTENT "#ifndef VOXRAY_SHADER_DIALECT\n#define VOXRAY_SHADER_DIALECT\n")
    file(CONFIGURE OUTPUT ${guards}/dialect_end.h CONTENT "#endif /* VOXRAY_SHADER_DIALECT */\n")
    file(CONFIGURE OUTPUT ${guards}/${name}_begin.h CONTENT "#ifndef VOXRAY_SHADER_${upper}\n#define VOXRAY_SHADER_${upper}\n")
    file(CONFIGURE OUTPUT ${guards}/${name}_end.h CONTENT "#endif /* VOXRAY_SHADER_${upper} */\n")
    voxray_kernel_files(dialect_files)
    set(guarded ${guards}/dialect_end.h ${guards}/${name}_begin.h ${arg_FILES} ${guards}/${name}_end.h)
    set(head_glsl ${backends_dir}/vulkan/shaders/include_head.glsl)
    set(head_cl ${backends_dir}/opencl/kernels/include_head.cl)
    if(arg_HEAD)
        set(head_glsl ${arg_HEAD}/include_head.glsl)
        set(head_cl ${arg_HEAD}/include_head.cl)
    endif()
    voxray_flatten(OUTPUT ${shaders}/${name}.glsl FILES ${head_glsl}
        ${guards}/dialect_begin.h ${backends_dir}/vulkan/shaders/dialect.glsl ${dialect_files} ${guarded})
    voxray_flatten(OUTPUT ${shaders}/${name}.cl FILES ${head_cl}
        ${guards}/dialect_begin.h ${backends_dir}/opencl/kernels/preamble.cl ${dialect_files} ${guarded})
    set(${out} ${shaders}/${name}.glsl ${shaders}/${name}.cl PARENT_SCOPE)
endfunction()

function(voxray_add_structure name)
    cmake_parse_arguments(arg "" "" "TYPE;PASSES" ${ARGN})
    if(NOT arg_TYPE)
        set(arg_TYPE "voxray::${name}")
    endif()
    set(dir ${PROJECT_SOURCE_DIR}/include/voxray/${name})
    foreach(f kernel.h layout.h ${name}.hpp)
        if(NOT EXISTS ${dir}/${f})
            message(FATAL_ERROR "voxray_add_structure(${name}): ${dir}/${f} is missing")
        endif()
    endforeach()
    set_property(GLOBAL APPEND PROPERTY VOXRAY_STRUCTURE_TYPES "${arg_TYPE}")
    voxray_add_kernel(${name} KERNEL ${name}/kernel.h HEADER voxray/${name}/${name}.hpp PASSES ${arg_PASSES})
endfunction()

# Scenes over one world kind (include/voxray/entities/): the world's kernel and the entity
# pass as one more kernel, scene_<world>, from entities/worlds/<world>.h and .hpp. Not a
# structure of the type list: a scene is built from a world and instances, not a model.
# TYPE: the world type the tests and the tool run scenes over (default voxray::<world>).
function(voxray_add_scene world)
    cmake_parse_arguments(arg "" "TYPE" "" ${ARGN})
    if(NOT arg_TYPE)
        set(arg_TYPE "voxray::${world}")
    endif()
    set_property(GLOBAL APPEND PROPERTY VOXRAY_SCENE_WORLD_TYPES "${arg_TYPE}")
    voxray_add_kernel(scene_${world} KERNEL entities/worlds/${world}.h HEADER voxray/entities/worlds/${world}.hpp STAGED)
endfunction()

# The stamp file of a check of the OpenCL C program `cl` with clang, in `out` (empty
# without clang): a kernel error shows up at build time, without a device.
function(voxray_opencl_check name cl out)
    set(${out} "" PARENT_SCOPE)
    if(VOXRAY_CLANG)
        set(stamp ${VOXRAY_GENERATED}/opencl/${name}.cl.checked)
        add_custom_command(OUTPUT ${stamp}
            COMMAND ${VOXRAY_CLANG} -x cl -cl-std=CL1.2 -Xclang -finclude-default-header -fsyntax-only
                    -Werror=implicit-function-declaration ${cl}
            COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
            DEPENDS ${cl}
            COMMENT "Checking the ${name} kernel as OpenCL C 1.2 (clang)" VERBATIM)
        set(${out} ${stamp} PARENT_SCOPE)
    endif()
endfunction()

# voxray_add_kernel(<name> KERNEL <file> HEADER <file> [PASSES <file>...] [STAGED]): the GPU
# programs of one kernel, vx_<name>_trace in KERNEL (under include/voxray/), whose host
# header HEADER (under include/) declares its tag (kernels/kernel_tag.inc) and compiles its
# CPU lanes. STAGED: the kernel also has vx_<name>_first and vx_<name>_then (its trace is
# then(first)), which OpenCL runs as two kernels (docs/design.md, "Staged kernels"); its
# program table says so (VOXRAY_KERNEL_STAGED_<name>).
function(voxray_add_kernel name)
    cmake_parse_arguments(arg "STAGED" "KERNEL;HEADER" "PASSES" ${ARGN})
    set_property(GLOBAL APPEND PROPERTY VOXRAY_STRUCTURES ${name})
    set_property(GLOBAL PROPERTY VOXRAY_KERNEL_HEADER_${name} ${arg_HEADER})
    set_property(GLOBAL PROPERTY VOXRAY_KERNEL_STAGED_${name} ${arg_STAGED})
    voxray_kernel_files(kernel_files ${arg_KERNEL})
    set(pass_files "")
    if(arg_STAGED)
        set(entry_lines "VX_OPENCL_STAGED_ENTRY(${name})\n")
    else()
        set(entry_lines "VX_OPENCL_ENTRY(${name})\n")
    endif()
    foreach(f ${arg_PASSES})
        list(APPEND pass_files ${PROJECT_SOURCE_DIR}/include/voxray/${f})
    endforeach()
    if(arg_PASSES)
        string(APPEND entry_lines "VX_OPENCL_PASS_ENTRY(${name})\n")
    endif()

    # OpenCL C: preamble, dialect, kernel (and passes), the entry macros and this kernel's entry lines.
    set(cl ${VOXRAY_GENERATED}/opencl/${name}.cl)
    set(entry ${VOXRAY_GENERATED}/opencl/${name}_entry.cl)
    file(CONFIGURE OUTPUT ${entry} CONTENT "${entry_lines}")
    set(cl_dir ${PROJECT_SOURCE_DIR}/backends/opencl/kernels)
    voxray_flatten(OUTPUT ${cl} LINE_MARKERS FILES ${cl_dir}/preamble.cl ${kernel_files} ${pass_files} ${cl_dir}/entry.cl ${entry})
    voxray_opencl_check(${name} ${cl} stamp)
    set(outputs ${cl} ${stamp})
    voxray_shader_include(${name} include_outputs FILES ${PROJECT_SOURCE_DIR}/include/voxray/${arg_KERNEL})
    list(APPEND outputs ${include_outputs})
    if(TARGET voxray_opencl)
        voxray_opencl_add_program(${name} ${cl})
    endif()
    if(TARGET voxray_vulkan)
        voxray_vulkan_add_program(${name} FILES ${kernel_files} PASSES ${pass_files})
    endif()
    if(NOT arg_STAGED)
        voxray_add_appearance_walk(${name} "${kernel_files}" walk_outputs)
        list(APPEND outputs ${walk_outputs})
    endif()
    add_custom_target(voxray_kernel_${name} ALL DEPENDS ${outputs})
endfunction()

# The compositing walk (appearance/walk.inc) over structure kernel `name`, whose dialect
# files are `kernel_files`: one more OpenCL program and SPIR-V module, <name>_appearance,
# with the entry vx_appearance_walk (backends/*/appearance_entry.*). The walk is written
# once; this file only instantiates it over the kernel's closest hit. `out`: the build
# outputs that must exist without a GPU backend (the OpenCL C and its clang check).
function(voxray_add_appearance_walk name kernel_files out)
    set_property(GLOBAL APPEND PROPERTY VOXRAY_APPEARANCE_KERNELS ${name})
    set(walk ${VOXRAY_GENERATED}/appearance/${name}_walk.h)
    file(CONFIGURE OUTPUT ${walk} CONTENT "/* Generated by voxray_add_appearance_walk (cmake/voxray_kernels.cmake): do not edit. */
#define VX_APP_WALK_NAME vx_app_walk
#define VX_APP_WALK_TRACE(b, r) vx_${name}_trace(b, r, VX_MODE_CLOSEST)
#include \"voxray/appearance/walk.inc\"
")
    set(files ${kernel_files})
    foreach(f ordinal.h record.h faithful_record.h walk_types.h walk_visit.h)
        list(APPEND files ${PROJECT_SOURCE_DIR}/include/voxray/appearance/${f})
    endforeach()
    list(APPEND files ${walk})
    set(cl_dir ${PROJECT_SOURCE_DIR}/backends/opencl/kernels)
    set(cl ${VOXRAY_GENERATED}/opencl/${name}_appearance.cl)
    voxray_flatten(OUTPUT ${cl} LINE_MARKERS FILES ${cl_dir}/preamble.cl ${files} ${cl_dir}/appearance_entry.cl)
    voxray_opencl_check(${name}_appearance ${cl} stamp)
    if(TARGET voxray_opencl)
        voxray_opencl_add_program(${name}_appearance ${cl})
    endif()
    if(TARGET voxray_vulkan)
        voxray_vulkan_add_walk(${name} "${files}")
    endif()
    set(${out} ${cl} ${stamp} PARENT_SCOPE)
endfunction()

# Writes the generated type list of every registered structure (voxray/generated/
# structures.hpp, for the tool and the tests) and lets each backend write its table.
function(voxray_finish_structures)
    get_property(names GLOBAL PROPERTY VOXRAY_STRUCTURES)
    get_property(types GLOBAL PROPERTY VOXRAY_STRUCTURE_TYPES)
    set(includes "")
    foreach(name ${names})
        get_property(header GLOBAL PROPERTY VOXRAY_KERNEL_HEADER_${name})
        string(APPEND includes "#include \"${header}\"\n")
    endforeach()
    string(REPLACE ";" ", " type_list "${types}")
    get_property(scene_worlds GLOBAL PROPERTY VOXRAY_SCENE_WORLD_TYPES)
    string(REPLACE ";" ", " scene_world_list "${scene_worlds}")
    file(CONFIGURE OUTPUT ${VOXRAY_GENERATED}/voxray/generated/structures.hpp CONTENT
"// Generated from the voxray_add_structure calls (cmake/voxray_kernels.cmake): do not edit.
#pragma once
#include \"voxray/core/type_list.hpp\"
@includes@
namespace voxray::registered {

using structures = type_list<@type_list@>;
// The world kinds scene<World> (voxray/entities/) has a kernel for (voxray_add_scene).
using scene_worlds = type_list<@scene_world_list@>;

}  // namespace voxray::registered
" @ONLY)
    if(COMMAND voxray_cpu_finish)
        voxray_cpu_finish(${names})
    endif()
    if(COMMAND voxray_opencl_finish)
        voxray_opencl_finish(${names})
    endif()
    if(COMMAND voxray_vulkan_finish)
        voxray_vulkan_finish(${names})
    endif()
endfunction()
