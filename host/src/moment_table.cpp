#include "penumbra/moment_table.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <cstring>
#include <string>

#include "depth_conversion.h"
#include "host/backend/backend.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

// Elements before the origin: give the corner query of row -1, column -1
// (element -1) a zero to read, and put the origin 4 KiB into the storage, so
// that OpenCL can address it as a sub-buffer on any device (sub-buffer offsets
// must be multiples of CL_DEVICE_MEM_BASE_ADDR_ALIGN, at most 4 KiB in practice).
constexpr std::size_t kLead = 1024;

// Both precisions store 4-byte elements (float or uint32).
constexpr std::size_t kElementSize = 4;

void check_rectangle(const MomentTable& t, int k, int count, int x0, int x1, int y0, int y1)
{
    require(!t.empty(), "MomentTable::box_sum", "the table is empty");
    require(k >= 1 && k <= count, "MomentTable::box_sum",
            "moment " + std::to_string(k) + " is not in [1, " + std::to_string(count) + "]");
    require(0 <= x0 && x0 < x1 && x1 <= t.width() && 0 <= y0 && y0 < y1 && y1 <= t.height(),
            "MomentTable::box_sum", "rectangle [" + std::to_string(x0) + ", " + std::to_string(x1) + ") x [" +
                                        std::to_string(y0) + ", " + std::to_string(y1) +
                                        ") is empty or outside the map");
}

// Two zero elements after every row: the pair planes of a 3-limb table read
// the pair before their origin (corner (0, 0)), which is the last two
// elements of the limb-2 plane before them (kernels/moment_table.h, layout).
int table_pitch(int width) { return padded_pitch(width + 1); }

// Where plane `plane` (0-based: value plane / limbs, limb plane % limbs) of a
// table lives: the first element of its plane group and the elements per
// entry of the group (2 for a limb table's pair plane of limbs 0 and 1,
// interleaved; else 1), as kernels/moment_table.h lays them out.
struct PlaneSlot {
    std::size_t group;  // in plane pitches from the origin
    int stride, lane;
};
PlaneSlot plane_slot(int plane, int limbs)
{
    const int k = plane / limbs, l = plane % limbs;
    if (limbs == 1) return {std::size_t(plane), 1, 0};
    if (l < 2) return {std::size_t(k * limbs), 2, l};
    return {std::size_t(k * limbs + 2), 1, 0};
}

}  // namespace

MomentTableLayout moment_table_layout(int width, int height, int planes)
{
    MomentTableLayout layout;
    layout.pitch = table_pitch(width);
    layout.plane_pitch = std::size_t(layout.pitch) * std::size_t(height + 1);
    layout.storage_elements = kLead + layout.plane_pitch * std::size_t(planes);
    layout.origin_offset_bytes = kLead * kElementSize;
    return layout;
}

MomentTable::MomentTable(int width, int height, int moments, Precision precision, int limbs, TableValues values)
    : width_(width), height_(height), pitch_(table_pitch(width)),
      plane_pitch_(std::size_t(table_pitch(width)) * std::size_t(height + 1)), moments_(moments),
      limbs_(precision == Precision::Exact ? limbs : 1), precision_(precision), values_(values)
{
    require(width > 0 && height > 0, "MomentTable", "the map is empty");
    require(moments == 2 || moments == 4, "MomentTable",
            "moments must be 2 or 4 (got " + std::to_string(moments) + ")");
    require(limbs >= 1 && limbs <= 3, "MomentTable", "limbs must be 1, 2 or 3 (got " + std::to_string(limbs) + ")");
    storage_ = AlignedBuffer(storage_elements() * kElementSize, AlignedBuffer::Uninitialized{});
    zero_borders();
}

// The kernels write every entry of the table's rows and nothing else; the
// zeros the corner queries read (the lead before the origin, each plane's
// zero row, the padding after every row, which is the next row's column -1)
// are set here, in parallel, so that the fresh pages fault on every thread.
// A pair plane's rows hold 2 pitches of elements, its texels 2 W of them.
void MomentTable::zero_borders()
{
    std::byte* base = storage_.data();
    std::memset(base, 0, kLead * kElementSize);
    const std::size_t rows = std::size_t(height_ + 1) * std::size_t(planes());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t row = r.begin(); row < r.end(); ++row) {
            const std::size_t plane = row / std::size_t(height_ + 1), y = row % std::size_t(height_ + 1);
            const PlaneSlot slot = plane_slot(int(plane), limbs_);
            if (slot.lane != 0) continue;  // the pair plane's rows are zeroed with limb 0
            const std::size_t row_elements = std::size_t(slot.stride) * std::size_t(pitch_);
            std::byte* start = base + (kLead + slot.group * plane_pitch_ + y * row_elements) * kElementSize;
            const std::size_t from = y == 0 ? 0 : std::size_t(slot.stride) * std::size_t(width_);
            std::memset(start + from * kElementSize, 0, (row_elements - from) * kElementSize);
        }
    });
}

std::size_t MomentTable::storage_elements() const noexcept
{
    return moment_table_layout(width_, height_, planes()).storage_elements;
}

std::size_t MomentTable::origin_offset_bytes() const noexcept
{
    return moment_table_layout(width_, height_, planes()).origin_offset_bytes;
}

