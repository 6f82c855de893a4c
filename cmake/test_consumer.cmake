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
