// Views of a caller's memory (penumbra/image_view.h) through the method table
// and the blur, on every backend: a planar view at a padded or packed pitch
// (read and written in place), an interleaved view and a 16-bit depth map
// (one copy each) give what the same data gives through Image, bit for bit;
// bytes outside a view's pixels are never written; bad views are typed errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/error.h"
#include "penumbra/image_view.h"
#include "penumbra/methods.h"
#include "support/backends.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

constexpr std::byte kSentinel{0xA5};

// A caller's buffer holding `image` at the given pitches (0: packed), every
// other byte the sentinel, and ending at the last pixel: a read past it
// would leave the allocation.
struct Buffer {
    std::vector<std::byte> bytes;
    ImageView view;
    MutableImageView output;
};

// A plane pitch of 0 means packed planes (image_view.h).
std::size_t planes_apart(std::size_t plane_pitch, std::size_t row_pitch, int height)
{
    return plane_pitch ? plane_pitch : row_pitch * std::size_t(height);
}

// Where channel c of pixel (x, y) lies in a buffer (plane_pitch resolved).
std::size_t offset_in(ChannelLayout layout, std::size_t row_pitch, std::size_t plane_pitch, int channels, int c,
                      int x, int y)
{
    if (layout == ChannelLayout::Interleaved) return y * row_pitch + (std::size_t(x) * channels + c) * 4;
    return c * plane_pitch + y * row_pitch + std::size_t(x) * 4;
}

std::size_t span_of(int width, int height, int channels, std::size_t element, std::size_t row_pitch,
                    std::size_t plane_pitch, ChannelLayout layout)
{
    plane_pitch = planes_apart(plane_pitch, row_pitch, height);
    const std::size_t row = std::size_t(width) * element * (layout == ChannelLayout::Interleaved ? channels : 1);
    const std::size_t plane = std::size_t(height - 1) * row_pitch + row;
    return layout == ChannelLayout::Interleaved ? plane : std::size_t(channels - 1) * plane_pitch + plane;
}

Buffer float_buffer(const Image& image, std::size_t row_pitch, std::size_t plane_pitch, ChannelLayout layout,
                    std::size_t misalign = 0)
{
    const int w = image.width(), h = image.height(), n = image.channels();
    Buffer b;
    b.bytes.assign(misalign + span_of(w, h, n, 4, row_pitch, plane_pitch, layout), kSentinel);
    std::byte* base = b.bytes.data() + misalign;
    b.view.plane_pitch = b.output.plane_pitch = plane_pitch;
    plane_pitch = planes_apart(plane_pitch, row_pitch, h);
    for (int c = 0; c < n; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                std::memcpy(base + offset_in(layout, row_pitch, plane_pitch, n, c, x, y), &image.row(c, y)[x], 4);
    b.view.data = base;
    b.output.data = base;
    b.view.width = b.output.width = w;
    b.view.height = b.output.height = h;
    b.view.channels = b.output.channels = n;
    b.view.row_pitch = b.output.row_pitch = row_pitch;
    b.view.layout = b.output.layout = layout;
    return b;
}

// An output buffer of the sentinel, its pixels to be written.
Buffer output_buffer(int width, int height, int channels, std::size_t row_pitch, std::size_t plane_pitch,
                     ChannelLayout layout)
{
    Image blank(width, height, channels);
    Buffer b = float_buffer(blank, row_pitch, plane_pitch, layout);
    plane_pitch = planes_apart(plane_pitch, row_pitch, height);
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)  // a NaN: the kernel must overwrite it
                std::memset(b.bytes.data() + offset_in(layout, row_pitch, plane_pitch, channels, c, x, y), 0xFF, 4);
    return b;
}

