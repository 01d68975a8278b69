// The method table: every shading method of the library as one entry (name,
// one line of description, the options it reads, its two steps: build from
// the shadow map, shade the receivers), and every
// option once (name, value, default, range, help). `penumbra shade`, `penumbra
// demo` and the benchmarks take method names, option parsing and help from
// here, and nowhere else (docs/architecture.md, "Adding a method").
//
// An option's name is also the library's parameter name (Error::parameter())
// of its check: a front end maps that name to its own spelling (the CLI: --name).
// Ranges come from penumbra/parameter_range.h, the same declarations the
// operations check against.
#pragma once

#include <any>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/context.h"
#include "penumbra/deep_lookup.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/depth_convention.h"
#include "penumbra/image.h"
#include "penumbra/image_view.h"
#include "penumbra/moments.h"
#include "penumbra/parameter_range.h"
#include "penumbra/soft_pcf.h"
#include "penumbra/pcf.h"
#include "penumbra/pismo.h"
#include "penumbra/pismo_files.h"

namespace penumbra {

// The values of every option; a method reads those it lists. The defaults are
// the operations' own (VsmOptions, MsmOptions, ...).
struct MethodSettings {
    int radius = VsmOptions{}.radius;
    // The table's element type. Not an option of the tool: the float tables
    // (with quantization Bits32) are kept for comparison, and benchmarks and
    // tests set it.
    Precision precision = Precision::Exact;
    float min_variance = kDefaultMinVariance;
    float bleed = 0.0f;
    float light_size = VssmOptions{}.light_size;
    std::optional<float> moment_bias{}, depth_bias{};  // unset: the method's default
    float plane_bias = MsmSoftOptions{}.plane_bias, plane_bias_max = MsmSoftOptions{}.plane_bias_max;
    Quantization quantization = Quantization::None;
    std::optional<float> positive_exponent{}, negative_exponent{};
    // pcss and burley (penumbra/soft_pcf.h).
    int blocker_samples = PcssOptions{}.blocker_samples, filter_samples = PcssOptions{}.filter_samples;
    float min_radius = BurleyOptions{}.min_radius, max_radius = BurleyOptions{}.max_radius;
    float bias_slope = BurleyOptions{}.bias_slope, falloff = BurleyOptions{}.falloff;
    float bias_slope_per_depth = BurleyOptions{}.bias_slope_per_depth;
    // The percentage-closer family (penumbra/pcf.h); depth_bias unset: kPcfDefaultDepthBias.
    BiasMode bias_mode = DepthBias{}.mode;
    float bias_min = DepthBias{}.min, bias_max = DepthBias{}.max, slope_scale = DepthBias{}.slope_scale;
    DerivativeSource derivatives = DepthBias{}.derivatives;
    int grid = PcfGaussOptions{}.grid;
    float sigma = PcfGaussOptions{}.sigma;
    int taps = PcfDiscOptions{}.taps;
    float disc_radius = PcfDiscOptions{}.radius;
    bool rotate = PcfDiscOptions{}.rotate;
    // Deep shadow map lookups (penumbra/deep_lookup.h); depth_bias unset: kDeepDefaultBias.
    DeepFilter deep_filter = DeepLookupOptions{}.filter;
    DeepSearch deep_search = DeepLookupOptions{}.search;
    // Pismo (penumbra/pismo.h): rays per shading point.
    int rays = PismoOptions{}.rays;
    // How a shadow map's depths and the receivers' z are stored (the methods
    // that read a shadow map; penumbra/depth_convention.h).
    DepthConvention depth_convention{};
};

// What a method's build step reads: a shadow map (one channel of depth in
// [0, 1], `penumbra shade --shadow-map`), a deep shadow map (`--deep-map`) or
// Pismo's light mesh and layered maps (`--pismo-maps`, or rendered from
// `--scene`: penumbra/pismo_files.h).
enum class MethodInput { ShadowMap, DeepMap, PismoMapSet };

// Each input once: the library parameter its errors name (Error::parameter())
// and the front end's name for it (the CLI's flag, without "--").
struct MethodInputInfo {
    MethodInput input;
    const char* parameter;  // "depth", "deep-map", "maps"
    const char* flag;       // "shadow-map", "deep-map", "pismo-maps"
    const char* what;       // "shadow map", "deep shadow map", "set of Pismo maps"
};
const std::vector<MethodInputInfo>& method_inputs();
const MethodInputInfo& input_info(MethodInput input);

struct Method;

// What a method's build step made of a shadow map, for its shade step: its
// table (a MomentTable, MsmTable, EvsmTable, ...), or none for a method that
// reads the map itself. It refers to the map, which must outlive it.
class PreparedMap {
public:
    explicit PreparedMap(const Image& map) : map_(&map) {}
    explicit PreparedMap(const DeepShadowMap& map) : deep_map_(&map) {}
    // Pismo's build step: the maps ready for the shadow-ray test (bled, and
    // the maximum-depth variant derived when asked), from the stored set.
    PreparedMap(const PismoMapSet& set, PismoMaps maps)
        : pismo_set_(&set), table_(std::make_shared<const PismoMaps>(std::move(maps)))
    {
    }
    template <class Table>
    PreparedMap(const Image& map, Table&& table)
        : map_(&map), table_(std::make_shared<const std::decay_t<Table>>(std::forward<Table>(table)))
    {
    }

