# cmake -DSPIRV=<file.spv> -DHEADER=<file.hpp> -DNAME=<symbol> -P spirv_header.cmake
# Turns a SPIR-V binary into a C++ header holding it as
#   inline constexpr std::uint32_t NAME[] = {...};
# (glslangValidator --vn writes a plain `const` array with no include for uint32_t and
# internal linkage; an inline constexpr array is one object in the whole program.)
file(READ "${SPIRV}" hex HEX)
string(LENGTH "${hex}" length)
math(EXPR rest "${length} % 8")
if(length EQUAL 0 OR NOT rest EQUAL 0)
    message(FATAL_ERROR "${SPIRV}: ${length} hex digits is not a whole number of 32-bit words")
endif()
# SPIR-V words are little-endian in the file: reverse the 4 bytes of each word.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x........u,){8})" "\\1\n    " words "${words}")
get_filename_component(source "${SPIRV}" NAME)
file(WRITE "${HEADER}.tmp"
"// Generated from ${source} by backends/vulkan/cmake/spirv_header.cmake: do not edit.\n"
"#pragma once\n#include <cstdint>\n\n"
"inline constexpr std::uint32_t ${NAME}[] = {\n    ${words}\n};\n")
# Leave the header untouched when the code did not change, so users' sources that
# include it are not rebuilt.
file(COPY_FILE "${HEADER}.tmp" "${HEADER}" ONLY_IF_DIFFERENT)
file(REMOVE "${HEADER}.tmp")
