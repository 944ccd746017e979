# The house's rule, enforced by the build: a layer sees only itself and the layers below
# it (renderer <- algorithms <- pipeline <- studies <- cli), and an algorithm folder sees
# only renderer/ and the algorithm interface, never another algorithm. Each target gets
# an include "view": a folder in the build tree holding symbolic links to just the paths
# it may include, as they are spelled from the repository's root ("renderer",
# "algorithms/knobs.hpp", ...). An #include of anything else is "No such file".

# hsr_include_view(TARGET SCOPE PATH...): TARGET includes through a view of PATHs (files
# or folders relative to the repository's root), PRIVATE or as its INTERFACE too (PUBLIC).
function(hsr_include_view target scope)
  set(view ${CMAKE_BINARY_DIR}/include-views/${target})
  file(REMOVE_RECURSE ${view})
  foreach(path ${ARGN})
    get_filename_component(parent ${view}/${path} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${path} ${view}/${path} SYMBOLIC)
  endforeach()
  target_include_directories(${target} ${scope} ${view})
endfunction()

# hsr_algorithm(NAME SOURCE...), in algorithms/NAME/CMakeLists.txt: the algorithm's
# sources, compiled seeing renderer/, the algorithm interface and its own folder only.
# Its entry, `AlgorithmEntry hsr::NAME::entry()`, joins the registry in the order the
# folders are added (algorithms/CMakeLists.txt).
function(hsr_algorithm name)
  hsr_algorithm_folder(${name} ${ARGN})
  set_property(GLOBAL APPEND PROPERTY HSR_ALGORITHMS ${name})
endfunction()

# hsr_algorithm_folder(NAME SOURCE...): a folder of algorithm code that is not itself a
# registry entry (the culling stages, which the culling pipeline lists).
function(hsr_algorithm_folder name)
  set(target hsr_algorithm_${name})
  add_library(${target} OBJECT ${ARGN})
  target_compile_options(${target} PRIVATE ${HSR_WARNINGS})
  target_link_libraries(${target} PUBLIC hsr_renderer)
  hsr_include_view(${target} PRIVATE algorithms/algorithm.hpp algorithms/knobs.hpp algorithms/${name})
  target_link_libraries(hsr_algorithms PRIVATE ${target})
endfunction()

# hsr_algorithm_test(NAME SOURCE...), in an algorithm's folder: its GoogleTest program,
# labelled NAME (ctest -L NAME), built with the other tests (tests/CMakeLists.txt).
function(hsr_algorithm_test name)
  set(sources "")
  foreach(source ${ARGN})
    list(APPEND sources ${CMAKE_CURRENT_SOURCE_DIR}/${source})
  endforeach()
  string(JOIN "," sources ${sources})  # one list item of the property
  set_property(GLOBAL APPEND PROPERTY HSR_ALGORITHM_TESTS "${name}=${sources}")
endfunction()
