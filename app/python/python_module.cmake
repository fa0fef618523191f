# The `bhm` Python module, only when Python 3 (with its headers) and pybind11 are found:
# Debian's python3-dev, pybind11-dev / python3-pybind11 (numpy is needed at run time only).
# Built into build/python/ so that PYTHONPATH=build/python python3 -c "import bhm" works.
# It links engine + evo (compiled position-independent for it) and the few app/cli files it wires;
# nothing of the renderer or the studio.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  # The system interpreter, whose headers and numpy the Debian packages provide (a pyenv or
  # venv python3 earlier on PATH would lack them).
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c "import pybind11; print(pybind11.get_cmake_dir())"
                  OUTPUT_VARIABLE BHM_PYBIND11_DIR OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET HINTS ${BHM_PYBIND11_DIR})
endif()
if(Python3_FOUND AND pybind11_FOUND)
  message(STATUS "Python module bhm: ${Python3_EXECUTABLE} (pybind11 ${pybind11_VERSION})")
  # -fPIC for the shared module; no semantic interposition so the PIC code is optimised exactly
  # like the executable's position-independent code (Debian builds PIE by default).
  set_target_properties(engine evo PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(engine PRIVATE -fno-semantic-interposition)
  target_compile_options(evo PRIVATE -fno-semantic-interposition)
  # NO_EXTRAS: no link-time optimisation (slow on two cores) and no stripping.
  pybind11_add_module(bhm_python MODULE NO_EXTRAS ${CMAKE_CURRENT_SOURCE_DIR}/python/bhm_module.cpp
                      ${CMAKE_CURRENT_SOURCE_DIR}/cli/simulation_report.cpp
                      ${CMAKE_CURRENT_SOURCE_DIR}/cli/simulation_limits.cpp
                      ${CMAKE_CURRENT_SOURCE_DIR}/cli/file_kind.cpp)
  target_include_directories(bhm_python PRIVATE ${BHM_ROOT} ${CMAKE_BINARY_DIR}/generated)
  target_link_libraries(bhm_python PRIVATE evo engine bhm_warnings)
  set_target_properties(bhm_python PROPERTIES OUTPUT_NAME bhm LIBRARY_OUTPUT_DIRECTORY
                                              ${CMAKE_BINARY_DIR}/python)
  set(BHM_PYTHON_MODULE ON PARENT_SCOPE)
  set(BHM_PYTHON_EXECUTABLE ${Python3_EXECUTABLE} PARENT_SCOPE)
else()
  message(STATUS "Python module bhm: not built (needs python3-dev and pybind11-dev)")
  set(BHM_PYTHON_MODULE OFF PARENT_SCOPE)
endif()
