# The OpenCL seed (cl/program_seed.h): after the library is built,
# penumbra_cl_seed builds every kernel entry's program once on this machine's
# OpenCL device into penumbra-cl-seed/ beside libpenumbra, installed beside it
# in lib/. A first run on a machine with the same device and driver then loads
# its kernels instead of compiling them (docs/opencl_startup.md has the
# figures and the step's cost). No device here: the step says so, makes an
# empty seed and the build goes on.
#
# The step depends on what decides the binaries (the embedded kernel sources
# and the cl/ code that keys, builds, launches and stores them), not on every
# relink of the library (LINK_DEPENDS_NO_SHARED), since it rebuilds all
# programs from source. Off in the sanitizer and fuzz trees (.ci/), which test
# the source build and would run the driver under the sanitizers at build time.
option(PENUMBRA_CL_SEED "Build the OpenCL programs once at build time, installed beside the library" ON)
if(NOT PENUMBRA_OPENCL OR NOT PENUMBRA_CL_SEED)
  return()
endif()

add_executable(penumbra_cl_seed cl/seed/make_seed.cpp)
target_link_libraries(penumbra_cl_seed PRIVATE penumbra penumbra_warnings OpenCL::OpenCL)
target_include_directories(penumbra_cl_seed PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(penumbra_cl_seed PRIVATE CL_HPP_TARGET_OPENCL_VERSION=120
                           CL_HPP_MINIMUM_OPENCL_VERSION=120 CL_HPP_ENABLE_EXCEPTIONS)
set_target_properties(penumbra_cl_seed PROPERTIES LINK_DEPENDS_NO_SHARED ON)

set(PENUMBRA_CL_SEED_DIR ${CMAKE_CURRENT_BINARY_DIR}/penumbra-cl-seed)  # beside libpenumbra.so (cl/program_seed.h)
file(GLOB PENUMBRA_CL_SEED_INPUTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/cl/*.cpp
     ${CMAKE_CURRENT_SOURCE_DIR}/cl/*.h)
add_custom_command(
  OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/penumbra-cl-seed.stamp
  COMMAND penumbra_cl_seed ${PENUMBRA_CL_SEED_DIR}
  COMMAND ${CMAKE_COMMAND} -E touch ${CMAKE_CURRENT_BINARY_DIR}/penumbra-cl-seed.stamp
  DEPENDS penumbra_cl_seed ${PENUMBRA_EMBEDDED_KERNELS} ${PENUMBRA_CL_SEED_INPUTS}
  COMMENT "Making the OpenCL seed: every kernel built once on this machine's device"
  VERBATIM)
add_custom_target(penumbra_cl_seed_binaries ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/penumbra-cl-seed.stamp)

install(DIRECTORY ${PENUMBRA_CL_SEED_DIR}/ DESTINATION ${CMAKE_INSTALL_LIBDIR}/penumbra-cl-seed COMPONENT penumbra)
