# cmake -DSOURCE_DIR=... -P check_no_relative_includes.cmake
# The include views (cmake/layers.cmake) decide what each layer may include; an include
# that climbs out of its own folder ("../") would go around them. There must be none.
file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR}
  ${SOURCE_DIR}/renderer/*.[ch]pp ${SOURCE_DIR}/algorithms/*.[ch]pp ${SOURCE_DIR}/pipeline/*.[ch]pp
  ${SOURCE_DIR}/studies/*.[ch]pp ${SOURCE_DIR}/cli/*.[ch]pp)
set(found "")
foreach(source ${sources})
  file(STRINGS ${SOURCE_DIR}/${source} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"\\.\\./")
  foreach(line ${lines})
    string(APPEND found "\n  ${source}: ${line}")
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "includes that climb out of their folder, around the layers' include views:${found}")
endif()
