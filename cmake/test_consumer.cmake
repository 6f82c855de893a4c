# ctest gate: install sbr from the build tree into a scratch prefix, then configure,
# build and run a separate consumer project that uses find_package(sbr) + sbr::sbr.
file(REMOVE_RECURSE "${SBR_WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${SBR_BUILD_DIR}" --prefix "${SBR_WORK}/prefix"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SBR_SOURCE_DIR}/tests/consumer" -B "${SBR_WORK}/build"
                        -G "${SBR_GENERATOR}" "-DCMAKE_PREFIX_PATH=${SBR_WORK}/prefix"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer configure failed (find_package(sbr))")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${SBR_WORK}/build" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer build failed")
endif()
execute_process(COMMAND "${SBR_WORK}/build/app" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer app returned ${rc}")
endif()
message(STATUS "consumer built against the installed sbr package and ran correctly")

# The same consumer with sbr added by add_subdirectory (as FetchContent does): it builds,
# runs, and does not inherit sbr's -Werror, tests or host tools unless it asks for them.
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SBR_SOURCE_DIR}/tests/consumer" -B "${SBR_WORK}/subdir"
                        -G "${SBR_GENERATOR}" "-DSBR_SOURCE=${SBR_SOURCE_DIR}"
                        -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "add_subdirectory consumer configure failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${SBR_WORK}/subdir" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "add_subdirectory consumer build failed")
endif()
execute_process(COMMAND "${SBR_WORK}/subdir/app" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "add_subdirectory consumer app returned ${rc}")
endif()
file(READ "${SBR_WORK}/subdir/compile_commands.json" cc)
if(NOT cc MATCHES "fd\\.c")
  message(FATAL_ERROR "add_subdirectory consumer: sbr's core not in compile_commands.json")
endif()
if(cc MATCHES "-Werror")
  message(FATAL_ERROR "add_subdirectory consumer inherited -Werror")
endif()
if(EXISTS "${SBR_WORK}/subdir/sbr/tests" OR EXISTS "${SBR_WORK}/subdir/sbr/host_tools")
  message(FATAL_ERROR "add_subdirectory consumer built sbr's tests or host tools")
endif()
message(STATUS "consumer built with add_subdirectory(sbr): no -Werror, no tests, ran correctly")
