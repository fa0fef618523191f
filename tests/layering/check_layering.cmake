# The include rules of docs/architecture.md, run by CTest (cmake -DROOT=<repo> -P this file):
#  1. nothing outside engine/ includes engine/internal/ (the step's private parts), except the
#     engine's own white-box tests in tests/engine/ (they check the private layout itself);
#  2. inside evo/, a folder includes only itself and folders before it in the order of the work:
#     experiment -> genome -> formats -> evaluate -> search -> run -> verify -> calibrate;
#  3. inside app/gui/, the studio's floors: the state (studio.hpp, document/, session/, view/,
#     settings/, welcome/, widgets/) -> actions/ -> panels/ -> the top (shell/, studio_app). A
#     source includes only its own floor and the floors below it, so nothing but the top includes
#     panels/ or shell/, and nothing below actions/ includes actions/.
# Prints every violation as FILE: includes HEADER (why) and fails when there is any.
cmake_minimum_required(VERSION 3.22)
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<repository root> -P check_layering.cmake")
endif()

set(evo_order experiment genome formats evaluate search run verify calibrate)
set(violations 0)

# The floor of an app/gui/ source (or header path), low to high; -1 outside app/gui/.
set(gui_floor_names state actions panels top)
string(REPLACE ";" " -> " gui_floors "${gui_floor_names}")
function(gui_floor path out)
  set(floor -1)
  if(path MATCHES "^app/gui/(studio\\.hpp|document/|session/|view/|settings/|welcome/|widgets/)")
    set(floor 0)
  elseif(path MATCHES "^app/gui/actions/")
    set(floor 1)
  elseif(path MATCHES "^app/gui/panels/")
    set(floor 2)
  elseif(path MATCHES "^app/gui/(shell/|studio_app\\.)")
    set(floor 3)
  elseif(path MATCHES "^app/gui/")
    set(floor -2)  # a place the rule does not know: a new folder must be given a floor here
  endif()
  set(${out} ${floor} PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE sources RELATIVE ${ROOT}
     ${ROOT}/engine/*.hpp ${ROOT}/engine/*.cpp ${ROOT}/evo/*.hpp ${ROOT}/evo/*.cpp
     ${ROOT}/render/*.hpp ${ROOT}/render/*.cpp ${ROOT}/app/*.hpp ${ROOT}/app/*.cpp
     ${ROOT}/tests/*.hpp ${ROOT}/tests/*.cpp)
list(LENGTH sources source_count)
if(source_count LESS 50)
  message(FATAL_ERROR "check_layering: found only ${source_count} sources under ${ROOT}")
endif()

foreach(source IN LISTS sources)
  file(STRINGS ${ROOT}/${source} include_lines REGEX "^[ \t]*#[ \t]*include[ \t]+\"")
  # The folder of a source under evo/, and its rank in the order of the work.
  set(own_rank -1)
  if(source MATCHES "^evo/([a-z_]+)/")
    list(FIND evo_order ${CMAKE_MATCH_1} own_rank)
    if(own_rank LESS 0)
      message("${source}: evo/${CMAKE_MATCH_1}/ is not a folder of the order (${evo_order})")
      math(EXPR violations "${violations} + 1")
    endif()
  elseif(source MATCHES "^evo/[^/]+$")
    message("${source}: evo/ keeps its sources in the folders of the order (${evo_order})")
    math(EXPR violations "${violations} + 1")
  endif()
  gui_floor(${source} own_floor)
  if(own_floor EQUAL -2)
    message("${source}: app/gui/ keeps its sources on the floors ${gui_floors} (docs/architecture.md)")
    math(EXPR violations "${violations} + 1")
  endif()
  foreach(line IN LISTS include_lines)
    if(NOT line MATCHES "#[ \t]*include[ \t]+\"([^\"]+)\"")
      continue()
    endif()
    set(header ${CMAKE_MATCH_1})
    if(header MATCHES "^engine/internal/" AND NOT source MATCHES "^(engine|tests/engine)/")
      message("${source}: includes ${header} (engine/internal/ is private to engine/)")
      math(EXPR violations "${violations} + 1")
    endif()
    if(own_rank GREATER_EQUAL 0 AND header MATCHES "^evo/([a-z_]+)/")
      list(FIND evo_order ${CMAKE_MATCH_1} header_rank)
      if(header_rank GREATER own_rank)
        message("${source}: includes ${header} (evo/${CMAKE_MATCH_1}/ comes later in the order ${evo_order})")
        math(EXPR violations "${violations} + 1")
      endif()
    endif()
    if(own_floor GREATER_EQUAL 0)
      gui_floor(${header} header_floor)
      if(header_floor GREATER own_floor)
        list(GET gui_floor_names ${own_floor} own_name)
        list(GET gui_floor_names ${header_floor} header_name)
        message("${source}: includes ${header} (${header_name} is above ${own_name} in the studio's floors ${gui_floors})")
        math(EXPR violations "${violations} + 1")
      endif()
    endif()
  endforeach()
endforeach()

if(violations GREATER 0)
  message(FATAL_ERROR "check_layering: ${violations} include(s) break the layering (docs/architecture.md)")
endif()
message(STATUS "check_layering: ${source_count} sources follow the layering")
