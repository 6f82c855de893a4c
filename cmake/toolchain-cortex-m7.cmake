# SPDX-License-Identifier: MIT
# Cortex-M7 bare metal with the single-precision FPU variant (fpv5-sp-d16), hard float.
# Builds the core only (no emulated test machine is configured for M7).
set(SBR_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-sp-d16")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)
set(SBR_BUILD_TESTS OFF CACHE BOOL "" FORCE)
