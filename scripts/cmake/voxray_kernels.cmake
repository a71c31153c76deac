# The portable kernel sources, in dependency order, and a build-time step that flattens
# them (resolving #include "voxray/...") into one translation unit for OpenCL C or GLSL.
# Add a new structure's layout and kernel files here, and its name to VOXRAY_KERNEL_NAMES.
set(VOXRAY_KERNEL_SOURCES
    kernels/prelude.h
    layout/dense_grid_layout.h
    kernels/ray.h
    kernels/dda.h
    kernels/dense_grid.h)
set(VOXRAY_KERNEL_NAMES dense_grid)

set(VOXRAY_FLATTEN_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/voxray_flatten.cmake)

# voxray_flatten(OUTPUT <file> PREAMBLE <file> EPILOGUE <file>)
# Writes PREAMBLE, the kernel sources and EPILOGUE into OUTPUT at build time.
function(voxray_flatten)
    cmake_parse_arguments(arg "" "OUTPUT;PREAMBLE;EPILOGUE" "" ${ARGN})
    set(sources "")
    foreach(s ${VOXRAY_KERNEL_SOURCES})
        list(APPEND sources ${PROJECT_SOURCE_DIR}/include/voxray/${s})
    endforeach()
    file(GLOB all_kernel_headers ${PROJECT_SOURCE_DIR}/include/voxray/kernels/*.h
                                 ${PROJECT_SOURCE_DIR}/include/voxray/layout/*.h)
    string(REPLACE ";" "|" files_arg "${arg_PREAMBLE};${sources};${arg_EPILOGUE}")
    add_custom_command(OUTPUT ${arg_OUTPUT}
        COMMAND ${CMAKE_COMMAND} -DINCLUDE_DIR=${PROJECT_SOURCE_DIR}/include "-DFILES=${files_arg}"
                -DOUTPUT=${arg_OUTPUT} -P ${VOXRAY_FLATTEN_SCRIPT}
        DEPENDS ${all_kernel_headers} ${arg_PREAMBLE} ${arg_EPILOGUE} ${VOXRAY_FLATTEN_SCRIPT}
        COMMENT "Flattening voxray kernels into ${arg_OUTPUT}" VERBATIM)
endfunction()