    const Image& map() const { return *map_; }  // a ShadowMap method's
    const DeepShadowMap& deep_map() const { return *deep_map_; }  // a DeepMap method's
    const PismoMapSet& pismo_set() const { return *pismo_set_; }  // a PismoMapSet method's
    // Whether the build step made a table (a box method at a small radius
    // makes none: its shade step sums the window from the map).
    bool has_table() const { return table_.has_value(); }
    // The table the build step made, as its own type (throws std::bad_any_cast
    // for another: a method's two steps disagree, a defect).
    template <class Table>
    const Table& table() const
    {
        return *std::any_cast<const std::shared_ptr<const Table>&>(table_);
    }
    // Keeps `owner` (what map() refers to: a view's InputImage) as long as
    // this prepared map and its copies live.
    void hold(std::shared_ptr<const void> owner) { owner_ = std::move(owner); }

private:
    std::shared_ptr<const void> owner_;
    const Image* map_ = nullptr;
    const DeepShadowMap* deep_map_ = nullptr;
    const PismoMapSet* pismo_set_ = nullptr;
    std::any table_;  // std::shared_ptr<const Table>: shared, never copied
};

struct MethodOption {
    const char* name;    // "radius": the parameter its check names
    const char* value;   // what the value looks like in help: "R", "P,N"
    const char* help;    // one line; range, default and methods are appended by method_help()
    const char* fallback;                   // the default, as help shows it
    const ParameterRange* range = nullptr;  // the numeric range, when it has one
    // Accepted, and ignored, by a method that does not read it (the shared
    // window and filter options); any other option is refused there.
    bool shared = false;
    // Sets the option in `settings` from `text`; throws Error naming the
    // parameter for text that is no value or a value out of range.
    void (*parse)(const Method& method, const std::string& text, MethodSettings& settings) = nullptr;
    // The parameters this option sets, when they are not just `name`.
    std::vector<std::string_view> parameters{};
};

struct Method {
    const char* name;      // "vsm"
    const char* summary;   // one line
    std::vector<std::string_view> reads;  // the options it uses, by name
    // The build step of a ShadowMap method: the method's table from `map`
    // (one channel, depth in [0, 1]), or none (prepare_map) for a method that
    // reads the map itself. Null for a DeepMap method.
    PreparedMap (*prepare)(Context& context, const Image& map, const MethodSettings& settings);
    // The shade step: visibility on the receivers' grid (`receivers`: u, v,
    // z) into `out` (one channel, the receivers' size).
    void (*shade)(Context& context, const PreparedMap& prepared, const Image& receivers,
                  const MethodSettings& settings, Image& out);

