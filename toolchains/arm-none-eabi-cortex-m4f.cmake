# Cortex-M4 with single-precision FPU (FPv4-SP-D16), hard-float ABI.
# double is soft-float on this core. Runs on QEMU's mps2-an386 board.
# docs/build.md#toolchains
set(CVT_ARM_CPU_FLAGS "-mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard -mthumb")
set(CVT_QEMU_MACHINE mps2-an386 CACHE STRING "QEMU machine for this CPU")
set(CVT_LINKER_SCRIPT_BOARD mps2-an386 CACHE STRING "port/cortex-m/<board>.ld")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)
