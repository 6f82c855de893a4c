# SPDX-License-Identifier: MIT
# ctest gate: a separate consumer project (tests/consumer) builds and runs against sbr
# twice: installed from the build tree into a scratch prefix (find_package(sbr) +
# sbr::sbr), and added with add_subdirectory (as FetchContent does), where it must not
# inherit sbr's -Werror, tests or host tools unless it asks for them.
file(REMOVE_RECURSE "${SBR_WORK}")

# run(WHAT COMMAND...): the command, or a fatal error naming WHAT
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc})")
  endif()
endfunction()

# consumer(DIR ARGS...): configure tests/consumer in DIR with ARGS, build it, run its app
function(consumer dir)
  run("consumer configure (${dir})" ${CMAKE_COMMAND} -S "${SBR_SOURCE_DIR}/tests/consumer" -B "${dir}"
      -G "${SBR_GENERATOR}" ${ARGN})
  run("consumer build (${dir})" ${CMAKE_COMMAND} --build "${dir}")
  run("consumer app (${dir})" "${dir}/app")
endfunction()

run("install" ${CMAKE_COMMAND} --install "${SBR_BUILD_DIR}" --prefix "${SBR_WORK}/prefix")
consumer("${SBR_WORK}/build" "-DCMAKE_PREFIX_PATH=${SBR_WORK}/prefix")
message(STATUS "consumer built against the installed sbr package and ran correctly")

consumer("${SBR_WORK}/subdir" "-DSBR_SOURCE=${SBR_SOURCE_DIR}" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
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
