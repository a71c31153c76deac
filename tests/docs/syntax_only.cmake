# Compiler launcher of the docs_blocks target (tests/docs/CMakeLists.txt):
#
#   cmake -P syntax_only.cmake -- <compiler> <arguments...>
#
# runs the compile command with -fsyntax-only (the documents' blocks are checked, never
# run), then creates the empty object file the build expects, so that an unchanged block
# is not compiled again at the next build.
set(command "")
set(object "")
set(started FALSE)
set(next_is_object FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
    set(arg "${CMAKE_ARGV${i}}")
    if(NOT started)
        if(arg STREQUAL "--")
            set(started TRUE)
        endif()
        continue()
    endif()
    if(next_is_object)
        set(object "${arg}")
        set(next_is_object FALSE)
    elseif(arg STREQUAL "-o")
        set(next_is_object TRUE)
    endif()
    list(APPEND command "${arg}")
endforeach()
if(NOT command)
    message(FATAL_ERROR "usage: cmake -P syntax_only.cmake -- <compiler> <arguments...>")
endif()
execute_process(COMMAND ${command} -fsyntax-only RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "a code block of the documents does not compile (see above)")
endif()
if(object)
    file(TOUCH "${object}")
endif()
