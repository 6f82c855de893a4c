# SPDX-License-Identifier: MIT
# Unity 2.6.1 (ThrowTheSwitch, MIT) as shipped in the PyPI wheel vyperling 0.0.4, folder
# vyperling/c/. Downloaded at configure time with pip, pinned by version and sha256, and
# unpacked into the build tree: Unity's files are never committed. -DUNITY_ROOT=<dir>
# (a folder holding unity.c, unity.h, unity_internals.h) skips the download.
set(SBR_UNITY_WHEEL "vyperling-0.0.4-py3-none-any.whl")
set(SBR_UNITY_SHA256 "028f4419cf4f49cfaed51256290718753a78cc035923fbf43acc8bcd62d205cb")

if(NOT UNITY_ROOT)
  set(_unity_dir "${CMAKE_BINARY_DIR}/_deps/unity")
  if(NOT EXISTS "${_unity_dir}/unity.c")
    if(NOT Python3_EXECUTABLE)
      message(FATAL_ERROR "Unity download needs python3 with pip (or pass -DUNITY_ROOT=<dir>)")
    endif()
    set(_dl "${CMAKE_BINARY_DIR}/_deps/unity-download")
    file(MAKE_DIRECTORY "${_dl}")
    file(WRITE "${_dl}/requirements.txt" "vyperling==0.0.4 --hash=sha256:${SBR_UNITY_SHA256}\n")
    execute_process(
      COMMAND "${Python3_EXECUTABLE}" -m pip download --quiet --no-deps --require-hashes
              -r "${_dl}/requirements.txt" -d "${_dl}"
      RESULT_VARIABLE _rc)
    if(NOT _rc EQUAL 0 OR NOT EXISTS "${_dl}/${SBR_UNITY_WHEEL}")
      message(FATAL_ERROR "Could not download ${SBR_UNITY_WHEEL} with pip (or pass -DUNITY_ROOT=<dir>)")
    endif()
    file(SHA256 "${_dl}/${SBR_UNITY_WHEEL}" _sum)
    if(NOT _sum STREQUAL SBR_UNITY_SHA256)
      message(FATAL_ERROR "${SBR_UNITY_WHEEL}: sha256 ${_sum}, expected ${SBR_UNITY_SHA256}")
    endif()
    file(ARCHIVE_EXTRACT INPUT "${_dl}/${SBR_UNITY_WHEEL}" DESTINATION "${_dl}/x"
         PATTERNS "vyperling/c/unity*" "vyperling/c/UNITY_LICENSE")
    file(MAKE_DIRECTORY "${_unity_dir}")
    foreach(_f unity.c unity.h unity_internals.h UNITY_LICENSE)
      file(COPY "${_dl}/x/vyperling/c/${_f}" DESTINATION "${_unity_dir}")
    endforeach()
  endif()
  set(UNITY_ROOT "${_unity_dir}")
endif()

foreach(_f unity.c unity.h unity_internals.h)
  if(NOT EXISTS "${UNITY_ROOT}/${_f}")
    message(FATAL_ERROR "UNITY_ROOT=${UNITY_ROOT} has no ${_f}")
  endif()
endforeach()

add_library(unity STATIC "${UNITY_ROOT}/unity.c")
target_include_directories(unity PUBLIC "${UNITY_ROOT}")
# Double assertions are used by the reference computations of the tests.
target_compile_definitions(unity PUBLIC UNITY_INCLUDE_DOUBLE)
message(STATUS "Unity: ${UNITY_ROOT}")
