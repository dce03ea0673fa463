# Writes the C++ compiler and the C++ flags of a Release build with a
# toolchain file, one per line, to OUT, so that check_m4_codec.sh compiles
# with the flags the firmware build itself uses (docs/build.md#toolchains).
# usage: cmake -DTOOLCHAIN=<toolchain file> -DOUT=<file> -P toolchain_flags.cmake
include(${TOOLCHAIN})
file(WRITE ${OUT} "${CMAKE_CXX_COMPILER}\n${CMAKE_CXX_FLAGS_INIT} ${CMAKE_CXX_FLAGS_RELEASE}\n")
