#include "exr_zip_inflate.h"

#include <libdeflate.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>

namespace penumbra::detail {
namespace {

struct FreeDecompressor {
    void operator()(libdeflate_decompressor* d) const noexcept { libdeflate_free_decompressor(d); }
};

// One decompressor per thread: chunks decode in parallel (exr_validate.cpp,
// for_each_chunk), and a decompressor holds 32 KiB of tables worth keeping.
struct Inflater {
    std::unique_ptr<libdeflate_decompressor, FreeDecompressor> decompressor{libdeflate_alloc_decompressor()};
};

// OpenEXR's ZIP filter, undone (ImfZipCompressor.cpp, OpenEXRCore
// internal_zip.c): the encoder stored byte differences d[i] = b[i] - b[i-1]
// + 128 (mod 256), of the bytes reordered so that the even-indexed ones come
// first, then the odd-indexed ones.
void undo_predictor_and_reorder(std::uint8_t* t, std::size_t n, std::uint8_t* out)
{
    for (std::size_t i = 1; i < n; ++i) t[i] = std::uint8_t(t[i - 1] + t[i] - 128);
    const std::uint8_t* evens = t;
    const std::uint8_t* odds = t + (n + 1) / 2;
    for (std::size_t i = 0; i + 1 < n; i += 2) {
        out[i] = *evens++;
        out[i + 1] = *odds++;
    }
    if (n % 2) out[n - 1] = *evens;
}

exr_result_t inflate_chunk(exr_decode_pipeline_t* decode)
{
    const std::size_t packed = decode->chunk.packed_size, unpacked = decode->chunk.unpacked_size;
    if (packed == 0) return EXR_ERR_SUCCESS;  // as the core: nothing stored, nothing to unpack
    auto* out = static_cast<std::uint8_t*>(decode->unpacked_buffer);
    if (out == nullptr) return EXR_ERR_OUT_OF_MEMORY;
    // An encoder stores a chunk raw when compressing would not shrink it.
    if (packed == unpacked) {
        if (decode->unpacked_buffer != decode->packed_buffer) std::memcpy(out, decode->packed_buffer, unpacked);
        return EXR_ERR_SUCCESS;
    }
    thread_local Inflater inflater;
    // Per chunk, as the core's own scratch: a buffer kept per thread would
    // stay resident through the kernels and count in the tool's peak memory.
    const std::unique_ptr<std::uint8_t[]> scratch(new (std::nothrow) std::uint8_t[unpacked]);
    if (!inflater.decompressor || !scratch) return EXR_ERR_OUT_OF_MEMORY;
    std::size_t inflated = 0;
    const libdeflate_result result = libdeflate_zlib_decompress(inflater.decompressor.get(), decode->packed_buffer,
                                                                packed, scratch.get(), unpacked, &inflated);
    if (result != LIBDEFLATE_SUCCESS || inflated != unpacked) return EXR_ERR_CORRUPT_CHUNK;
    undo_predictor_and_reorder(scratch.get(), unpacked, out);
    return EXR_ERR_SUCCESS;
}

}  // namespace

void inflate_zip_with_libdeflate(exr_decode_pipeline_t& decode, exr_compression_t compression)
{
    if (decode.decompress_fn && (compression == EXR_COMPRESSION_ZIP || compression == EXR_COMPRESSION_ZIPS))
        decode.decompress_fn = &inflate_chunk;
}

}  // namespace penumbra::detail
