# ctest: install penumbra into a scratch prefix, then configure, build and run
# a consumer project against it with find_package(penumbra CONFIG).
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DSCRATCH=... -DGENERATOR=... -DMAKE_PROGRAM=...
#       -DCXX_COMPILER=... [-DCXX_FLAGS=...] -DCOMPONENTS=<install components, comma-separated>
#       -DCONSUMER=<folder under tests/> [-DCORE_ONLY=1] [-DC_COMPILER=... -DC_CONSUMER=1]
#       -P install_test.cmake
# The consumer is configured with the parent build's generator, make program and
# compiler: CMake's default generator (Unix Makefiles) needs `make`, which a
# fresh Debian 12 root does not have (issue 11, defect 13), and a sanitizer
# build's library links only into a consumer built with the same -fsanitize flags.
#
# CORE_ONLY (with COMPONENTS=penumbra): the prefix must hold nothing of the
# reference component (no header, no library, no targets file, no
# penumbra::reference symbol in libpenumbra), and a consumer asking for
# COMPONENTS reference must be refused at configure time.
#
# C_CONSUMER: the consumer also builds `consumer_c`, a C program on
# penumbra/penumbra.h, which must run too.
file(REMOVE_RECURSE ${SCRATCH})
set(prefix ${SCRATCH}/prefix)
string(REPLACE "," ";" COMPONENTS "${COMPONENTS}")  # a list cannot pass through add_test whole
include(${CMAKE_CURRENT_LIST_DIR}/install_components.cmake)
install_components(${BUILD_DIR} ${prefix} ${COMPONENTS})

function(configure_consumer name binary_dir result)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/${name} -B ${binary_dir}
                          -G ${GENERATOR} -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}
                          -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
                          -DCMAKE_C_COMPILER=${C_COMPILER} "-DCMAKE_C_FLAGS=${CXX_FLAGS}"
                          -DCMAKE_PREFIX_PATH=${prefix} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  set(${result} ${rc} PARENT_SCOPE)
  set(${result}_output "${out}" PARENT_SCOPE)
endfunction()

if(CORE_ONLY)
  file(GLOB_RECURSE leaked RELATIVE ${prefix} ${prefix}/*reference* ${prefix}/*metrics* ${prefix}/*sdf_scene*)
  if(leaked)
    message(FATAL_ERROR "the core install holds reference files: ${leaked}")
  endif()
  file(GLOB libraries ${prefix}/lib*/libpenumbra.so*)
  find_program(NM nm)
  if(NM AND libraries)
    list(GET libraries 0 library)
    execute_process(COMMAND ${NM} -DC --defined-only ${library} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
    string(REGEX MATCHALL "[^\n]*penumbra::reference::[^\n]*" leaked_symbols "${symbols}")
    if(rc OR leaked_symbols)
      message(FATAL_ERROR "libpenumbra defines reference symbols (nm rc ${rc}): ${leaked_symbols}")
    endif()
  endif()
  configure_consumer(consumer_reference ${SCRATCH}/refused rc)
  if(NOT rc OR NOT rc_output MATCHES "reference")
    message(FATAL_ERROR "find_package(penumbra COMPONENTS reference) should fail without the component:\n${rc_output}")
  endif()
endif()

configure_consumer(${CONSUMER} ${SCRATCH}/build rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer failed: ${rc}\n${rc_output}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${SCRATCH}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
set(programs consumer)
if(C_CONSUMER)
  list(APPEND programs consumer_c)
endif()
foreach(program IN LISTS programs)
  execute_process(COMMAND ${SCRATCH}/build/${program} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "the consumer's check failed (${program}): ${rc}")
  endif()
endforeach()
file(REMOVE_RECURSE ${SCRATCH})
