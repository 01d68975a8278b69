// numpy arrays as views and Images as numpy arrays (numpy_views.h).
#include "numpy_views.h"

#include <optional>

#include "penumbra/error.h"

namespace penumbra::python {
namespace {

struct Strides {
    py::ssize_t channels, height, width;   // extents
    py::ssize_t plane, row, pixel;         // strides in bytes
};

// A dimension of extent 1 has no meaningful stride (numpy may give it any):
// the pixel's is then the element's; rows get theirs in view_of.
Strides strides_of(const py::array& a)
{
    const int last = int(a.ndim()) - 1;
    const py::ssize_t pixel = a.shape(last) == 1 ? a.itemsize() : a.strides(last);
    if (a.ndim() == 2) return {1, a.shape(0), a.shape(1), a.shape(0) * a.strides(0), a.strides(0), pixel};
    return {a.shape(0), a.shape(1), a.shape(2), a.strides(0), a.strides(1), pixel};
}

// The view of `a` if its strides are one the library takes; nullopt otherwise.
template <class View>
std::optional<View> view_of(const py::array& a, void* data)
{
    const Strides s = strides_of(a);
    const py::ssize_t item = a.itemsize();
    const py::ssize_t row = s.height == 1 ? s.width * s.pixel : s.row;
    View v;
    v.data = data;
    v.width = int(s.width);
    v.height = int(s.height);
    v.channels = int(s.channels);
    if (row <= 0) return std::nullopt;
    v.row_pitch = std::size_t(row);
    if (s.pixel == item) {
        const py::ssize_t plane = s.channels == 1 ? row * s.height : s.plane;
        if (plane <= 0) return std::nullopt;
        v.plane_pitch = std::size_t(plane);
        v.layout = ChannelLayout::Planar;
        return v;
    }
    if (s.pixel == s.channels * item && (s.plane == item || s.channels == 1)) {
        v.layout = ChannelLayout::Interleaved;
        return v;
    }
    return std::nullopt;
}

void check_rank(const py::array& a, const std::string& op, const std::string& parameter)
{
    if (a.ndim() != 2 && a.ndim() != 3)
        refuse(op, parameter,
               "'" + parameter + "' has " + std::to_string(a.ndim()) + " dimensions; give (H, W) or (C, H, W)");
}

}  // namespace

[[noreturn]] void refuse(const std::string& op, const std::string& parameter, const std::string& message)
{
    throw Error(ErrorCategory::InvalidArgument, op, parameter, message);
}

// An input array as a view; `keep` holds the array (or its float32 or
// contiguous copy, for another dtype or strides no view can express).
ImageView input_view(const py::object& object, const std::string& op, const std::string& parameter,
                               py::array& keep)
{
    keep = py::array::ensure(object);
    if (!keep) refuse(op, parameter, "'" + parameter + "' is not an array");
    if (!keep.dtype().is(py::dtype::of<float>()) && !keep.dtype().is(py::dtype::of<std::uint16_t>()))
        keep = py::array_t<float, py::array::forcecast>::ensure(keep);
    check_rank(keep, op, parameter);
    auto view = view_of<ImageView>(keep, const_cast<void*>(keep.data()));
    if (!view) {
        keep = py::array::ensure(keep, py::array::c_style);
        view = view_of<ImageView>(keep, const_cast<void*>(keep.data()));
    }
    view->type = keep.dtype().is(py::dtype::of<float>()) ? PixelType::Float32 : PixelType::UInt16;
    return *view;
}

// `out` as given (written in place: float32, writable, a layout a view
// takes), or a new float32 array of `shape`.
std::pair<py::array, MutableImageView> output_view(const py::object& out, std::vector<py::ssize_t> shape,
                                                            const std::string& op)
{
    py::array a = out.is_none() ? py::array_t<float>(shape) : py::array::ensure(out);
    const std::string hint = "; give a writable float32 array of shape (H, W) or (C, H, W), planar or "
                             "an (H, W, C) array's transpose(2, 0, 1)";
    if (!a || !a.dtype().is(py::dtype::of<float>()) || !a.writeable()) refuse(op, "out", "'out' is not writable float32" + hint);
    check_rank(a, op, "out");
    const auto view = view_of<MutableImageView>(a, a.mutable_data());
    if (!view) refuse(op, "out", "'out' has strides no view can express" + hint);
    return {a, *view};
}

py::array to_numpy(Image image)
{
    auto* owned = new Image(std::move(image));
    const py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
    const auto f = py::ssize_t(sizeof(float));
    const py::ssize_t w = owned->width(), h = owned->height(), pitch = owned->pitch() * f;
    if (owned->channels() == 1) return py::array_t<float>({h, w}, {pitch, f}, owned->plane(0), owner);
    const py::ssize_t planes = py::ssize_t(owned->plane_pitch()) * f;
    return py::array_t<float>({py::ssize_t(owned->channels()), h, w}, {planes, pitch, f}, owned->plane(0), owner);
}

}  // namespace penumbra::python
