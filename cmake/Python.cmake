# The Python module (tools/python, docs/python.md): pybind11 from Debian's pybind11-dev, built for
# Debian's python3, whose pandas, numpy and distributed it uses (not a python3 first on PATH).
# On by default where pybind11 is found; off under the sanitizers (an ASan extension loads only
# into a python started with libasan preloaded), in the fuzz build and when cross-compiling.
set(ROADLOAD_PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Debian's python3: the module is built for it and the tests run it")
set(roadload_python_default OFF)
if(NOT ROADLOAD_SANITIZE AND NOT ROADLOAD_FUZZ AND NOT CMAKE_CROSSCOMPILING)
  set(Python_EXECUTABLE ${ROADLOAD_PYTHON_EXECUTABLE})
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  if(pybind11_FOUND)
    set(roadload_python_default ON)
  endif()
endif()
option(ROADLOAD_PYTHON "Build the Python module roadload (pybind11)" ${roadload_python_default})
# Where the package installs below the prefix: Debian's folder for python3's packages, on its
# sys.path for a /usr prefix.
set(ROADLOAD_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING "The Python package's folder below the install prefix")

if(ROADLOAD_PYTHON)
  set(Python_EXECUTABLE ${ROADLOAD_PYTHON_EXECUTABLE})
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG REQUIRED)
  # The extension links the same static libraries as the programs, so they are built once, as
  # position-independent code. Without semantic interposition GCC inlines and propagates across
  # them as it does for a program's -fPIE (no symbol of theirs is meant to be replaced).
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  add_compile_options(-fno-semantic-interposition)
endif()
