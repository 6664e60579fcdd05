# The layering rule, checked on the sources. Two kinds of folder are checked:
#  - a layer: its sources (src/LAYER/) and public headers (include/gjklab/LAYER/) include gjklab
#    headers only of their own layer and of the layers it uses, and the third-party headers one
#    layer owns (CGAL, HDF5, TOML, MPI, CLI11) only in that layer's sources;
#  - a folder above the layers (apps/, python/, fuzz/, bench/): it includes any layer's public
#    headers (gjklab/LAYER/...) and its own, never a layer's private header (src/LAYER/, through
#    a path with ".." or by its name under src/), and of the owned third-party headers only its
#    own (CLI11 is apps'), those the table allows the folder, and the single files' exceptions.
# The rules come from the layer table in the top-level CMakeLists.txt, written by it into RULES;
# the build runs this script for each layer before compiling the layer and for each folder above
# the layers, and ctest runs it for all of them (tests `layering` and `layering_detects`).
#
#   cmake -DRULES=BUILD/layering/rules.cmake -DSOURCE_DIR=SOURCE [-DONLY=LAYER|FOLDER]
#         [-DSTAMP=FILE] -P cmake/check_layering.cmake
#
# Prints one line per wrong-way include (FILE:LINE: error: ...) and per exception of the table
# that no file needs any more, and fails; touches STAMP when every include keeps the rule.
cmake_minimum_required(VERSION 3.21)

