# cmake -DCOMPILER=... -DVIEWS=dir;dir -DHEADER=path -DEXPECT=found|missing -P check_include.cmake
# Compiles a file holding only `#include "HEADER"` through the include views of a target
# (cmake/layers.cmake) and checks that the header is found, or that it is missing: the
# build's proof that a layer sees what it may and nothing else.
string(MAKE_C_IDENTIFIER "${HEADER}" stem)
set(probe ${CMAKE_CURRENT_BINARY_DIR}/include_probe_${stem}.cpp)
file(WRITE ${probe} "#include \"${HEADER}\"\n")
set(flags -std=c++20 -fsyntax-only)
foreach(view ${VIEWS})
  list(APPEND flags -I${view})
endforeach()
execute_process(COMMAND ${COMPILER} ${flags} ${probe} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(EXPECT STREQUAL "found" AND NOT result EQUAL 0)
  message(FATAL_ERROR "${HEADER} should be visible here but does not compile:\n${output}")
elseif(EXPECT STREQUAL "missing")
  if(result EQUAL 0)
    message(FATAL_ERROR "${HEADER} should not be visible here, and it compiled")
  # "No such file" in GCC's words, then in clang's (the sanitize preset).
  elseif(NOT output MATCHES "${HEADER}: No such file or directory" AND NOT output MATCHES "'${HEADER}' file not found")
    message(FATAL_ERROR "${HEADER} failed for another reason than not being visible:\n${output}")
  endif()
endif()
