// Python bindings (pybind11): a context, the method table's methods with
// their options, shading and the blur on numpy arrays, penumbra::Error as
// penumbra.Error. Arrays become views (penumbra/image_view.h) by their
// strides, so the library reads and writes numpy's memory in place where
// the layout allows (docs/integration.md, "Python").
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/context.h"
#include "penumbra/error.h"
#include "penumbra/image_view.h"
#include "penumbra/methods.h"
#include "numpy_views.h"
#include "reference_module.h"

namespace py = pybind11;
using penumbra::Error;
using penumbra::ErrorCategory;
using penumbra::python::input_view;
using penumbra::python::output_view;
using penumbra::python::refuse;

namespace {

// Options as keyword arguments: min_variance=... is the option min-variance.
std::vector<std::pair<std::string, std::string>> method_options(const py::kwargs& options)
{
    std::vector<std::pair<std::string, std::string>> given;
    for (const auto& [key, value] : options) {
        std::string name = py::str(key);
        for (char& c : name)
            if (c == '_') c = '-';
        given.emplace_back(name, std::string(py::str(value)));  // parsed as the tool's text
    }
    return given;
}

py::array shade(penumbra::Context& context, const std::string& name, const py::object& depth,
                const py::object& receivers, const py::object& out, const py::kwargs& options)
{
    const penumbra::Method& method = penumbra::find_method(name);
    const penumbra::MethodSettings settings = penumbra::parse_method_settings(method, method_options(options));
    py::array depth_keep, receivers_keep;
    const penumbra::ImageView map = input_view(depth, name, "depth", depth_keep);
    const penumbra::ImageView rx = input_view(receivers, name, "receivers", receivers_keep);
    auto [array, view] = output_view(out, {py::ssize_t(rx.height), py::ssize_t(rx.width)}, name);
    {
        py::gil_scoped_release unlocked;
        method.run(context, map, rx, settings, view);
    }
    return array;
}

penumbra::BilateralRange range_of(const std::string& name)
{
    if (name == "gaussian") return penumbra::BilateralRange::Gaussian;
    if (name == "threshold") return penumbra::BilateralRange::Threshold;
    refuse("cross_bilateral", "range", "range '" + name + "' is neither 'gaussian' nor 'threshold'");
}

penumbra::BilateralWindow window_of(const std::string& name)
{
    if (name == "square") return penumbra::BilateralWindow::Square;
    if (name == "disk") return penumbra::BilateralWindow::Disk;
    refuse("cross_bilateral", "window", "window '" + name + "' is neither 'square' nor 'disk'");
}

py::array blur(penumbra::Context& context, const py::object& mask, const py::object& guide_depth,
               const py::object& guide_normals, const py::object& out, int radius, float spatial_sigma,
               const std::string& range, bool relative, float depth_sigma, float depth_threshold,
               const std::string& window, bool separable, float normal_sigma)
{
    const std::string op = "cross_bilateral";
    const penumbra::BilateralOptions options{radius,      spatial_sigma,     range_of(range), relative,
                                             depth_sigma, depth_threshold, window_of(window), separable,
                                             normal_sigma};
    py::array mask_keep, guide_keep, normals_keep;
    const penumbra::ImageView m = input_view(mask, op, "mask", mask_keep);
    const penumbra::ImageView g = input_view(guide_depth, op, "guide-depth", guide_keep);
    std::optional<penumbra::ImageView> n;
    if (!guide_normals.is_none()) n = input_view(guide_normals, op, "guide-normals", normals_keep);
    std::vector<py::ssize_t> shape{py::ssize_t(m.height), py::ssize_t(m.width)};
    if (m.channels > 1 || mask_keep.ndim() == 3) shape.insert(shape.begin(), m.channels);
    auto [array, view] = output_view(out, shape, op);
    {
        py::gil_scoped_release unlocked;
        penumbra::cross_bilateral(context, m, g, options, view, n ? &*n : nullptr);
    }
    return array;
}

std::vector<std::string> method_names()
{
    std::vector<std::string> names;
    for (const penumbra::Method& m : penumbra::methods()) names.emplace_back(m.name);
    return names;
}

}  // namespace

PYBIND11_MODULE(penumbra, m)
{
    m.doc() = "penumbra: shadow filtering kernels (SIMD and OpenCL) on numpy arrays";

    static py::exception<Error> error(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            py::object instance = py::reinterpret_borrow<py::object>(error.ptr())(e.what());  // the type, called
            instance.attr("category") = std::string(penumbra::to_string(e.category()));
            instance.attr("operation") = e.operation();
            instance.attr("parameter") = e.parameter();
            PyErr_SetObject(error.ptr(), instance.ptr());
        }
    });

    py::class_<penumbra::Context>(m, "Context", "Owns the backend every operation runs on (penumbra/context.h).")
        .def(py::init([](const std::string& backend) {
                 return penumbra::Context(penumbra::ContextOptions{penumbra::parse_backend(backend), {}});
             }),
             py::arg("backend") = "auto", "backend: auto | simd | opencl | scalar")
        .def_property_readonly("backend", [](const penumbra::Context& c) { return penumbra::to_string(c.backend()); })
        .def_property_readonly("description", &penumbra::Context::description)
        .def_property_readonly("reason", &penumbra::Context::reason);

    m.def("methods", &method_names, "The method table's methods, by name.");
    m.def(
        "method_input",
        [](const std::string& method) {
            return std::string(penumbra::input_info(penumbra::find_method(method).input).flag);
        },
        py::arg("method"),
        "What the method reads: 'shadow-map' (shade's depth), or 'deep-map' and 'pismo-maps' (not from Python yet).");
    m.def("methods_help", [] { return penumbra::methods_help(); });
    m.def("options_help", [] { return penumbra::method_options_help(""); },
          "Every method option (pass as keyword arguments, '-' spelt '_').");
    m.def("shade", &shade, py::arg("context"), py::arg("method"), py::arg("depth"), py::arg("receivers"),
          py::kw_only(), py::arg("out") = py::none(),
          "Visibility (H, W) float32 of receivers (3, H, W) = u, v, z against the shadow map depth (H, W) in\n"
          "[0, 1] (float32, or uint16 read as value / 65535), through the method's build and shade steps.\n"
          "Options are keyword arguments (radius=3, min_variance=1e-5). `out`: write there in place.");
    const penumbra::BilateralOptions d;
    m.def("blur", &blur, py::arg("context"), py::arg("mask"), py::arg("guide_depth"),
          py::arg("guide_normals") = py::none(), py::kw_only(), py::arg("out") = py::none(),
          py::arg("radius") = d.radius, py::arg("spatial_sigma") = d.spatial_sigma, py::arg("range") = d.range == penumbra::BilateralRange::Threshold ? "threshold" : "gaussian",
          py::arg("relative") = d.relative, py::arg("depth_sigma") = d.depth_sigma,
          py::arg("depth_threshold") = d.depth_threshold, py::arg("window") = d.window == penumbra::BilateralWindow::Disk ? "disk" : "square",
          py::arg("separable") = d.separable, py::arg("normal_sigma") = d.normal_sigma,
          "The cross-bilateral blur of mask (H, W) or (C, H, W), C <= 4, guided by depth (H, W) and\n"
          "optionally normals (3, H, W) (penumbra/bilateral.h).");

    penumbra::python::add_reference(m);
}
