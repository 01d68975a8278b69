// penumbra.reference: the measuring stick from Python (penumbra/reference.h):
// the built-in scenes, their shadow maps, receivers and ray-traced ground
// truth as numpy arrays (over the library's images, no copy), and the error
// metrics on numpy arrays (read in place where the layout allows).
#include "reference_module.h"

#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "numpy_views.h"
#include "penumbra/reference.h"

namespace penumbra::python {
namespace {

namespace ref = penumbra::reference;

ref::SceneSet scene_set(const std::string& name)
{
    if (name == "opaque") return ref::SceneSet::Opaque;
    if (name == "deep") return ref::SceneSet::Deep;
    if (name == "all") return ref::SceneSet::All;
    refuse("scenes", "set", "scene set '" + name + "' is none of 'opaque', 'deep', 'all'");
}

// A metric of one-channel arrays: each a view of the caller's memory
// where it can be, an Image only to the metric.
template <double (*Metric)(const Image&, const Image&, const Image*)>
double metric(const py::object& estimate, const py::object& truth, const py::object& mask, const char* op)
{
    py::array estimate_keep, truth_keep, mask_keep;
    const InputImage e(input_view(estimate, op, "estimate", estimate_keep), op, "estimate");
    const InputImage t(input_view(truth, op, "truth", truth_keep), op, "truth");
    std::optional<InputImage> m;
    if (!mask.is_none()) m.emplace(input_view(mask, op, "mask", mask_keep), op, "mask");
    return Metric(e.image(), t.image(), m ? &m->image() : nullptr);
}

template <double (*Metric)(const Image&, const Image&, const Image*)>
void def_metric(py::module_& m, const char* name, const char* doc)
{
    m.def(
        name,
        [name](const py::object& estimate, const py::object& truth, const py::object& mask) {
            return metric<Metric>(estimate, truth, mask, name);
        },
        py::arg("estimate"), py::arg("truth"), py::arg("mask") = py::none(), doc);
}

}  // namespace

void add_reference(py::module_& parent)
{
    py::module_ m = parent.def_submodule("reference", "Scenes, ground truth and metrics (penumbra/reference.h).");
    py::class_<ref::Scene>(m, "Scene", "A reference scene (penumbra/reference/scene.h).")
        .def("to_json", [](const ref::Scene& s) { return ref::scene_to_json(s); });
    m.def("scenes", [](const std::string& set) { return ref::builtin_scene_names(scene_set(set)); },
          py::arg("set") = "opaque", "The built-in scenes' names: 'opaque', 'deep' or 'all'.");
    m.def("scene", [](const std::string& name) { return ref::builtin_scene(name); }, py::arg("name"));
    m.def("scene_from_json", [](const std::string& text) { return ref::scene_from_json(text); }, py::arg("text"));

    m.def("render_shadow_map",
          [](const ref::Scene& s, int width, int height) { return to_numpy(ref::render_shadow_map(s, width, height)); },
          py::arg("scene"), py::arg("width"), py::arg("height"),
          "The light's depth map (H, W) in [0, 1] (first surface; 1 where the ray meets nothing).");
    m.def(
        "render_receivers",
        [](const ref::Scene& s, int width, int height) {
            ref::Receivers r = ref::render_receivers(s, width, height);
            py::dict d;
            d["light_uvz"] = to_numpy(std::move(r.light_uvz));
            d["world_position"] = to_numpy(std::move(r.world_position));
            d["normal"] = to_numpy(std::move(r.normal));
            d["view_depth"] = to_numpy(std::move(r.view_depth));
            d["hit"] = to_numpy(std::move(r.hit));
            d["mask"] = to_numpy(std::move(r.mask));
            return d;
        },
        py::arg("scene"), py::arg("width"), py::arg("height"),
        "What the view camera sees: a dict of light_uvz (3, H, W), world_position, normal (3, H, W), view_depth,\n"
        "hit, mask (H, W) (penumbra/reference/render.h).");
    m.def(
        "ground_truth",
        [](const ref::Scene& s, int width, int height, int strata) {
            const ref::Receivers r = ref::render_receivers(s, width, height);
            ref::GroundTruthOptions options;
            options.strata = strata;
            Image truth;
            {
                py::gil_scoped_release unlocked;
                truth = ref::ground_truth(s, r, options);
            }
            return to_numpy(std::move(truth));
        },
        py::arg("scene"), py::arg("width"), py::arg("height"), py::arg("strata") = ref::GroundTruthOptions{}.strata,
        "The visible fraction of the light (H, W) at the receivers render_receivers gives for this size,\n"
        "by stratified ray casting (strata x strata samples per receiver).");

    def_metric<&ref::rmse>(m, "rmse", "sqrt(mean((estimate - truth)^2)) where mask > 0.5 (every pixel without one).");
    def_metric<&ref::p99_abs_error>(m, "p99_abs_error", "The 99th percentile of |estimate - truth| (nearest rank).");
    def_metric<&ref::light_leaking>(m, "light_leaking", "Mean of max(estimate - truth, 0) where truth < 0.05.");
    def_metric<&ref::over_darkening>(m, "over_darkening", "Mean of max(truth - estimate, 0) where truth > 0.95.");
}

}  // namespace penumbra::python