// The buffer read back as an image; every byte outside the pixels must still be the sentinel.
Image read_back(const Buffer& b, const char* what)
{
    const MutableImageView& v = b.output;
    Image image(v.width, v.height, v.channels);
    std::vector<bool> pixel(b.bytes.size(), false);
    const std::size_t plane_pitch = planes_apart(v.plane_pitch, v.row_pitch, v.height);
    for (int c = 0; c < v.channels; ++c)
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x) {
                const std::size_t at = offset_in(v.layout, v.row_pitch, plane_pitch, v.channels, c, x, y);
                std::memcpy(&image.row(c, y)[x], b.bytes.data() + at, 4);
                for (int i = 0; i < 4; ++i) pixel[at + i] = true;
            }
    for (std::size_t i = 0; i < b.bytes.size(); ++i)
        if (!pixel[i]) {
            EXPECT_EQ(b.bytes[i], kSentinel) << what << ": byte " << i << " outside the pixels was written";
        }
    return image;
}

void expect_same(const Image& expected, const Image& got, const std::string& what)
{
    ASSERT_EQ(expected.channels(), got.channels()) << what;
    for (int c = 0; c < expected.channels(); ++c)
        for (int y = 0; y < expected.height(); ++y)
            for (int x = 0; x < expected.width(); ++x)
                ASSERT_EQ(expected.at(c, x, y), got.at(c, x, y))
                    << what << ": channel " << c << " pixel (" << x << ", " << y << ")";
}

struct Size {
    int width, height;
};
// Odd sizes and widths around every lane count here (1, N-1, N, N+1).
std::vector<Size> sizes()
{
    std::vector<Size> s{{1, 1}, {7, 3}};
    for (int w : testing::lane_edge_widths())
        if (w > 1 && w < 40) s.push_back({w, 2});
    return s;
}

bool reads_shadow_map(const Method& m) { return m.input == MethodInput::ShadowMap; }

// The choice itself: a planar float view is the caller's memory; an
// interleaved, 16-bit or misaligned one a planar copy; an output copy
// reaches the view only at commit().
TEST(ImageViewChoice, BorrowsPlanarFloatAndCopiesTheRest)
{
    const Image image = testing::random_depth(5, 3, 61);
    Buffer planar = float_buffer(image, 5 * 4 + 4, 0, ChannelLayout::Planar);
    const InputImage borrowed(planar.view, "test", "in");
    EXPECT_FALSE(borrowed.copied());
    EXPECT_EQ(static_cast<const void*>(borrowed.image().plane(0)), planar.view.data);
    EXPECT_EQ(borrowed.image().pitch(), 6);
    const Image copy = borrowed.image();  // a copy of a borrowed image owns its pixels
    EXPECT_FALSE(copy.borrowed());
    expect_same(image, copy, "copy");

    const Buffer interleaved = float_buffer(testing::random_depth(5, 3, 62), 5 * 4, 0, ChannelLayout::Interleaved);
    EXPECT_FALSE(InputImage(interleaved.view, "test", "in").copied());  // one channel: planar
    Image two(5, 3, 2);
    const Buffer pairs = float_buffer(two, 5 * 2 * 4, 0, ChannelLayout::Interleaved);
    EXPECT_TRUE(InputImage(pairs.view, "test", "in").copied());

    Buffer out = output_buffer(5, 3, 2, 5 * 2 * 4, 0, ChannelLayout::Interleaved);
    OutputImage output(out.output, "test", "out");
    ASSERT_TRUE(output.copied());
    for (int c = 0; c < 2; ++c) output.image().fill(c, float(c + 1));
    EXPECT_TRUE(std::isnan(read_back(out, "before commit").at(0, 0, 0)));
    output.commit();
    const Image written = read_back(out, "after commit");
    EXPECT_EQ(written.at(0, 4, 2), 1.0f);
    EXPECT_EQ(written.at(1, 4, 2), 2.0f);
}

class ImageViews : public ::testing::TestWithParam<std::string> {};

