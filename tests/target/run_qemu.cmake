# Runs one Cortex-M image under qemu-system-arm and checks its exit status and
# console output. Used by the ctest entries in tests/target/CMakeLists.txt.
#   cmake -DQEMU=... -DMACHINE=mps2-an386 -DIMAGE=x.elf -DEXPECT_STATUS=0
#         [-DEXPECT_REGEX=...] [-DTIMEOUT=60] [-DLOG_FILE=out.log] -P run_qemu.cmake
# LOG_FILE keeps the console output for later steps (the cross-target
# determinism check reads the HASH lines from it).
# docs/build.md#qemu
foreach(v QEMU MACHINE IMAGE EXPECT_STATUS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_qemu.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT DEFINED TIMEOUT)
  set(TIMEOUT 60)
endif()

# -icount shift=0: one virtual nanosecond per instruction, which makes the
# SysTick instruction counter exact and the run deterministic.
execute_process(
  COMMAND ${QEMU} -M ${MACHINE} -nographic -monitor null -serial null
          -semihosting-config enable=on,target=native -icount shift=0
          -kernel ${IMAGE}
  TIMEOUT ${TIMEOUT}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE out)
message("${out}")
if(DEFINED LOG_FILE)
  file(WRITE "${LOG_FILE}" "${out}")
endif()
if(NOT status STREQUAL "${EXPECT_STATUS}")
  message(FATAL_ERROR "qemu exit status '${status}', expected ${EXPECT_STATUS}")
endif()
if(DEFINED EXPECT_REGEX AND NOT out MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}'")
endif()
message("qemu exit status ${status} as expected")