    // What the build step reads; a DeepMap method's build step is prepare_deep.
    MethodInput input = MethodInput::ShadowMap;
    PreparedMap (*prepare_deep)(Context& context, const DeepShadowMap& map, const MethodSettings& settings) = nullptr;
    // A PismoMapSet method's build step (its receivers: world positions, receiver_channels).
    PreparedMap (*prepare_pismo)(Context& context, const PismoMapSet& set, const MethodSettings& settings) = nullptr;

    // Both steps, into a new image, as `penumbra shade` and `penumbra demo`
    // run a method; a benchmark times each step alone. Each throws
    // Error(InvalidArgument, parameter "method") for a method of the other input.
    Image run(Context& context, const Image& map, const Image& receivers, const MethodSettings& settings) const;
    Image run(Context& context, const DeepShadowMap& map, const Image& receivers,
              const MethodSettings& settings) const;

    // The two steps on views of the caller's memory (penumbra/image_view.h):
    // read and written in place where the layout allows, else one copy each
    // (docs/integration.md). The map view may be 16-bit (value / 65535); the
    // prepared map refers to the map's memory when it was read in place, so
    // that memory must outlive it. `out`: one channel, the receivers' size,
    // disjoint from the receivers. Errors name the parameters "depth",
    // "receivers" and "out".
    PreparedMap prepare_view(Context& context, const ImageView& map, const MethodSettings& settings) const;
    void shade_view(Context& context, const PreparedMap& prepared, const ImageView& receivers,
                    const MethodSettings& settings, const MutableImageView& out) const;
    void run(Context& context, const ImageView& map, const ImageView& receivers, const MethodSettings& settings,
             const MutableImageView& out) const;
    Image run(Context& context, const PismoMapSet& set, const Image& receivers, const MethodSettings& settings) const;
    // Both steps on a one-texel map and receivers, on a backend that builds
    // or loads its programs on first use (OpenCL), so that this method's are
    // ready before a real run (start_context's `prepare`); nothing on the
    // CPU backends. The kernels launched are the ones run() launches, found
    // by running it rather than listed. May throw what run() throws.
    void warm_up(Context& context, const MethodSettings& settings) const;
};

// The receivers' channels a method run with `settings` reads from a file:
// u, v, z, and dzdu, dzdv when a bias takes its derivatives from channels.
std::vector<std::string> receiver_channels(const MethodSettings& settings);
// The same for `method`: a PismoMapSet method reads world positions P.x, P.y,
// P.z (render-scene's RX.exr channels), the others as above.
std::vector<std::string> receiver_channels(const Method& method, const MethodSettings& settings);

// The build step of a method that reads the shadow map itself: keeps no table.
PreparedMap prepare_map(Context& context, const Image& map, const MethodSettings& settings);

const std::vector<Method>& methods();
const std::vector<MethodOption>& method_options();

// Throws Error(InvalidArgument, parameter "method") naming the valid methods.
const Method& find_method(std::string_view name);
// The option that sets `parameter` (an Error::parameter()), or null.
const MethodOption* option_for_parameter(std::string_view parameter);
// The names joined by `separator`: "vsm|vssm|msm|msm-soft|evsm2|evsm4".
std::string method_names(std::string_view separator);

// Settings for `method` from (option name, text) pairs: each text parsed and
// range-checked (the operations check the same again at run time, and what
// depends on the map, a light too large for its table), an option the method
// cannot use refused (shared ones are checked and ignored). Throws
// Error(InvalidArgument) naming the option's parameter.
MethodSettings parse_method_settings(const Method& method,
                                     const std::vector<std::pair<std::string, std::string>>& given);

// The help lines of every option: "  --radius R   box radius ...", with
// `flag_prefix` before each name ("--" for the CLI).
std::string method_options_help(std::string_view flag_prefix);
// One line per method: "  vsm       variance shadow maps ...".
std::string methods_help();

}  // namespace penumbra
