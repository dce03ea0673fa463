# Shared part of the bare-metal Arm toolchain files (docs/build.md#toolchains).
# Not used directly: arm-none-eabi-cortex-m4f.cmake / -cortex-m7.cmake set
# CVT_ARM_CPU_FLAGS and then include this file.
#
# Everything here is what a firmware project would also use, so the library is
# built and tested with the same code-generation flags it ships with.

set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

# A bare-metal compiler cannot link a test executable without a startup file
# and linker script, so CMake's compiler checks build a static library instead.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CVT_ARM_TRIPLE arm-none-eabi CACHE STRING "Prefix of the bare-metal Arm GCC")
find_program(CMAKE_C_COMPILER   ${CVT_ARM_TRIPLE}-gcc REQUIRED)
find_program(CMAKE_CXX_COMPILER ${CVT_ARM_TRIPLE}-g++ REQUIRED)
find_program(CMAKE_ASM_COMPILER ${CVT_ARM_TRIPLE}-gcc REQUIRED)
find_program(CMAKE_OBJCOPY ${CVT_ARM_TRIPLE}-objcopy)
find_program(CMAKE_SIZE    ${CVT_ARM_TRIPLE}-size)

# Code generation common to C, C++ and assembler:
#  -ffunction-sections/-fdata-sections + --gc-sections: drop unused code.
#  -fstack-usage: one .su file per object, for worst-case stack review.
#  -ffp-contract=off: no fused multiply-add contraction, so float results
#   are bit-identical to the host build (docs/build.md#determinism).
set(_cvt_common "${CVT_ARM_CPU_FLAGS} -ffunction-sections -fdata-sections -fstack-usage -ffp-contract=off -fno-fast-math")
set(CMAKE_C_FLAGS_INIT   "${_cvt_common}")
set(CMAKE_ASM_FLAGS_INIT "${CVT_ARM_CPU_FLAGS}")
# No exceptions, no RTTI, no thread-safe statics guard calls (there is one
# thread; the guards would pull __cxa_guard_* from libsupc++). Static
# destructors are registered through __aeabi_atexit, which port/cortex-m
# defines as a no-op: a firmware image never tears down its statics.
set(CMAKE_CXX_FLAGS_INIT "${_cvt_common} -fno-exceptions -fno-rtti -fno-threadsafe-statics")
# newlib-nano (smaller libc, still only for memcpy/memset and libm); each
# image supplies its own startup (-nostartfiles) and linker script
# (port/cortex-m). The no-heap link check lives in port/cortex-m/ld/no_heap.ld.
set(CMAKE_EXE_LINKER_FLAGS_INIT "${CVT_ARM_CPU_FLAGS} --specs=nano.specs -nostartfiles -Wl,--gc-sections")

# Release-type builds: -O2, asserts off. CACHE so that CMake's GNU defaults
# (-O3) do not get appended; -O2 is what the instruction counts in
# docs/build.md#icount are quoted for.
foreach(_lang C CXX)
  set(CMAKE_${_lang}_FLAGS_RELEASE "-O2 -DNDEBUG" CACHE STRING "")
  set(CMAKE_${_lang}_FLAGS_RELWITHDEBINFO "-O2 -g -DNDEBUG" CACHE STRING "")
endforeach()

# Headers and libraries come from the cross sysroot; programs from the host.
# Packages (CMake config files) may come from both: Eigen is header-only and
# architecture-independent, so the host's /usr/share/eigen3/cmake is fine.
set(CMAKE_FIND_ROOT_PATH /usr/lib/${CVT_ARM_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# The QEMU board that runs this CPU's images (used by tests/target).
set(CVT_QEMU_SYSTEM qemu-system-arm CACHE STRING "QEMU system emulator for Cortex-M images")
