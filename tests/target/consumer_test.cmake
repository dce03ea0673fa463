# Installs a configured cvtplant build into a scratch prefix, then configures,
# builds and (if an emulator is given) runs tests/target/consumer against it
# with find_package(cvtplant). docs/build.md#find-package
#   cmake -DBUILD_DIR=... -DWORK_DIR=... [-DTOOLCHAIN=...]
#         [-DRUN="qemu;args" | -DRUN_NATIVE=ON] -P consumer_test.cmake
foreach(v BUILD_DIR WORK_DIR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "consumer_test.cmake: -D${v}=... is required")
  endif()
endforeach()
get_filename_component(src ${CMAKE_CURRENT_LIST_DIR}/consumer ABSOLUTE)
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
set(tc)
if(DEFINED TOOLCHAIN AND NOT TOOLCHAIN STREQUAL "")
  set(tc -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN})
endif()
run(${CMAKE_COMMAND} -S ${src} -B ${WORK_DIR}/build -G Ninja ${tc}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
file(GLOB exe ${WORK_DIR}/build/consumer ${WORK_DIR}/build/consumer.elf)
if(RUN_NATIVE OR (DEFINED RUN AND NOT RUN STREQUAL ""))
  run(${RUN} ${exe})
  if(NOT last_output MATCHES "consumer OK")
    message(FATAL_ERROR "consumer did not report OK")
  endif()
endif()
message("consumer project built against ${prefix}")
