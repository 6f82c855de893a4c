# SPDX-License-Identifier: MIT
# Cortex-M4F bare metal (arm-none-eabi GCC + newlib), single-precision FPU, hard float.
# Tests run on qemu's mps2-an386 (Cortex-M4 with FPU) through semihosting.
set(SBR_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)

set(SBR_QEMU_MACHINE mps2-an386 CACHE STRING "qemu machine for the tests")
set(CMAKE_CROSSCOMPILING_EMULATOR
    qemu-system-arm -M ${SBR_QEMU_MACHINE} -cpu cortex-m4 -nographic
    -semihosting-config enable=on,target=native -kernel)
