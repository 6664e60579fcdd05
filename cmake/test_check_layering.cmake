# Test of cmake/check_layering.cmake (ctest `layering_detects`): on a scratch source tree with
# one wrong-way include per kind, in the layers and in the folders above them, it must fail and
# name each, FILE:LINE first; on the same tree with the rule kept it must pass; and an exception
# of the table that no file needs must fail it.
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
put(src/experiment/run/result_codec.hpp "#pragma once\n")
# Above the layers: any layer's public headers, the folder's own, CLI11 in apps/, libhdf5 in the
# archive fuzz targets, the libraries nobody owns; and each file the table excepts, with its
# header (from the rules, so the test follows the table as exceptions go).
put(apps/gjklab/cli.hpp "#pragma once\n#include \"gjklab/experiment/config/config.hpp\"\n")
put(apps/gjklab/fine.cpp "#include \"gjklab/cli.hpp\"\n#include <CLI/CLI.hpp>\n#include \"gjklab/scene/world.hpp\"\n")
put(python/bindings.cpp "#include <pybind11/pybind11.h>\n#include \"gjklab/experiment/run/driver.hpp\"\n")
put(fuzz/archive.cpp "#include <hdf5.h>\n#include \"support.hpp\"\n#include \"gjklab/experiment/archive/archive.hpp\"\n")
put(bench/fine.cpp "#include <benchmark/benchmark.h>\n#include \"random_inputs.hpp\"\n#include \"gjklab/exact/hull_adjacency.hpp\"\n")
include(${RULES})
foreach(exception IN LISTS GJKLAB_ABOVE_EXCEPTIONS)
  string(REPLACE "=" ";" parts "${exception}")
  list(GET parts 0 file)
  list(GET parts 1 prefix)
  if(prefix MATCHES "/$")
    string(APPEND prefix "header.h")
  endif()
  put(${file} "#include <${prefix}>\n")
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -DRULES=${RULES} -DSOURCE_DIR=${WORK} -P ${CHECK}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the check refused includes that keep the rule:\n${out}")
endif()

# An exception of the table that no file needs: the same tree, one more entry in the table.
set(stale_rules ${WORK}/stale_rules.cmake)
file(READ ${RULES} rules)
file(WRITE ${stale_rules} "${rules}list(APPEND GJKLAB_ABOVE_EXCEPTIONS \"bench/fine.cpp=toml++/\")\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DRULES=${stale_rules} -DSOURCE_DIR=${WORK} -P ${CHECK}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
set(expected "bench/fine.cpp: error: the exception \"bench/fine.cpp=toml++/\" of GJKLAB_ABOVE_EXCEPTIONS is not needed")
string(FIND "${out}" "${expected}" at)
if(status EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "the check did not refuse an exception no file needs:\n${out}")
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
put(apps/gjklab/wrong.cpp "#include <hdf5.h>\n#include \"../../src/experiment/run/result_codec.hpp\"\n#include \"experiment/run/result_codec.hpp\"\n")
put(bench/wrong.cpp "#include <toml++/toml.h>\n#include \"../src/experiment/run/result_codec.hpp\"\n#include <CLI/CLI.hpp>\n#include \"gjklab/cli.hpp\"\n")
put(python/wrong.cpp "#include <mpi.h>\n#include \"gjklab/cli.hpp\"\n")
put(fuzz/wrong.cpp "#include <CGAL/Gmpq.h>\n")
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
  "apps/gjklab/wrong.cpp:1: error: #include \"hdf5.h\" is included only in src/experiment/ (apps/ goes through the experiment layer)"
  "apps/gjklab/wrong.cpp:2: error: #include \"../../src/experiment/run/result_codec.hpp\" leaves the folder"
  "apps/gjklab/wrong.cpp:3: error: #include \"experiment/run/result_codec.hpp\" is a private header of the experiment layer (src/experiment/)"
  "bench/wrong.cpp:1: error: #include \"toml++/toml.h\" is included only in src/experiment/ or src/simulation/ (bench/ goes through the experiment or simulation layer)"
  "bench/wrong.cpp:2: error: #include \"../src/experiment/run/result_codec.hpp\" leaves the folder"
  "bench/wrong.cpp:3: error: #include \"CLI/CLI.hpp\" is the command line's"
  "bench/wrong.cpp:4: error: #include \"gjklab/cli.hpp\" is neither a public header of a layer (include/gjklab/LAYER/) nor one of bench/"
  "python/wrong.cpp:1: error: #include \"mpi.h\" is included only in src/experiment/ (python/ goes through the experiment layer)"
  "python/wrong.cpp:2: error: #include \"gjklab/cli.hpp\" is neither a public header of a layer (include/gjklab/LAYER/) nor one of python/"
  "fuzz/wrong.cpp:1: error: #include \"CGAL/Gmpq.h\" is included only in src/exact/ (fuzz/ goes through the exact layer)"
  "layering rule broken: 20 wrong-way include(s)")
foreach(line IN LISTS expected)
  string(FIND "${out}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the check's output lacks\n  ${line}\nOutput:\n${out}")
  endif()
endforeach()
message(STATUS "the check names all 20 wrong-way includes:\n${out}")
file(REMOVE_RECURSE "${WORK}")
