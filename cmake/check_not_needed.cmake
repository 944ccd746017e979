# cmake -DBINARY=path -DLIBRARY=regex -P check_not_needed.cmake
# Fails when the program names a shared library matching LIBRARY among those it needs at
# start (readelf's NEEDED entries): the proof that the hsr program starts without
# OpenImageIO and loads it only on use (renderer/image/image_library.hpp).
execute_process(COMMAND readelf --dynamic ${BINARY} RESULT_VARIABLE failed OUTPUT_VARIABLE dynamic ERROR_VARIABLE dynamic)
if(failed)
  message(FATAL_ERROR "readelf cannot read ${BINARY}:\n${dynamic}")
endif()
string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*" needed "${dynamic}")
if(NOT needed)
  message(FATAL_ERROR "${BINARY} lists no NEEDED libraries: not a dynamically linked program?")
endif()
foreach(entry ${needed})
  if(entry MATCHES "${LIBRARY}")
    message(FATAL_ERROR "${BINARY} needs ${entry} at start")
  endif()
endforeach()
