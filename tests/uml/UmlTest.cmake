# roadload_add_uml_test(NAME <name> COMMAND <cmd> [<arg>...]
#                       [TIMEOUT <seconds>] [VCAN <n>] [MEM <size>]
#                       [WORKING_DIRECTORY <dir>] [ENVIRONMENT <VAR=value>...]
#                       [LABELS <label>...])
#
# Registers a ctest test that runs <cmd> inside a User-Mode Linux kernel with
# SocketCAN through tests/uml/uml-run. The test is labelled `uml` and is
# reported as skipped (exit 77) where linux.uml is not installed.
#
# TIMEOUT (default 120) is uml-run's own limit, which kills the UML process
# tree with a clear message; ctest's TIMEOUT is set 30 s higher as a backstop.
# ENVIRONMENT reaches the command only for PATH, HOME and ROADLOAD_* names:
# uml-run passes no other variables into the guest.
#
# Defined at directory scope of tests/uml but, like every CMake function,
# callable from any directory added after it.

set_property(GLOBAL PROPERTY ROADLOAD_UML_RUN "${CMAKE_CURRENT_LIST_DIR}/uml-run")

function(roadload_add_uml_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg ""
    "NAME;TIMEOUT;VCAN;MEM;WORKING_DIRECTORY" "COMMAND;ENVIRONMENT;LABELS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "roadload_add_uml_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_NAME OR NOT arg_COMMAND)
    message(FATAL_ERROR "roadload_add_uml_test: NAME and COMMAND are required")
  endif()
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 120)
  endif()
  if(NOT arg_TIMEOUT MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "roadload_add_uml_test(${arg_NAME}): TIMEOUT must be whole seconds, got '${arg_TIMEOUT}'")
  endif()
  if(NOT arg_WORKING_DIRECTORY)
    set(arg_WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  endif()

  get_property(uml_run GLOBAL PROPERTY ROADLOAD_UML_RUN)
  set(runner_args --timeout ${arg_TIMEOUT})
  if(DEFINED arg_VCAN)
    list(APPEND runner_args --vcan ${arg_VCAN})
  endif()
  if(arg_MEM)
    list(APPEND runner_args --mem ${arg_MEM})
  endif()

  add_test(NAME ${arg_NAME}
    COMMAND "${uml_run}" ${runner_args} -- ${arg_COMMAND}
    WORKING_DIRECTORY "${arg_WORKING_DIRECTORY}")
  math(EXPR ctest_timeout "${arg_TIMEOUT} + 30")
  set(labels uml ${arg_LABELS})
  set_tests_properties(${arg_NAME} PROPERTIES
    LABELS "${labels}"
    SKIP_RETURN_CODE 77
    TIMEOUT ${ctest_timeout}
    RESOURCE_LOCK uml)
  if(arg_ENVIRONMENT)
    set_property(TEST ${arg_NAME} PROPERTY ENVIRONMENT ${arg_ENVIRONMENT})
  endif()
endfunction()
