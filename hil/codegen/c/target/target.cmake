# The C codec linked into a Cortex-M image with the no-heap link check and run
# under QEMU (docs/can.md#c-codec). Included at the end of the configure of an
# embedded build, once port/cortex-m and tests/target have defined their
# targets and found QEMU.
if(NOT TARGET cvtplant_port_cortex_m)
  return()
endif()
add_executable(cvt_can_c_target ${CMAKE_CURRENT_LIST_DIR}/main.cpp ${CMAKE_CURRENT_LIST_DIR}/selftest.c)
set_target_properties(cvt_can_c_target PROPERTIES SUFFIX .elf C_STANDARD 99 C_STANDARD_REQUIRED ON)
target_link_libraries(cvt_can_c_target PRIVATE cvtplant::can_c cvtplant::port_cortex_m)
if(CVT_QEMU_SYSTEM_EXE AND CVT_QEMU_MACHINE)
  add_test(NAME hil.c_codec_cortex_m
    COMMAND ${CMAKE_COMMAND} -DQEMU=${CVT_QEMU_SYSTEM_EXE} -DMACHINE=${CVT_QEMU_MACHINE}
      -DIMAGE=$<TARGET_FILE:cvt_can_c_target> -DEXPECT_STATUS=0
      "-DEXPECT_REGEX=C codec self-test: 0 failed checks.*RESULT PASS" -DTIMEOUT=60
      -P ${PROJECT_SOURCE_DIR}/tests/target/run_qemu.cmake)
  set_tests_properties(hil.c_codec_cortex_m PROPERTIES TIMEOUT 60 LABELS "target;qemu;can")
endif()
