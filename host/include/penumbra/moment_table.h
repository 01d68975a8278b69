// Summed-area tables of depth moments (kernels/moment_table.h is the kernel).
//
// build_moment_table() turns a depth map (one channel, values in [0, 1]) into
// per-moment inclusive sums, from which any rectangle's mean depth, mean square
// depth (and, with 4 moments, the third and fourth moments) cost four reads.
//
// Precision::Exact (the default) quantizes depth to 16 bits and sums in
// wrapping uint32: every window of at most 65537 texels (255 x 255, radius
// 127) has exact sums for maps of any size, 16384^2 included. Precision::Float
// sums z^k in float: faster to use in float pipelines, but its error grows with
// the map (docs/moment_table.md has the measured worst case).
#pragma once

#include <cstdint>

#include "penumbra/context.h"
#include "penumbra/image.h"

namespace penumbra {

enum class Precision { Exact, Float };

inline constexpr int kExactMaxWindowArea = 65537;  // texels
inline constexpr int kExactMaxRadius = 127;        // (2r + 1)^2 <= 65537

class MomentTable {
public:
    MomentTable() = default;
    MomentTable(int width, int height, int moments, Precision precision);

    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    int moments() const noexcept { return moments_; }
    Precision precision() const noexcept { return precision_; }
    bool empty() const noexcept { return moments_ == 0; }
    // Elements between rows and between planes (kernels/params.h, SatParams).
    int pitch() const noexcept { return pitch_; }
    std::size_t plane_pitch() const noexcept { return plane_pitch_; }

    // The table's origin: the zero row before row 0. Element -1 is valid (zero).
    float* float_origin() noexcept;
    const float* float_origin() const noexcept;
    std::uint32_t* exact_origin() noexcept;
    const std::uint32_t* exact_origin() const noexcept;
    std::size_t storage_elements() const noexcept;  // the lead before the origin included
    std::size_t origin_offset_bytes() const noexcept;
    const std::byte* storage() const noexcept { return storage_.data(); }
    std::byte* storage() noexcept { return storage_.data(); }

    // Sum of moment k (1-based) over texels [x0, x1) x [y0, y1), on the host, in
    // the units of z^k (exact tables decoded). For tests and for users who need
    // a few values; throws Error for an empty or out-of-range rectangle.
    double box_sum(int k, int x0, int x1, int y0, int y1) const;
    // The raw wrapped integer sum of an exact table (no decoding).
    std::uint32_t exact_box_sum(int k, int x0, int x1, int y0, int y1) const;

private:
    void zero_borders();

    int width_ = 0, height_ = 0, pitch_ = 0;
    std::size_t plane_pitch_ = 0;
    int moments_ = 0;
    Precision precision_ = Precision::Exact;
    AlignedBuffer storage_;
};

// Builds the table. Throws Error for an empty map, a map with more than one
// channel, non-finite depths or depths outside [0, 1], moments not 2 or 4.
MomentTable build_moment_table(Context& context, const Image& depth, int moments = 2,
                               Precision precision = Precision::Exact);

// The same into an existing table of the map's size (its moments and
// precision are kept): no allocation, for per-frame use. If it throws (a bad
// depth), the table's contents are unspecified.
void build_moment_table(Context& context, const Image& depth, MomentTable& table);

std::string to_string(Precision precision);
Precision parse_precision(const std::string& name);

}  // namespace penumbra
