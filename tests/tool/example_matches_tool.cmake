# cmake -DEXAMPLE=... -DTOOL=... -DSCENE=x.vox -DOUT=dir -P example_matches_tool.cmake
# Runs examples/render_vox.cpp on a real scene and `voxray render` with the same structure,
# backend and size: the example must succeed, and the two PNGs must be the same bytes
# (both shade with the public helpers of voxray/rays.hpp, so they cannot drift apart).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
foreach(cmd "${EXAMPLE};${SCENE};${OUT}/example.png;320;180"
            "${TOOL};render;${SCENE};--structure;brickmap;--backend;cpu;--width;320;--height;180;--out;${OUT}/tool.png")
    execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}\n${err}")
    endif()
    message(STATUS "${out}")
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/example.png ${OUT}/tool.png RESULT_VARIABLE differ)
if(differ)
    message(FATAL_ERROR "the example's image differs from `voxray render`'s (${OUT})")
endif()
