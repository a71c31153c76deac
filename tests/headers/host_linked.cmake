# cmake -DNM=<nm> -DOBJECT=<host_linked_program.o> -P host_linked.cmake
# The object of a program that links voxray::kernels must call the host code and the
# SIMD streams (undefined symbols: the library's) and define none of them itself.
set(called
    "voxray::io::load_vox\\("
    "voxray::naadf::naadf\\("
    "voxray::naadf::apply_batch\\("
    "voxray::naadf::refine\\("
    "voxray::vulkan_detail::shared_context\\("
    "voxray::vulkan_detail::command_stream::submit_and_wait\\("
    "voxray::opencl_detail::acquire_device_context\\("
    "voxray::opencl_detail::committer::commit\\("
    "voxray::kernels::simd16::trace_stream<")
set(compiled_here_too
    "voxray::io::"
    "voxray::naadf::(naadf\\(|apply_batch|refine|commit|rebuild|settle_pages)"
    "voxray::naadf_detail::build"
    "voxray::vulkan_detail::(choose_device|inspect|shared_context|instance::create|context::|buffer::create|command_stream::|committer::commit|compute_pipeline::create)"
    "voxray::opencl_detail::(select_device|check_user_context|acquire_device_context|cl_status_name)\\("
    "voxray::opencl_detail::(device_context::(device_context|build|build_log|read_device)|committer::(commit|create_kernel)|pass_runner::(run|read|write))\\("
    "voxray::kernels::simd(8|16)::")
execute_process(COMMAND ${NM} -C --undefined-only ${OBJECT} OUTPUT_VARIABLE undefined RESULT_VARIABLE r1)
execute_process(COMMAND ${NM} -C --defined-only ${OBJECT} OUTPUT_VARIABLE defined RESULT_VARIABLE r2)
if(NOT r1 EQUAL 0 OR NOT r2 EQUAL 0)
    message(FATAL_ERROR "${NM} could not read ${OBJECT}")
endif()
set(failures "")
foreach(symbol ${called})
    if(NOT undefined MATCHES "${symbol}")
        string(APPEND failures "\n  not called from the library: ${symbol}")
    endif()
endforeach()
string(REPLACE "\n" ";" defined_lines "${defined}")
foreach(line ${defined_lines})
    foreach(pattern ${compiled_here_too})
        if(line MATCHES "[TtWw] .*${pattern}")
            string(APPEND failures "\n  compiled in the program although voxray::kernels holds it: ${line}")
            break()
        endif()
    endforeach()
endforeach()
if(failures)
    message(FATAL_ERROR "host_linked_program.o:${failures}")
endif()
message(STATUS "host code and SIMD streams: called, none compiled in the program")
