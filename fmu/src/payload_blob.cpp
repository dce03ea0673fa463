// The FMU payload (payload_main.cpp) inside the program that writes FMUs:
// `cvtplant fmu` needs no file beside it. CVT_FMU_PAYLOAD is the payload's
// path in the build tree (fmu/CMakeLists.txt).
#ifndef CVT_FMU_PAYLOAD
#error "CVT_FMU_PAYLOAD: the path of the payload zip"
#endif

__asm__(
    ".section .rodata.cvt_fmu_payload,\"a\",@progbits\n"
    ".balign 16\n"
    ".globl cvt_fmu_payload_begin\n"
    ".hidden cvt_fmu_payload_begin\n"
    "cvt_fmu_payload_begin:\n"
    ".incbin \"" CVT_FMU_PAYLOAD "\"\n"
    ".globl cvt_fmu_payload_end\n"
    ".hidden cvt_fmu_payload_end\n"
    "cvt_fmu_payload_end:\n"
    ".byte 0\n"
    ".previous\n");