float* MomentTable::float_origin() noexcept { return reinterpret_cast<float*>(storage_.data()) + kLead; }
const float* MomentTable::float_origin() const noexcept
{
    return reinterpret_cast<const float*>(storage_.data()) + kLead;
}
std::uint32_t* MomentTable::exact_origin() noexcept { return reinterpret_cast<std::uint32_t*>(storage_.data()) + kLead; }
const std::uint32_t* MomentTable::exact_origin() const noexcept
{
    return reinterpret_cast<const std::uint32_t*>(storage_.data()) + kLead;
}

std::uint32_t MomentTable::exact_box_sum(int plane_index, int x0, int x1, int y0, int y1) const
{
    check_rectangle(*this, plane_index, planes(), x0, x1, y0, y1);
    require(precision_ == Precision::Exact, "MomentTable::exact_box_sum", "the table is not exact");
    const PlaneSlot slot = plane_slot(plane_index - 1, limbs_);
    const std::uint32_t* plane = exact_origin() + plane_pitch_ * slot.group + slot.lane;
    auto corner = [&](int x, int y) { return plane[(std::ptrdiff_t(y) * pitch_ + x - 1) * slot.stride]; };
    return (corner(x1, y1) - corner(x0, y1)) - (corner(x1, y0) - corner(x0, y0));
}

double MomentTable::box_sum(int k, int x0, int x1, int y0, int y1) const
{
    check_rectangle(*this, k, moments_, x0, x1, y0, y1);
    if (precision_ == Precision::Exact) {
        // Same decoding as sat_limb_box_sum() in kernels/moment_table.h.
        double unit = 1.0 / 65536.0, sum = 0.0;
        for (int l = 0; l < limbs_; ++l, unit /= 65536.0)
            sum += double(exact_box_sum((k - 1) * limbs_ + l + 1, x0, x1, y0, y1)) * unit;
        return sum;
    }
    const float* plane = float_origin() + plane_pitch_ * std::size_t(k - 1);
    auto corner = [&](int x, int y) { return double(plane[std::ptrdiff_t(y) * pitch_ + x - 1]); };
    return (corner(x1, y1) - corner(x0, y1)) - (corner(x1, y0) - corner(x0, y0));
}

static void check_depth_map_shape(const Image& depth)
{
    const std::string op = "build_moment_table";
    require(!depth.empty(), op, "depth", "the shadow map is empty (0 pixels)");
    require(depth.channels() == 1, op, "depth",
            "the shadow map must have one channel (depth), got " + std::to_string(depth.channels()));
}

// Builds, then reports the first bad depth if a kernel flagged one. The table
// is then incomplete, but the caller gets the error instead of it.
static void build_checked(Context& context, const Image& depth, MomentTable& table)
{
    std::vector<int> bad_rows(std::size_t(depth.height()), 0);
    context.impl().build_moment_table(depth, table, bad_rows.data());
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
        require_depths_in(depth, table.values().depth, "build_moment_table");
}

MomentTable build_moment_table(Context& context, const Image& depth, int moments, Precision precision,
                               const DepthConvention& convention)
{
    check_depth_map_shape(depth);
    check_depth_convention(convention, "build_moment_table");
    MomentTable table(depth.width(), depth.height(), moments, precision, kVsmLimbs, TableValues{0, 0, 0, convention});
    build_checked(context, depth, table);
    return table;
}

void build_moment_table(Context& context, const Image& depth, MomentTable& table)
{
    check_depth_map_shape(depth);
    require(!table.empty() && table.width() == depth.width() && table.height() == depth.height(),
            "build_moment_table", "the table is " + std::to_string(table.width()) + "x" +
                                      std::to_string(table.height()) + " but the map is " +
                                      std::to_string(depth.width()) + "x" + std::to_string(depth.height()) +
                                      "; allocate it as MomentTable(width, height, moments, precision)");
    build_checked(context, depth, table);
}

std::string to_string(Precision precision) { return precision == Precision::Exact ? "exact" : "float"; }

Precision parse_precision(const std::string& name)
{
    if (name == "exact") return Precision::Exact;
    if (name == "float") return Precision::Float;
    throw Error(ErrorCategory::InvalidArgument, "precision", "'" + name + "' is not exact or float");
}

namespace detail {

pn_dims dims_of(const Image& image)
{
    return {image.width(), image.height(), image.pitch(), int(image.plane_pitch())};
}

pn_dims dims_of(const MomentTable& table)
{
    return {table.width(), table.height(), table.pitch(), int(table.plane_pitch())};
}

SatParams sat_params(const Image& depth, const MomentTable& table, int column_rows, int band_height)
{
    SatParams p = sat_params(dims_of(depth), dims_of(table), table.moments(), table.limbs(), column_rows, band_height);
    p.encoding = table.values().kind;
    p.exponent_positive = table.values().positive;
    p.exponent_negative = table.values().negative;
    p.convention = kernel_conversion(table.values().depth);
    return p;
}

SatParams sat_params(pn_dims depth, pn_dims table, int moments, int limbs, int column_rows, int band_height)
{
    SatParams p{};
    p.depth = depth;
    p.table = table;
    p.moments = moments;
    p.limbs = limbs;
    p.band_height = band_height;
    const int pitch = padded_pitch(depth.width);
    p.columns = {depth.width, column_rows, pitch, pitch * column_rows};
    return p;
}

SatParams join_params(const EncodedSatParams& p)
{
    SatParams s{};
    s.depth = p.depth;
    s.table = p.table;
    s.columns = p.columns;
    s.moments = p.channels;
    s.limbs = 1;
    s.band_height = p.band_height;
    return s;
}

}  // namespace detail
}  // namespace penumbra
