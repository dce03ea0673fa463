# 64-bit Arm Linux (e.g. a Raspberry Pi class HIL host or an automotive SoC).
# Test executables run on x86-64 through qemu-user, so `ctest` works unchanged.
# docs/build.md#aarch64
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(CVT_CROSS_TRIPLE aarch64-linux-gnu)
find_program(CMAKE_C_COMPILER   ${CVT_CROSS_TRIPLE}-gcc REQUIRED)
find_program(CMAKE_CXX_COMPILER ${CVT_CROSS_TRIPLE}-g++ REQUIRED)

# -L points qemu at the cross sysroot so the dynamically linked test binaries
# find ld-linux-aarch64.so.1, libstdc++ and libm.
find_program(CVT_QEMU_AARCH64 qemu-aarch64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${CVT_QEMU_AARCH64} -L /usr/${CVT_CROSS_TRIPLE})

set(CMAKE_FIND_ROOT_PATH /usr/${CVT_CROSS_TRIPLE} /usr/lib/${CVT_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
# Header-only dependencies (Eigen, doctest) are architecture-independent and
# live in the host's /usr/include and /usr/share/*/cmake, so both the sysroot
# and the host are searched for headers and CMake package files. Compiled
# libraries (CLI11 is header-only too, but toml++/libpng are not) are NOT
# cross-installed, which is why the aarch64 preset turns the tools off.
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# doctest's stock package config would add -isystem /usr/include; use the
# cross-safe one next to this file instead.
set(doctest_DIR ${CMAKE_CURRENT_LIST_DIR}/cross-packages/doctest CACHE PATH "doctest config for cross builds")
