#include "bench_inputs.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <numeric>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "simd/cpu_kernels.h"  // supported_isas()

namespace penumbra::bench {
namespace {

constexpr int kCells = 16;            // occluder grid per side
constexpr float kOccluderShare = 0.6f; // of a cell's side: 0.36 of the area

bool in_occluder(int x, int y, int size)
{
    const int cell = size / kCells;
    const int side = int(float(cell) * kOccluderShare);
    const int margin = (cell - side) / 2;
    const int cx = x % cell, cy = y % cell;
    return cx >= margin && cx < margin + side && cy >= margin && cy < margin + side;
}

Image make_depth_map(int size)
{
    Image depth(size, size, 1);
    const float inv = 1.0f / float(size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            // Gentle slopes, so that windows have a non-zero variance.
            const float s = float(x) * inv, t = float(y) * inv;
            depth.at(0, x, y) = in_occluder(x, y, size) ? 0.25f + 0.05f * s : 0.75f + 0.05f * s + 0.05f * t;
        }
    return depth;
}

// `step` texels of the map per receiver, about the map's centre: 1 puts one
// receiver at every texel centre.
Image make_receivers(int size, float step = 1.0f)
{
    Image r(size, size, 3);
    const float inv = 1.0f / float(size), start = 0.5f * (1.0f - step);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            r.at(0, x, y) = start + step * (float(x) + 0.5f) * inv;
            r.at(1, x, y) = start + step * (float(y) + 0.5f) * inv;
            r.at(2, x, y) = 0.5f + 0.1f * float(y) * inv;
        }
    return r;
}

Image shuffle_pixels(const Image& in)
{
    const std::size_t n = std::size_t(in.width()) * std::size_t(in.height());
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::shuffle(order.begin(), order.end(), std::mt19937_64(20261204));
    Image out(in.width(), in.height(), in.channels());
    for (std::size_t i = 0; i < n; ++i) {
        const int x = int(i % std::size_t(in.width())), y = int(i / std::size_t(in.width()));
        const int sx = int(order[i] % std::size_t(in.width())), sy = int(order[i] / std::size_t(in.width()));
        for (int c = 0; c < in.channels(); ++c) out.at(c, x, y) = in.at(c, sx, sy);
    }
    return out;
}

template <class T, class Make>
const T& cached(std::map<int, T>& cache, int key, Make&& make)
{
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, make()).first;
    return it->second;
}

}  // namespace

const Image& depth_map(int size)
{
    static std::map<int, Image> cache;
    return cached(cache, size, [&] { return make_depth_map(size); });
}

const Image& receivers(int size)
{
    static std::map<int, Image> cache;
    return cached(cache, size, [&] { return make_receivers(size); });
}

const Image& shuffled_receivers(int size)
{
    static std::map<int, Image> cache;
    return cached(cache, size, [&] { return shuffle_pixels(receivers(size)); });
}

const Image& magnified_receivers(int size)
{
    static std::map<int, Image> cache;
    return cached(cache, size, [&] { return make_receivers(size, kMagnifiedStep); });
}

std::string best_cpu_backend()
{
    const std::vector<std::string_view> isas = cpu::supported_isas();
    return isas.empty() ? std::string("scalar") : std::string(isas.back());
}

const MomentTable& moment_table(int size, Precision precision)
{
    static std::map<int, MomentTable> cache;
    const int key = size * 2 + (precision == Precision::Exact);
    return cached(cache, key, [&] {
        return build_moment_table(context(best_cpu_backend()), depth_map(size), 2, precision);
    });
}

const CopyBuffers& copy_buffers(std::size_t bytes)
{
    static std::map<std::size_t, CopyBuffers> cache;
    auto it = cache.find(bytes);
    if (it != cache.end()) return it->second;
    const std::size_t rounded = (bytes + kAlignment - 1) / kAlignment * kAlignment;
    auto* src = static_cast<std::byte*>(std::aligned_alloc(kAlignment, rounded));
    auto* dst = static_cast<std::byte*>(std::aligned_alloc(kAlignment, rounded));
    if (!src || !dst) throw std::bad_alloc();
    // Touch every page, as the table build's input is: no page fault is timed.
    std::memset(src, 0x3c, rounded);
    std::memset(dst, 0, rounded);
    // Kept to the end of the process, like the other inputs.
    return cache.emplace(bytes, CopyBuffers{src, dst, bytes}).first->second;
}

Context& context(const std::string& backend)
{
    static std::map<std::string, Context> cache;
    auto it = cache.find(backend);
    if (it != cache.end()) return it->second;
    return cache.emplace(backend, Context(testing::backend_options(backend))).first->second;
}

}  // namespace penumbra::bench