// Planar float views at a padded pitch (12 bytes past the row, a pitch of no
// cache-line multiple, gaps between planes, a pointer of no 16-byte
// alignment) and at a packed pitch: read and
// written in place, the same bits as through Image, for every method.
PN_BACKEND_TEST(ImageViews, PlanarViewsAreReadInPlaceAndMatchImage)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const Size s : sizes()) {
        const Image map = testing::random_depth(s.width + 2, s.height + 1, 11);
        const Image receivers = testing::scattered_receivers(s.width, s.height, 0.0f, 1.0f, 0.0f, 1.0f, 12);
        for (const std::size_t pad : {std::size_t(12), std::size_t(0)}) {
            const std::size_t map_pitch = map.width() * 4 + pad, rec_pitch = s.width * 4 + pad;
            const std::size_t rec_plane = pad ? rec_pitch * s.height + 20 : 0;
            const Buffer m = float_buffer(map, map_pitch, 0, ChannelLayout::Planar);
            // Padded: the receivers 4 bytes off the allocation's alignment too
            // (whole floats, so still in place; OpenCL wraps such a pointer as well).
            const Buffer r = float_buffer(receivers, rec_pitch, rec_plane, ChannelLayout::Planar, pad ? 4 : 0);
            Buffer out = output_buffer(s.width, s.height, 1, rec_pitch, 0, ChannelLayout::Planar);
            ASSERT_TRUE(in_place(m.view) && in_place(r.view) && in_place(out.output));
            for (const Method& method : methods()) {
                if (!reads_shadow_map(method)) continue;
                const std::string what = std::string(method.name) + " " + std::to_string(s.width) + "x" +
                                         std::to_string(s.height) + " pad " + std::to_string(pad);
                const Image expected = method.run(ctx, map, receivers, MethodSettings{});
                method.run(ctx, m.view, r.view, MethodSettings{}, out.output);
                expect_same(expected, read_back(out, what.c_str()), what);
            }
        }
    }
}

// Interleaved receivers (u, v, z per pixel), and a map whose pointer is no
// whole float: one copy in each; the one-channel output is planar.
PN_BACKEND_TEST(ImageViews, InterleavedAndMisalignedViewsAreCopiedAndMatchImage)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image map = testing::random_depth(9, 5, 21);
    const Image receivers = testing::scattered_receivers(7, 3, 0.0f, 1.0f, 0.0f, 1.0f, 22);
    const Buffer m = float_buffer(map, 9 * 4 + 2, 0, ChannelLayout::Planar, 1);
    const Buffer r = float_buffer(receivers, 7 * 3 * 4 + 8, 0, ChannelLayout::Interleaved);
    Buffer out = output_buffer(7, 3, 1, 7 * 4, 0, ChannelLayout::Interleaved);
    EXPECT_FALSE(in_place(m.view));
    EXPECT_FALSE(in_place(r.view));
    EXPECT_TRUE(in_place(out.output));  // one channel: interleaved is planar
    for (const Method& method : methods()) {
        if (!reads_shadow_map(method)) continue;
        const Image expected = method.run(ctx, map, receivers, MethodSettings{});
        method.run(ctx, m.view, r.view, MethodSettings{}, out.output);
        expect_same(expected, read_back(out, method.name), method.name);
    }
}

// A 16-bit depth map is read as value / 65535; the prepared map holds its
// copy, so the caller's buffer may go before the shade step.
PN_BACKEND_TEST(ImageViews, SixteenBitDepthMatchesItsFloatValues)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 17, h = 6;
    std::mt19937 rng(31);
    std::vector<std::uint16_t> depth16(std::size_t(w) * h);
    Image as_float(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto q = std::uint16_t(rng() & 0xFFFF);
            depth16[std::size_t(y) * w + x] = q;
            as_float.at(0, x, y) = float(q) / 65535.0f;
        }
    const Image receivers = testing::scattered_receivers(5, 4, 0.0f, 1.0f, 0.0f, 1.0f, 32);
    for (const Method& method : methods()) {
        if (!reads_shadow_map(method)) continue;
        PreparedMap prepared = [&] {
            std::vector<std::uint16_t> caller = depth16;
            ImageView v;
            v.data = caller.data();
            v.width = w;
            v.height = h;
            v.type = PixelType::UInt16;
            EXPECT_FALSE(in_place(v));
            return method.prepare_view(ctx, v, MethodSettings{});
        }();
        Image got(5, 4, 1);
        method.shade_view(ctx, prepared, receivers, MethodSettings{}, got);
        expect_same(method.run(ctx, as_float, receivers, MethodSettings{}), got, method.name);
    }
}

