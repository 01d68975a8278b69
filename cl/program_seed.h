// The seed: program binaries made at build time on the build machine's OpenCL
// device (cl/seed/make_seed.cpp, run by CMake), installed beside the library,
// so that a first run on a machine with the same device and driver loads its
// kernels instead of compiling them (seconds with PoCL: docs/opencl_startup.md).
//
// Runtime::build reads it when the user's cache misses and never writes it.
// Its files are ordinary program cache files (program_cache.h): named by the
// key, which hashes the source, options, device, driver and platform, and
// checked against their header and checksum, so a seed made for another
// device is never found (another key), a damaged one is a miss, and a binary
// the driver refuses anyway (CL_INVALID_BINARY) falls back to the source build.
#pragma once

#include <string>

namespace penumbra::cl_backend {

// The folder's name beside libpenumbra (the build tree and lib/ of an install).
inline constexpr const char* kSeedFolderName = "penumbra-cl-seed";

// $PENUMBRA_CL_SEED_DIR if set (empty: no seed), else kSeedFolderName in the
// folder of the libpenumbra this code runs in; empty when it cannot be found.
std::string seed_directory();

}  // namespace penumbra::cl_backend
