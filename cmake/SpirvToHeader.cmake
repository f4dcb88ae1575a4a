# Turns a SPIR-V binary into a C++ header holding it as a uint32_t array (4-byte aligned, as Vulkan needs).
# Invoked by ripple_add_shaders as: cmake -DINPUT=x.spv -DOUTPUT=x.spv.h -DNAME=x -P SpirvToHeader.cmake
file(READ "${INPUT}" bytes HEX)
string(LENGTH "${bytes}" length)
math(EXPR remainder "${length} % 8")
if(NOT remainder EQUAL 0)
  message(FATAL_ERROR "${INPUT} is not a whole number of 32-bit words")
endif()
# SPIR-V words are little-endian: bytes b0 b1 b2 b3 form 0xb3b2b1b0.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${bytes}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){8})" "\\1\n    " words "${words}")
file(WRITE "${OUTPUT}.tmp"
"// Generated from ${NAME}.comp by cmake/SpirvToHeader.cmake; do not edit.\n"
"#pragma once\n#include <cstdint>\n\nnamespace ripple::shaders {\n"
"inline constexpr uint32_t ${NAME}[] = {\n    ${words}\n};\n}  // namespace ripple::shaders\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