// The blur on a padded planar 2-channel mask and on an interleaved
// 3-channel mask written into an interleaved output (one copy out).
PN_BACKEND_TEST(ImageViews, BlurViewsMatchImage)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const Size s : sizes()) {
        for (const int channels : {2, 3}) {
            const ChannelLayout layout = channels == 2 ? ChannelLayout::Planar : ChannelLayout::Interleaved;
            Image mask = testing::random_depth(s.width, s.height * channels, 41);
            Image planes(s.width, s.height, channels);
            for (int c = 0; c < channels; ++c)
                for (int y = 0; y < s.height; ++y)
                    for (int x = 0; x < s.width; ++x) planes.at(c, x, y) = mask.at(0, x, y + c * s.height);
            const Image guide = testing::random_depth(s.width, s.height, 42);
            const std::size_t row = std::size_t(s.width) * 4 * (channels == 3 ? 3 : 1);
            const Buffer m = float_buffer(planes, row + 8, 0, layout);
            const Buffer g = float_buffer(guide, s.width * 4 + 4, 0, ChannelLayout::Planar);
            Buffer out = output_buffer(s.width, s.height, channels, row + 8, 0, layout);
            BilateralOptions options;
            options.radius = 1;
            const Image expected = cross_bilateral(ctx, planes, guide, options);
            cross_bilateral(ctx, m.view, g.view, options, out.output);
            const std::string what = std::to_string(channels) + " channels " + std::to_string(s.width);
            expect_same(expected, read_back(out, what.c_str()), what);
        }
    }
}

template <class Call>
void expect_view_error(Call call, const std::string& parameter, const std::string& says)
{
    try {
        call();
        ADD_FAILURE() << "no error for " << parameter << " (" << says << ")";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::InvalidArgument) << e.what();
        EXPECT_EQ(e.parameter(), parameter) << e.what();
        EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
}

PN_BACKEND_TEST(ImageViews, BadViewsAreTypedErrors)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image map = testing::random_depth(8, 4, 51);
    const Image receivers = testing::scattered_receivers(6, 2, 0.0f, 1.0f, 0.0f, 1.0f, 52);
    Image out(6, 2, 1);
    const Method& vsm = find_method("vsm");
    const MethodSettings settings;
    const auto shade = [&](ImageView m, ImageView r, MutableImageView o) { vsm.run(ctx, m, r, settings, o); };

    ImageView null_map = map;
    null_map.data = nullptr;
    expect_view_error([&] { shade(null_map, receivers, out); }, "depth", "null data pointer");
    ImageView empty = receivers;
    empty.width = 0;
    expect_view_error([&] { shade(map, empty, out); }, "receivers", "at least one pixel");
    ImageView short_rows = receivers;
    short_rows.row_pitch = 6 * 4 - 4;
    expect_view_error([&] { shade(map, short_rows, out); }, "receivers", "shorter than a row");
    ImageView short_planes = receivers;
    short_planes.plane_pitch = receivers.pitch() * 4;  // one row
    expect_view_error([&] { shade(map, short_planes, out); }, "receivers", "shorter than a plane");
    ImageView no_channels = receivers;
    no_channels.channels = 0;
    expect_view_error([&] { shade(map, no_channels, out); }, "receivers", "channels");
    MutableImageView short_out = out;
    short_out.row_pitch = 8;
    expect_view_error([&] { shade(map, receivers, short_out); }, "out", "shorter than a row");

    // An output over an input: the kernels read what they would overwrite.
    Image mask(6, 2, 1), guide(6, 2, 1);
    MutableImageView over_mask = mask;
    expect_view_error([&] { cross_bilateral(ctx, ImageView(mask), ImageView(guide), {}, over_mask); }, "out",
                      "overlaps");
    ImageView null_guide = guide;
    null_guide.data = nullptr;
    Image blurred(6, 2, 1);
    expect_view_error([&] { cross_bilateral(ctx, ImageView(mask), null_guide, {}, MutableImageView(blurred)); },
                      "guide-depth", "null data pointer");
}

INSTANTIATE_TEST_SUITE_P(Backends, ImageViews, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
