// Summed-area tables of depth moments (kernels/moment_table.h is the kernel).
//
// build_moment_table() turns a depth map (one channel, values in [0, 1]) into
// per-moment inclusive sums, from which any rectangle's mean depth, mean square
// depth (and, with 4 moments, the third and fourth moments) cost four reads.
//
// Precision::Exact (the default) is a "limb" table (kernels/moment_table.h):
// each value z^k of the float32 depth is rounded to 32 bits (2 limbs; 48 with
// 3) and every 16-bit limb summed in its own wrapping uint32 plane, so every
// window of at most 255 x 255 texels (radius 127) has sums exact to that
// rounding (1.2e-10 with 2 limbs) for maps of any size, 16384^2 included.
// Precision::Float sums z^k in float: its error grows with the map
// (docs/moment_table.md has the measured worst case).
#pragma once

#include <cstdint>

#include "penumbra/context.h"
#include "penumbra/depth_convention.h"
#include "penumbra/image.h"

namespace penumbra {

enum class Precision { Exact, Float };

inline constexpr int kExactMaxWindowArea = 65535;  // texels
inline constexpr int kExactMaxRadius = 127;        // (2r + 1)^2 <= 65535
// 16-bit limbs per value of an exact table: VSM's z, z^2 need 2 (docs/moment_table.md);
// MSM's z..z^4 and EVSM's warps 3 (docs/moments.md).
inline constexpr int kVsmLimbs = 2;
inline constexpr int kMomentLimbs = 3;

// What a table's values are (kernels/params.h, PN_TABLE_*): the powers z^k,
// or EVSM's warps with these exponents, of the normalised depth z, which
// the build converts from the map's convention `depth` where it loads a texel.
struct TableValues {
    int kind = 0;  // PN_TABLE_POWERS (0) or PN_TABLE_EVSM (1)
    float positive = 0.0f, negative = 0.0f;
    DepthConvention depth{};
};

// Where a table of this shape keeps its elements (4 bytes each): what a
// MomentTable allocates, and a device-resident one (penumbra/device_image.h).
struct MomentTableLayout {
    int pitch = 0;                        // elements between rows
    std::size_t plane_pitch = 0;          // elements between planes
    std::size_t storage_elements = 0;     // the lead before the origin included
    std::size_t origin_offset_bytes = 0;  // from the storage's start to the origin
};
MomentTableLayout moment_table_layout(int width, int height, int planes);

class MomentTable {
public:
    MomentTable() = default;
    // `limbs`: 16-bit limbs per value of an exact table (1 for the 16-bit
    // optimized MSM table, whose values are 16-bit steps); float tables have 1.
    MomentTable(int width, int height, int moments, Precision precision, int limbs = kVsmLimbs,
                TableValues values = {});

    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    int moments() const noexcept { return moments_; }
    Precision precision() const noexcept { return precision_; }
    int limbs() const noexcept { return limbs_; }
    int planes() const noexcept { return moments_ * limbs_; }
    const TableValues& values() const noexcept { return values_; }
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
    // The raw wrapped integer sum of plane `plane` of an exact table (no
    // decoding); 1-based: value k (1-based) limb l (0-based, most significant
    // first) is plane (k - 1) * limbs + l + 1.
    std::uint32_t exact_box_sum(int plane, int x0, int x1, int y0, int y1) const;

private:
    void zero_borders();

    int width_ = 0, height_ = 0, pitch_ = 0;
    std::size_t plane_pitch_ = 0;
    int moments_ = 0;
    int limbs_ = 1;
    Precision precision_ = Precision::Exact;
    TableValues values_{};
    AlignedBuffer storage_;
};

// Builds the table. Throws Error for an empty map, a map with more than one
// channel, non-finite depths or depths outside the convention's range ([0, 1]
// by default), a bad convention, moments not 2 or 4.
MomentTable build_moment_table(Context& context, const Image& depth, int moments = 2,
                               Precision precision = Precision::Exact, const DepthConvention& convention = {});

// The same into an existing table of the map's size (its moments and
// precision are kept): no allocation, for per-frame use. If it throws (a bad
// depth), the table's contents are unspecified.
void build_moment_table(Context& context, const Image& depth, MomentTable& table);

std::string to_string(Precision precision);
Precision parse_precision(const std::string& name);

}  // namespace penumbra
