# Extracts the C++ code blocks of a markdown file into one .cpp file each, so that the
# build compiles them (tests/docs/CMakeLists.txt) and the documents cannot drift from the
# API. The rules (docs/style.md, "Code blocks in the documents"):
#
#   ```cpp            compiled. A block that contains `int main(` is a whole program and
#                     is compiled as it stands. Any other block is a fragment: its
#                     #include lines go to the top of the file, after tests/docs/preamble.hpp
#                     (which declares the few inputs fragments may use: model, rays, hits,
#                     and the GPU handles of the interop examples), and the rest becomes the
#                     body of a function.
#   ```cpp nocompile  not compiled (a signature, pseudo-code): listed at configure time.
#   ```c++, ```cpp <anything else>: an error in the generated file, so the build names it.
#
# Blocks whose code (comments left out) names `vulkan` or `opencl` (or MPI: `MPI_`,
# `voxray/mpi/`; glTF: `voxray/gltf/`) are compiled only when that backend (component) is built. `#line` directives point compiler messages at the document's lines.
#
#   voxray_docs_extract(DOC <path under the repository> ROOT <repository> OUT <folder>
#                       PREFIX <file name prefix> VULKAN <bool> OPENCL <bool> MPI <bool>
#                       SOURCES <variable> REPORT <variable>)
# sets SOURCES to the files written and REPORT to a line per block not compiled.

# Writes `content` to `path` only if it differs, so unchanged blocks are not compiled again.
# Takes the first line of the text in variable `text_var` (the text must end in a newline)
# into `line_var`, and leaves the rest in `text_var`.
macro(_voxray_docs_pop_line text_var line_var)
    string(FIND "${${text_var}}" "\n" _voxray_newline)
    string(SUBSTRING "${${text_var}}" 0 ${_voxray_newline} ${line_var})
    math(EXPR _voxray_newline "${_voxray_newline} + 1")
    string(SUBSTRING "${${text_var}}" ${_voxray_newline} -1 ${text_var})
endmacro()

function(voxray_docs_write path content)
    if(EXISTS "${path}")
        file(READ "${path}" old)
        if(old STREQUAL content)
            return()
        endif()
    endif()
    file(WRITE "${path}" "${content}")
endfunction()

function(voxray_docs_extract)
    cmake_parse_arguments(arg "" "DOC;ROOT;OUT;PREFIX;VULKAN;OPENCL;MPI;GLTF;SOURCES;REPORT" "" ${ARGN})
    file(READ "${arg_ROOT}/${arg_DOC}" text)
    string(APPEND text "\n")
    file(MAKE_DIRECTORY "${arg_OUT}")
    set(sources "")
    set(report "")
    set(number 0)      # line number of `line`
    set(index 0)       # C++ blocks seen
    set(in_block FALSE)
    while(NOT text STREQUAL "")
        _voxray_docs_pop_line(text line)
        math(EXPR number "${number} + 1")
        if(NOT in_block)
            if(line MATCHES "^( *)(```+|~~~+)[ ]*([^ `]*)[ ]*(.*)$")
                set(in_block TRUE)
                string(LENGTH "${CMAKE_MATCH_1}" indent)
                set(fence "${CMAKE_MATCH_2}")
                set(language "${CMAKE_MATCH_3}")
                string(STRIP "${CMAKE_MATCH_4}" attributes)
                set(start ${number})
                set(body "")
                set(body_lines "")
            endif()
            continue()
        endif()
        # Inside a block: a closing fence has the same character, at least as long.
        if(line MATCHES "^ *(```+|~~~+) *$")
            string(SUBSTRING "${CMAKE_MATCH_1}" 0 1 close_char)
            string(SUBSTRING "${fence}" 0 1 open_char)
            string(LENGTH "${CMAKE_MATCH_1}" close_length)
            string(LENGTH "${fence}" open_length)
            if(close_char STREQUAL open_char AND NOT close_length LESS open_length)
                set(in_block FALSE)
                _voxray_docs_block()
                continue()
            endif()
        endif()
        # The block's own indentation (a block inside a list item) is not code.
        if(indent GREATER 0)
            string(REPEAT " " ${indent} pad)
            string(FIND "${line}" "${pad}" at_pad)
            if(at_pad EQUAL 0)
                string(SUBSTRING "${line}" ${indent} -1 line)
            endif()
        endif()
        string(APPEND body "${line}\n")
    endwhile()
    if(in_block)
        message(FATAL_ERROR "${arg_DOC}:${start}: a code block is never closed")
    endif()
    # Files of blocks that are gone.
    file(GLOB old "${arg_OUT}/${arg_PREFIX}_*.cpp")
    foreach(f ${old})
        list(FIND sources "${f}" kept)
        if(kept EQUAL -1)
            file(REMOVE "${f}")
        endif()
    endforeach()
    set(${arg_SOURCES} ${sources} PARENT_SCOPE)
    set(${arg_REPORT} ${report} PARENT_SCOPE)
