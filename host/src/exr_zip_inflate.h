// ZIP and ZIPS chunks of an EXR inflated with libdeflate instead of zlib, for
// read_exr's decode pass (exr_validate.cpp). Inflating was a third of a
// `penumbra shade` run (issue 10 item 10: the receivers' file holds ten float
// channels, all of which are inflated to read three); libdeflate inflates the
// same deflate stream about twice as fast (docs/benchmarks.md, "The tool
// against its I/O").
#pragma once

#include <OpenEXR/openexr.h>

namespace penumbra::detail {

// For a pipeline set up by exr_decoding_choose_default_routines: replaces its
// decompress step when `compression` is ZIP or ZIPS, leaves it otherwise. The
// replacement fails (EXR_ERR_CORRUPT_CHUNK) exactly where the core's does: a
// stream that is not zlib, or that inflates to any size but the chunk's.
void inflate_zip_with_libdeflate(exr_decode_pipeline_t& decode, exr_compression_t compression);

}  // namespace penumbra::detail
