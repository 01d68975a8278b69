// DistanceGrid and its file format (docs/sdf.md, "Grid files").
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "penumbra/error.h"
#include "penumbra/exr_io.h"  // detail::write_file_atomically
#include "penumbra/input_file.h"
#include "penumbra/sdf.h"

namespace penumbra {
namespace {

constexpr char kMagic[8] = {'P', 'N', 'S', 'D', 'F', 'G', 'R', '1'};
constexpr std::size_t kHeaderBytes = 8 + 3 * 4 + 4 * 4;
constexpr std::size_t kMaxNodes = std::size_t(std::numeric_limits<std::int32_t>::max());

bool finite(SdfVec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The header's fields, as stored.
struct Header {
    std::int32_t n[3];
    float origin[3];
    float voxel;
};

// The format is little-endian; so are the machines this builds for.
static_assert(std::endian::native == std::endian::little, "grid files are little-endian");

void put(std::string& bytes, const void* data, std::size_t size) { bytes.append(static_cast<const char*>(data), size); }

std::string header_bytes(const DistanceGrid& grid)
{
    Header h{{grid.nx(), grid.ny(), grid.nz()},
             {float(grid.origin().x), float(grid.origin().y), float(grid.origin().z)},
             float(grid.voxel_size())};
    std::string bytes(kMagic, sizeof kMagic);
    put(bytes, h.n, sizeof h.n);
    put(bytes, h.origin, sizeof h.origin);
    put(bytes, &h.voxel, sizeof h.voxel);
    return bytes;
}

[[noreturn]] void bad_file(ErrorCategory category, const std::string& path, const std::string& what)
{
    throw Error(category, "read_distance_grid", path + ": " + what);
}

Header read_header(const InputFile& in, const std::string& path)
{
    char bytes[kHeaderBytes] = {};
    if (!in.read_at(0, bytes, sizeof bytes) || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
        bad_file(ErrorCategory::Io, path, "not a penumbra distance grid (no PNSDFGR1 header)");
    Header h{};
    std::memcpy(h.n, bytes + 8, sizeof h.n);
    std::memcpy(h.origin, bytes + 8 + sizeof h.n, sizeof h.origin);
    std::memcpy(&h.voxel, bytes + 8 + sizeof h.n + sizeof h.origin, sizeof h.voxel);
    return h;
}

void check_header(const Header& h, const std::string& path, std::uintmax_t file_bytes)
{
    const char* axes[] = {"nx", "ny", "nz"};
    for (int a = 0; a < 3; ++a)
        if (h.n[a] < 2)
            bad_file(ErrorCategory::InvalidData, path, std::string(axes[a]) + " is " + std::to_string(h.n[a]) +
                                                           "; a grid needs at least 2 nodes per axis");
    // Each axis is below 2^31, so a product of two fits in 64 bits; the third
    // factor is checked by division first, so the product cannot wrap (with
    // nx = 2^22, ny = nz = 2^21 it is 2^64, which wrapped to 0 here once).
    const std::uint64_t plane = std::uint64_t(h.n[0]) * std::uint64_t(h.n[1]);
    if (plane > kMaxNodes || std::uint64_t(h.n[2]) > kMaxNodes / plane)
        bad_file(ErrorCategory::InvalidData, path,
                 std::to_string(h.n[0]) + "x" + std::to_string(h.n[1]) + "x" + std::to_string(h.n[2]) +
                     " is more than 2^31 - 1 nodes");
    const std::uint64_t nodes = plane * std::uint64_t(h.n[2]);
    if (!(std::isfinite(h.voxel) && h.voxel > 0.0f))
        bad_file(ErrorCategory::InvalidData, path,
                 "voxel size is " + std::to_string(h.voxel) + "; it must be finite and > 0");
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(h.origin[a])) bad_file(ErrorCategory::InvalidData, path, "the origin is not finite");
    if (file_bytes != kHeaderBytes + 4 * nodes)
        bad_file(ErrorCategory::Io, path,
                 "is " + std::to_string(file_bytes) + " bytes; a " + std::to_string(h.n[0]) + "x" +
                     std::to_string(h.n[1]) + "x" + std::to_string(h.n[2]) + " grid takes " +
                     std::to_string(kHeaderBytes + 4 * nodes) + " (truncated or not a grid)");
}

void check_nodes(const DistanceGrid& grid, const std::string& path)
{
    for (int k = 0; k < grid.nz(); ++k)
        for (int j = 0; j < grid.ny(); ++j)
            for (int i = 0; i < grid.nx(); ++i)
                if (!std::isfinite(grid.at(i, j, k)))
                    bad_file(ErrorCategory::InvalidData, path,
                             "node (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                                 ") is " + std::to_string(grid.at(i, j, k)) + "; distances must be finite");
}

}  // namespace

DistanceGrid::DistanceGrid(int nx, int ny, int nz, SdfVec3 origin, double voxel_size)
{
    const std::string op = "DistanceGrid";
    require(nx >= 2 && ny >= 2 && nz >= 2, op,
            "a grid needs at least 2 nodes per axis (got " + std::to_string(nx) + "x" + std::to_string(ny) + "x" +
                std::to_string(nz) + ")");
    require(std::size_t(nx) * std::size_t(ny) * std::size_t(nz) <= kMaxNodes, op, "more than 2^31 - 1 nodes");
    require(std::isfinite(voxel_size) && voxel_size > 0.0 && float(voxel_size) > 0.0f, op,
            "voxel size must be finite and > 0 (got " + std::to_string(voxel_size) + ")");
    require(finite(origin), op, "the origin must be finite");
    nx_ = nx;
    ny_ = ny;
    nz_ = nz;
    origin_[0] = float(origin.x);
    origin_[1] = float(origin.y);
    origin_[2] = float(origin.z);
    voxel_ = float(voxel_size);
    storage_ = AlignedBuffer(size() * sizeof(float));
}

SdfVec3 DistanceGrid::upper() const noexcept
{
    return {origin_[0] + double(voxel_) * (nx_ - 1), origin_[1] + double(voxel_) * (ny_ - 1),
            origin_[2] + double(voxel_) * (nz_ - 1)};
}

void write_distance_grid(const std::string& path, const DistanceGrid& grid)
{
    require(!grid.empty(), "write_distance_grid", "the grid is empty");
    detail::write_file_atomically(path, "write_distance_grid", [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        const std::string header = header_bytes(grid);
        out.write(header.data(), std::streamsize(header.size()));
        out.write(reinterpret_cast<const char*>(grid.data()), std::streamsize(grid.size() * sizeof(float)));
        out.close();
        if (!out) throw Error(ErrorCategory::Io, "write_distance_grid", "cannot write " + path);
    });
}

// The file's size (fstat of the opened file) must be exactly what the header
// implies, and the node count is bounded, before the grid is allocated.
DistanceGrid read_distance_grid(const std::string& path)
{
    const InputFile in = open_input_file(path, "read_distance_grid");
    const Header h = read_header(in, path);
    check_header(h, path, in.size());
    DistanceGrid grid(h.n[0], h.n[1], h.n[2], {h.origin[0], h.origin[1], h.origin[2]}, h.voxel);
    if (!in.read_at(kHeaderBytes, grid.data(), grid.size() * sizeof(float)))
        bad_file(ErrorCategory::Io, path, "cannot read the distances (truncated)");
    check_nodes(grid, path);
    return grid;
}

}  // namespace penumbra