endfunction()

# One finished block (variables of voxray_docs_extract): writes its file, or says why not.
macro(_voxray_docs_block)
    set(where "${arg_DOC}:${start}")
    string(TOLOWER "${language}" lower)
    set(cxx FALSE)
    set(error "")
    if(lower STREQUAL "cpp" AND attributes STREQUAL "")
        set(cxx TRUE)
    elseif(lower STREQUAL "cpp" AND attributes STREQUAL "nocompile")
        list(APPEND report "${where}: marked nocompile")
    elseif(lower MATCHES "^(cpp|c\\+\\+|cxx|cc|hpp)$")
        string(STRIP "${language} ${attributes}" info)
        set(error "${where}: unknown code block info string '${info}': use ```cpp (compiled) or ```cpp nocompile")
    endif()
    if(cxx OR error)
        math(EXPR index "${index} + 1")
        # Which backends the code itself names (comments left out).
        string(REGEX REPLACE "//[^\n]*" "" code "${body}")
        set(needs "")
        if(code MATCHES "vulkan" AND NOT arg_VULKAN)
            set(needs "voxray::vulkan")
        elseif(code MATCHES "opencl" AND NOT arg_OPENCL)
            set(needs "voxray::opencl")
        elseif(code MATCHES "MPI_|voxray/mpi/" AND NOT arg_MPI)
            set(needs "voxray::mpi")
        elseif(code MATCHES "voxray/gltf/" AND NOT arg_GLTF)
            set(needs "voxray::gltf")
        endif()
        string(LENGTH "${index}" digits)
        set(name "${index}")
        if(digits EQUAL 1)
            set(name "0${index}")
        endif()
        set(path "${arg_OUT}/${arg_PREFIX}_${name}.cpp")
        set(head "// Generated from ${where} by tests/docs/extract_blocks.cmake: do not edit.\n")
        if(error)
            voxray_docs_write("${path}" "${head}#error \"${error}\"\n")
            list(APPEND sources "${path}")
        elseif(needs)
            list(APPEND report "${where}: needs ${needs}, which this build lacks: not compiled")
        elseif(body MATCHES "int main\\(")
            math(EXPR first "${start} + 1")
            voxray_docs_write("${path}" "${head}#line ${first} \"${arg_DOC}\"\n${body}")
            list(APPEND sources "${path}")
        else()
            _voxray_docs_fragment()
            voxray_docs_write("${path}" "${head}#include \"preamble.hpp\"\n${includes}\nvoid docs_block_${arg_PREFIX}_${name}() {\n${code_out}}\n")
            list(APPEND sources "${path}")
        endif()
    endif()
endmacro()

# A fragment: its #include lines (each with its #line) in `includes`, the rest, with a
# #line wherever lines were taken out, in `code_out`.
macro(_voxray_docs_fragment)
    set(includes "")
    set(code_out "")
    set(rest "${body}")
    set(at ${start})
    set(need_line TRUE)
    while(NOT rest STREQUAL "")
        _voxray_docs_pop_line(rest piece)
        math(EXPR at "${at} + 1")
        if(piece MATCHES "^[ ]*#[ ]*include")
            string(APPEND includes "#line ${at} \"${arg_DOC}\"\n${piece}\n")
            set(need_line TRUE)
        else()
            if(need_line)
                string(APPEND code_out "#line ${at} \"${arg_DOC}\"\n")
                set(need_line FALSE)
            endif()
            string(APPEND code_out "${piece}\n")
        endif()
    endwhile()
endmacro()
