# cmake -DINPUT=file -DOUTPUT=header -DNAME=kSymbol -P embed_text.cmake: writes a header holding the file as a string.
file(READ ${INPUT} text)
file(WRITE ${OUTPUT} "#pragma once\n// Generated from ${INPUT}; do not edit.\nnamespace tessera::examples {\n"
                     "inline constexpr const char* ${NAME} = R\"embedded(${text})embedded\";\n}\n")
