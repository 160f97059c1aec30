# cmake -DINPUT=file.spv -DOUTPUT=header.h -DIDENT=name -P EmbedBinary.cmake
file(READ ${INPUT} hex HEX)
string(LENGTH "${hex}" length)
math(EXPR size "${length} / 2")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
file(WRITE ${OUTPUT} "// Generated from ${INPUT}; do not edit.\n#pragma once\n#include <cstddef>\n"
  "alignas(4) static const unsigned char ${IDENT}[] = {${bytes}};\n"
  "static const std::size_t ${IDENT}_size = ${size};\n")
