# Cortex-M7 with double-precision FPU (FPv5-D16), hard-float ABI: both float
# and double are done in hardware. Runs on QEMU's mps2-an500 board.
# docs/build.md#toolchains
set(CVT_ARM_CPU_FLAGS "-mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard -mthumb")
set(CVT_QEMU_MACHINE mps2-an500 CACHE STRING "QEMU machine for this CPU")
set(CVT_LINKER_SCRIPT_BOARD mps2-an500 CACHE STRING "port/cortex-m/<board>.ld")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)
