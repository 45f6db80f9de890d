# Script mode: -DINPUT=file -DOUTPUT=file.cpp -DSYMBOL=name
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" hex_len)
math(EXPR size "${hex_len} / 2")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE "${OUTPUT}" "// Generated from ${INPUT}; do not edit.\n#include <span>\nnamespace spectrace::embedded {\nnamespace {\nalignas(4) const unsigned char bytes[${size} + 1] = {\n${bytes}0};\n}\nstd::span<const unsigned char> ${SYMBOL}() { return {bytes, ${size}}; }\n}  // namespace spectrace::embedded\n")