if(NOT RULES OR NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DRULES=<rules.cmake> -DSOURCE_DIR=<source> [-DONLY=<layer or folder>] [-DSTAMP=<file>] -P check_layering.cmake")
endif()
# GJKLAB_LAYERS, GJKLAB_LAYER_USES_<layer>, GJKLAB_LAYER_ALSO_<layer>, GJKLAB_OWNED_HEADERS,
# GJKLAB_ABOVE_LAYERS, GJKLAB_ABOVE_MAY_INCLUDE_<folder>, GJKLAB_ABOVE_EXCEPTIONS
include(${RULES})

# The owners of the owned third-party header `path` (layers, or apps; "a|b" in the table), as a
# list in `owner` and as text in `owner_text` ("src/a/ or src/b/"), and the prefix that
# matched, in `prefix`; all empty for any other header.
function(owned_header path)
  foreach(owned IN LISTS GJKLAB_OWNED_HEADERS)
    string(REPLACE "=" ";" owned "${owned}")
    list(GET owned 0 prefix)
    list(GET owned 1 owner)
    string(FIND "${path}" "${prefix}" at)
    if(at EQUAL 0)
      string(REPLACE "|" " or src/" text "src/${owner}/")
      string(REPLACE " or src/" "/ or src/" text "${text}")
      string(REPLACE "|" ";" owner "${owner}")
      set(owner "${owner}" PARENT_SCOPE)
      set(owner_text "${text}" PARENT_SCOPE)
      set(prefix "${prefix}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(owner "" PARENT_SCOPE)
  set(owner_text "" PARENT_SCOPE)
  set(prefix "" PARENT_SCOPE)
endfunction()

# Why `#include path` in a file of `layer` breaks the rule (`public`: the file is a public
# header), in `problem`; empty when it keeps it.
function(layer_include_problem layer public path)
  set(uses ${GJKLAB_LAYER_USES_${layer}})
  set(allowed ${layer} ${uses})
  if(uses)
    string(REPLACE ";" ", " uses_text "${uses}")
    set(uses_text "${layer} uses only ${uses_text}")
  else()
    set(uses_text "${layer} uses no other layer")
  endif()
  set(problem "")
  if(path MATCHES "(^|/)\\.\\.(/|$)")
    set(problem "leaves the folder (a path through ..); include it as gjklab/LAYER/...")
  elseif(path MATCHES "^gjklab/([^/]+)/")
    set(dir "${CMAKE_MATCH_1}")
    if(dir IN_LIST allowed)
    elseif(dir IN_LIST GJKLAB_LAYERS)
      set(problem "is a header of the ${dir} layer: ${layer} may not use ${dir} (${uses_text})")
    else()
      set(problem "is not a header of a layer (include/gjklab/LAYER/)")
    endif()
  elseif(path MATCHES "^gjklab/")
    if(NOT path IN_LIST GJKLAB_LAYER_ALSO_${layer})
      set(problem "is not a header of ${layer} or of a layer it uses (${uses_text})")
    endif()
  else()
    owned_header("${path}")
    if(NOT owner)
    elseif(NOT layer IN_LIST owner)
      if(owner STREQUAL "apps")
        set(problem "is the command line's: only apps/ includes ${prefix}")
      else()
        set(problem "is included only in ${owner_text} (${layer} may not)")
      endif()
    elseif(public)
      set(problem "is included only in ${owner_text}, never in a public header")
    endif()
  endif()
  set(problem "${problem}" PARENT_SCOPE)
endfunction()

# Why `#include path` in the file `rel` of `folder`, above the layers, breaks the rule, in
# `problem`; empty when it keeps it. An exception of the table that allows it is recorded in
# the global property gjklab_used_exceptions.
function(above_include_problem folder rel path)
  # The first folder of the path, and the second when the first is gjklab/.
  set(first "")
  set(second "")
  if(path MATCHES "^([^/]+)/")
    set(first "${CMAKE_MATCH_1}")
  endif()
  if(path MATCHES "^gjklab/([^/]+)/")
    set(second "${CMAKE_MATCH_1}")
  endif()
  set(problem "")
  if(path MATCHES "(^|/)\\.\\.(/|$)")
    string(CONCAT problem "leaves the folder (a path through ..): a layer's private header "
                          "(src/) stays private; include a public one as gjklab/LAYER/...")
  elseif(first STREQUAL "gjklab")
    # A layer's public header (every folder above the layers may use every layer), or the
    # folder's own (apps/gjklab/cli.hpp is "gjklab/cli.hpp").
    if(NOT second IN_LIST GJKLAB_LAYERS AND NOT EXISTS "${SOURCE_DIR}/${folder}/${path}")
      string(CONCAT problem "is neither a public header of a layer (include/gjklab/LAYER/) "
                            "nor one of ${folder}/")
    endif()
  elseif(first IN_LIST GJKLAB_LAYERS AND EXISTS "${SOURCE_DIR}/src/${path}")
    string(CONCAT problem "is a private header of the ${first} layer (src/${first}/); include "
                          "a public one as gjklab/LAYER/...")
  else()
    owned_header("${path}")
    if(NOT owner OR folder IN_LIST owner OR prefix IN_LIST GJKLAB_ABOVE_MAY_INCLUDE_${folder})
    elseif("${rel}=${prefix}" IN_LIST GJKLAB_ABOVE_EXCEPTIONS)
      set_property(GLOBAL APPEND PROPERTY gjklab_used_exceptions "${rel}=${prefix}")
    elseif(owner STREQUAL "apps")
      set(problem "is the command line's: only apps/ includes ${prefix}")
    else()
      string(REPLACE ";" " or " layers "${owner}")
      set(problem "is included only in ${owner_text} (${folder}/ goes through the ${layers} layer)")
    endif()
  endif()
  set(problem "${problem}" PARENT_SCOPE)
endfunction()

if(ONLY)
  set(units ${ONLY})
else()
  set(units ${GJKLAB_LAYERS} ${GJKLAB_ABOVE_LAYERS})
endif()

set(errors 0)
set(checked 0)
foreach(unit IN LISTS units)
  if(unit IN_LIST GJKLAB_LAYERS)
    file(GLOB_RECURSE files LIST_DIRECTORIES false
         "${SOURCE_DIR}/src/${unit}/*" "${SOURCE_DIR}/include/gjklab/${unit}/*")
  elseif(unit IN_LIST GJKLAB_ABOVE_LAYERS)
    file(GLOB_RECURSE files LIST_DIRECTORIES false "${SOURCE_DIR}/${unit}/*")
  else()
    message(FATAL_ERROR "check_layering: ${unit} is neither a layer (${GJKLAB_LAYERS}) nor a "
                        "folder above the layers (${GJKLAB_ABOVE_LAYERS})")
  endif()
  list(SORT files)
  foreach(file IN LISTS files)
    if(NOT file MATCHES "\\.(c|cc|cpp|cxx|h|hh|hpp|hxx|inl|ipp|tpp)$")
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    file(RELATIVE_PATH rel "${SOURCE_DIR}" "${file}")
    set(public OFF)
    if(rel MATCHES "^include/")
      set(public ON)
    endif()
    file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS lines)
      if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"]")
        continue()  # an #include of a macro: not a path this check can read
      endif()
      set(path "${CMAKE_MATCH_1}")
      if(unit IN_LIST GJKLAB_LAYERS)
        layer_include_problem(${unit} ${public} "${path}")
      else()
        above_include_problem(${unit} "${rel}" "${path}")
      endif()
      if(problem)
        file(READ "${file}" text)
        string(FIND "${text}" "${line}" offset)
        string(SUBSTRING "${text}" 0 ${offset} before)
        string(REGEX MATCHALL "\n" newlines "${before}")
        list(LENGTH newlines number)
        math(EXPR number "${number} + 1")
        message(NOTICE "${rel}:${number}: error: #include \"${path}\" ${problem}")
        math(EXPR errors "${errors} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()

# An exception no file needs any more is an error too, so that the table says only what is
# true: each entry goes as soon as its code moves into a layer.
get_property(used GLOBAL PROPERTY gjklab_used_exceptions)
foreach(exception IN LISTS GJKLAB_ABOVE_EXCEPTIONS)
  string(REGEX MATCH "^[^/]+" folder "${exception}")
  if(folder IN_LIST units AND NOT exception IN_LIST used)
    string(REPLACE "=" ";" parts "${exception}")
    list(GET parts 0 rel)
    list(GET parts 1 prefix)
    message(NOTICE "${rel}: error: the exception \"${exception}\" of GJKLAB_ABOVE_EXCEPTIONS is "
                   "not needed (the file does not include ${prefix}): remove it from the table")
    math(EXPR errors "${errors} + 1")
  endif()
endforeach()

if(errors GREATER 0)
  message(FATAL_ERROR "layering rule broken: ${errors} wrong-way include(s) or unneeded "
                      "exception(s) above (the layers and what each may use: the layer table "
                      "in CMakeLists.txt)")
endif()
if(STAMP)
  file(TOUCH "${STAMP}")
endif()
