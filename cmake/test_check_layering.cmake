# Test of cmake/check_layering.cmake (ctest `layering_detects`): on a scratch source tree with
# one wrong-way include per kind it must fail and name each, FILE:LINE first; on the same tree
# with the rule kept it must pass.
#
#   cmake -DRULES=BUILD/layering/rules.cmake -DCHECK=cmake/check_layering.cmake -DWORK=DIR
#         -P cmake/test_check_layering.cmake
cmake_minimum_required(VERSION 3.21)

file(REMOVE_RECURSE "${WORK}")
function(put path text)
  file(WRITE "${WORK}/${path}" "${text}")
endfunction()

# Includes that keep the rule (a layer's own headers, those of the layers it uses, private
# headers of its folder, the owned third-party headers in the owner's sources).
put(src/geometry/fine.cpp "#include \"gjklab/geometry/types.hpp\"\n#include <vector>\n")
put(src/gjk/fine.cpp "#include \"gjklab/gjk/simplex.hpp\"\n#include \"gjklab/geometry/support.hpp\"\n")
put(src/exact/fine.cpp "#include <CGAL/version.h>\n#include \"hull.hpp\"\n#include \"gjklab/geometry/types.hpp\"\n")
put(src/experiment/fine.cpp "#include \"gjklab/build_info.hpp\"\n#include <hdf5.h>\n#include \"gjklab/peers/sat.hpp\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DRULES=${RULES} -DSOURCE_DIR=${WORK} -P ${CHECK}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the check refused includes that keep the rule:\n${out}")
endif()

# One wrong-way include of each kind.
put(src/geometry/wrong.cpp "// a comment\n\n#include \"gjklab/gjk/simplex.hpp\"\n")
put(include/gjklab/geometry/wrong.hpp "#pragma once\n#  include <gjklab/experiment/config/config.hpp>\n")
put(src/gjk/wrong.cpp "#include \"gjklab/exact/oracle.hpp\"\n")
put(src/exact/wrong.cpp "#include \"../gjk/simplex.hpp\"\n")
put(include/gjklab/exact/wrong.hpp "#pragma once\n#include <CGAL/Gmpq.h>\n")
put(src/scene/wrong.cpp "#include \"gjklab/experiment/archive/archive.hpp\"\n#include <hdf5.h>\n")
put(src/peers/wrong.cpp "#include \"gjklab/cli.hpp\"\n")
put(src/experiment/wrong.cpp "#include \"gjklab/scene/world.hpp\"\n#include <CLI/CLI.hpp>\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DRULES=${RULES} -DSOURCE_DIR=${WORK} -P ${CHECK}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(status EQUAL 0)
  message(FATAL_ERROR "the check passed a tree with wrong-way includes:\n${out}")
endif()
set(expected
  "src/geometry/wrong.cpp:3: error: #include \"gjklab/gjk/simplex.hpp\" is a header of the gjk layer: geometry may not use gjk (geometry uses no other layer)"
  "include/gjklab/geometry/wrong.hpp:2: error: #include \"gjklab/experiment/config/config.hpp\" is a header of the experiment layer: geometry may not use experiment"
  "src/gjk/wrong.cpp:1: error: #include \"gjklab/exact/oracle.hpp\" is a header of the exact layer: gjk may not use exact (gjk uses only geometry)"
  "src/exact/wrong.cpp:1: error: #include \"../gjk/simplex.hpp\" leaves the folder"
  "include/gjklab/exact/wrong.hpp:2: error: #include \"CGAL/Gmpq.h\" is included only in src/exact/, never in a public header"
  "src/scene/wrong.cpp:1: error: #include \"gjklab/experiment/archive/archive.hpp\" is a header of the experiment layer: scene may not use experiment"
  "src/scene/wrong.cpp:2: error: #include \"hdf5.h\" is included only in src/experiment/"
  "src/peers/wrong.cpp:1: error: #include \"gjklab/cli.hpp\" is not a header of peers or of a layer it uses"
  "src/experiment/wrong.cpp:1: error: #include \"gjklab/scene/world.hpp\" is a header of the scene layer: experiment may not use scene"
  "src/experiment/wrong.cpp:2: error: #include \"CLI/CLI.hpp\" is the command line's"
  "layering rule broken: 10 wrong-way include(s)")
foreach(line IN LISTS expected)
  string(FIND "${out}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the check's output lacks\n  ${line}\nOutput:\n${out}")
  endif()
endforeach()
message(STATUS "the check names all 10 wrong-way includes:\n${out}")
file(REMOVE_RECURSE "${WORK}")
