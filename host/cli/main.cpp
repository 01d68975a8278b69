// penumbra: the command-line tool. Exit status: 0 success, 2 bad input (bad
// options, unreadable or invalid files, a backend this machine lacks), 1 any
// other failure (a backend error, a bug). Errors are one line on stderr.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "sdf_command.h"
#include "penumbra/error.h"

namespace {

const char* kUsage =
    "penumbra: shadow-filtering kernels on SIMD CPUs and OpenCL\n"
    "\n"
    "usage: penumbra <command> [options]\n"
    "  info [--json] [--verbose]   backends, the one Auto chooses and why, CPU ISAs, OpenCL devices\n"
    "  shade --method vsm|vssm|msm|msm-soft|evsm2|evsm4 --shadow-map SM.exr --receivers RX.exr --out OUT.exr [options]\n"
    "                              filter a shadow map for a set of receivers (shade --help)\n"
    "  example --out DIR           write a small synthetic shadow map and receivers to DIR\n"
    "  render-scene NAME --shadow-map SM.exr --receivers RX.exr --truth GT.exr [options]\n"
    "                              a reference scene and its ray-traced ground truth\n"
    "  demo [--quick] [--out DIR]  every method on every scene: images, CSV, time-vs-error chart\n"
    "  blur --in MASK.exr --guide DEPTH.exr --out OUT.exr [options]\n"
    "                              cross-bilateral blur of a mask, stopping at depth edges (blur --help)\n"
    "  sdf-shade (--scene S | --grid G) --receivers RX.exr --out OUT.exr [options]\n"
    "                              sphere-traced distance-field soft shadows (sdf-shade --help)\n"
    "  sdf-bake --scene S --out GRID.pnsdf [--voxel V]  a scene's distance grid, for sdf-shade --grid\n"
    "\n"
    "Environment: PENUMBRA_BACKEND=auto|simd|opencl|scalar overrides Auto;\n"
    "PENUMBRA_SIMD_ISA=sse4.2|avx2|avx512 forces an ISA.\n";

std::string one_line(std::string text)
{
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::cout << kUsage;
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "info") return penumbra::cli::info_command(args);
        if (command == "shade") return penumbra::cli::shade_command(args);
        if (command == "example") return penumbra::cli::example_command(args);
        if (command == "render-scene") return penumbra::cli::render_scene_command(args);
        if (command == "demo") return penumbra::cli::demo_command(args);
        if (command == "blur") return penumbra::cli::blur_command(args);
        if (command == "sdf-shade") return penumbra::cli::sdf_shade_command(args);
        if (command == "sdf-bake") return penumbra::cli::sdf_bake_command(args);
        std::cerr << "penumbra: unknown command '" << command << "' (see penumbra --help)\n";
        return 2;
    } catch (const penumbra::cli::UsageError& e) {
        std::cerr << "penumbra " << command << ": " << one_line(e.message) << "\n";
        return 2;
    } catch (const penumbra::Error& e) {
        const bool bad_input = e.category() != penumbra::ErrorCategory::Backend;
        // The message starts with the operation that failed ("shade: ...").
        std::cerr << "penumbra " << (bad_input ? one_line(e.what()) : std::string(e.what())) << "\n";
        return bad_input ? 2 : 1;
    } catch (const std::exception& e) {
        std::cerr << "penumbra " << command << ": internal error: " << one_line(e.what()) << "\n";
        return 1;
    }
}
