# Sanitizer builds (docs/ci.md). One interface target, penumbra_sanitize, holds
# the flags; link_libraries() hands it to every target defined after this file
# is included -- the library, each per-ISA object library, the CLI, the tests,
# the benchmarks and the fuzz targets -- because every link must carry the
# runtime, and code compiled without the checks is code nobody checks. The one
# exception is chosen per target (PENUMBRA_UNINSTRUMENTED, below).
#
#   -DPENUMBRA_SANITIZE=address,undefined   gcc or clang; the CI's sanitizer job
#   -DPENUMBRA_FUZZ=ON                      clang; adds fuzzer-no-link (coverage
#                                           counters) and builds tests/fuzz
#
# -fno-sanitize-recover=all: a UBSan finding aborts the process instead of
# printing and carrying on, so a test or a fuzz run fails on it.
add_library(penumbra_sanitize INTERFACE)
if(PENUMBRA_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PENUMBRA_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  if(NOT PENUMBRA_SANITIZE)
    set(PENUMBRA_SANITIZE address,undefined)
  endif()
endif()
if(PENUMBRA_SANITIZE)
  set(_penumbra_compile_sanitizers ${PENUMBRA_SANITIZE})
  if(PENUMBRA_FUZZ)
    string(APPEND _penumbra_compile_sanitizers ",fuzzer-no-link")
  endif()
  # A target with PENUMBRA_UNINSTRUMENTED set (the test sources and their float64
  # references in tests/support: drivers of the instrumented code, like Debian's
  # uninstrumented GoogleTest beside them) compiles without the checks and still
  # links the runtime (docs/ci.md, cut 12).
  set(_penumbra_instrumented "$<NOT:$<BOOL:$<TARGET_PROPERTY:PENUMBRA_UNINSTRUMENTED>>>")
  target_compile_options(penumbra_sanitize INTERFACE
                         "$<${_penumbra_instrumented}:-fsanitize=${_penumbra_compile_sanitizers};-fno-sanitize-recover=all>"
                         -fno-omit-frame-pointer)
  target_link_options(penumbra_sanitize INTERFACE -fsanitize=${PENUMBRA_SANITIZE})
  # BUILD_INTERFACE: the installed package does not name this build-only
  # target; the install test's consumer, which links the instrumented library
  # and so needs the same runtime, gets the flag itself (tests/install_test.cmake).
  link_libraries($<BUILD_INTERFACE:penumbra_sanitize>)
  set(PENUMBRA_CONSUMER_CXX_FLAGS "-fsanitize=${PENUMBRA_SANITIZE}")
endif()
