# SPDX-License-Identifier: MIT
# 32-bit ARM Linux (armhf, hard float). Tests run under qemu user-mode emulation;
# executables are linked statically so qemu-arm needs no ARM sysroot.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-linux-gnueabihf-gcc)
set(CMAKE_CXX_COMPILER arm-linux-gnueabihf-g++)
set(CMAKE_NM arm-linux-gnueabihf-nm)
set(SBR_SIZE_TOOL arm-linux-gnueabihf-size)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CMAKE_FIND_ROOT_PATH /usr/arm-linux-gnueabihf)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(SBR_TARGET_ARMHF ON CACHE BOOL "armhf Linux build" FORCE)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-arm)
