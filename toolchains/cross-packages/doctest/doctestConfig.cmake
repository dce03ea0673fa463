# doctest for cross builds (selected by toolchains/aarch64-linux-gnu.cmake).
#
# doctest is header-only, so the host's /usr/include/doctest works for any
# target. But Debian's own doctestConfig.cmake puts /usr/include on the
# include path, which would place the host's glibc headers in front of the
# cross sysroot's. This config exposes only the doctest directory, through a
# symlink in a staging directory of the build tree.
set(_cvt_doctest_host_dir /usr/include/doctest)
if(NOT EXISTS ${_cvt_doctest_host_dir}/doctest.h)
  set(doctest_FOUND FALSE)
  set(doctest_NOT_FOUND_MESSAGE "doctest headers not found in ${_cvt_doctest_host_dir} (apt-get install doctest-dev)")
  return()
endif()
set(_cvt_stage ${CMAKE_BINARY_DIR}/cvt-cross-include)
file(MAKE_DIRECTORY ${_cvt_stage})
if(NOT EXISTS ${_cvt_stage}/doctest)
  file(CREATE_LINK ${_cvt_doctest_host_dir} ${_cvt_stage}/doctest SYMBOLIC)
endif()
if(NOT TARGET doctest::doctest)
  add_library(doctest::doctest INTERFACE IMPORTED)
  set_target_properties(doctest::doctest PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${_cvt_stage})
endif()
set(doctest_FOUND TRUE)
