# SPDX-License-Identifier: MIT
# Shared by the bare-metal toolchain files: arm-none-eabi GCC + newlib. The including file
# sets SBR_CPU_FLAGS (core, FPU, float ABI) first.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(CMAKE_NM arm-none-eabi-nm)
set(SBR_SIZE_TOOL arm-none-eabi-size)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "${SBR_CPU_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${SBR_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${SBR_CPU_FLAGS}")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

set(SBR_TARGET_CORTEX_M ON CACHE BOOL "Bare-metal Cortex-M build" FORCE)
