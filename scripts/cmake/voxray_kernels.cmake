# The portable kernel sources, in dependency order, and a build-time step that flattens
# them (resolving #include "voxray/...") into one translation unit for OpenCL C or GLSL.
# Add a new structure's layout and kernel files here, and its name to VOXRAY_KERNEL_NAMES.
set(VOXRAY_KERNEL_SOURCES
    kernels/prelude.h
    layout/dense_grid_layout.h
    kernels/ray.h
    kernels/dda.h
    kernels/dense_grid.h
    layout/brickmap_layout.h
    kernels/brickmap.h)
set(VOXRAY_KERNEL_NAMES dense_grid brickmap)

# voxray_flatten(OUTPUT <file> [CPP_STRING <name>] PREAMBLE <file> EPILOGUE <file>)
# Writes PREAMBLE, the kernel sources and EPILOGUE into OUTPUT at build time; with
# CPP_STRING, as a C++ header holding the text in a constant of that name.
function(voxray_flatten)
    cmake_parse_arguments(arg "" "OUTPUT;PREAMBLE;EPILOGUE;CPP_STRING" "" ${ARGN})
    if(NOT TARGET voxray_flatten)
        add_executable(voxray_flatten ${PROJECT_SOURCE_DIR}/scripts/kernel_tools/flatten.cpp)
        target_compile_features(voxray_flatten PRIVATE cxx_std_20)
    endif()
    set(sources "")
    foreach(s ${VOXRAY_KERNEL_SOURCES})
        list(APPEND sources ${PROJECT_SOURCE_DIR}/include/voxray/${s})
    endforeach()
    file(GLOB kernel_headers ${PROJECT_SOURCE_DIR}/include/voxray/kernels/*.h
                             ${PROJECT_SOURCE_DIR}/include/voxray/layout/*.h)
    set(cpp_args "")
    if(arg_CPP_STRING)
        set(cpp_args --cpp-string ${arg_CPP_STRING})
    endif()
    add_custom_command(OUTPUT ${arg_OUTPUT}
        COMMAND voxray_flatten ${PROJECT_SOURCE_DIR}/include ${arg_OUTPUT} ${cpp_args}
                ${arg_PREAMBLE} ${sources} ${arg_EPILOGUE}
        DEPENDS voxray_flatten ${kernel_headers} ${arg_PREAMBLE} ${arg_EPILOGUE}
        COMMENT "Flattening voxray kernels into ${arg_OUTPUT}" VERBATIM)
endfunction()
