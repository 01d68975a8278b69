// penumbra: the command-line tool. Exit status: 0 success, 2 bad input (bad
// options, unreadable or invalid files, a backend this machine lacks), 1 any
// other failure (a backend error, a bug). Errors are one line on stderr.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "input_limits.h"
#include "sdf_command.h"
#include "penumbra/error.h"
#include "penumbra/methods.h"

namespace {

struct Command {
    std::string name;
    std::string arguments;  // the usage line after the name
    std::string summary;
    int (*run)(const std::vector<std::string>& args);
};

// The commands: dispatch and the usage text both come from this table.
const std::vector<Command>& commands()
{
    using namespace penumbra::cli;
    static const std::vector<Command> table = {
        {"info", "[--json] [--verbose]", "backends, the one Auto chooses and why, CPU ISAs, OpenCL devices",
         info_command},
        {"shade",
         "--method " + penumbra::method_names("|") + " --shadow-map SM.exr --receivers RX.exr --out OUT.exr [options]",
         "filter a shadow map for a set of receivers (shade --help)", shade_command},
        {"example", "--out DIR", "write a small synthetic shadow map and receivers to DIR", example_command},
        {"render-scene", "NAME --shadow-map SM.exr --receivers RX.exr --truth GT.exr [options]",
         "a reference scene and its ray-traced ground truth", render_scene_command},
        {"dsm-build", "--scene S --out DSM.exr [--size N] [--samples K] [--tolerance E] [--filter box|gaussian]",
         "a reference scene's deep shadow map, as an OpenEXR deep file (dsm-build --help)", dsm_build_command},
        {"pismo-build", "--scene S --out DIR [--light-level L] [--map-size N] [--layers K] [--receivers RX.exr]",
         "a reference scene's Pismo maps (light mesh, layered depth maps) (pismo-build --help)",
         pismo_build_command},
        {"demo", "[--quick] [--out DIR]", "every method on every scene: images, CSV, time-vs-error chart",
         demo_command},
        {"blur", "--in MASK.exr --guide DEPTH.exr --out OUT.exr [options]",
         "cross-bilateral blur of a mask, stopping at depth edges (blur --help)", blur_command},
        {"sdf-shade", "(--scene S | --grid G) --receivers RX.exr --out OUT.exr [options]",
         "sphere-traced distance-field soft shadows (sdf-shade --help)", sdf_shade_command},
        {"sdf-bake", "--scene S --out GRID.pnsdf [--voxel V]", "a scene's distance grid, for sdf-shade --grid",
         sdf_bake_command},
        {"ambient", "--rig RIG.json [--dark-rig DARK.json --volumes VOL.json] --receivers RX.exr --out OUT.exr",
         "irradiance from SH ambient rigs and volumes (ambient --help)", ambient_command},
        {"mask", "--scene S --out MASK.exr [--view-size WxH] [--blur] [step options]",
         "a scene view's deferred mask: ao (ssao-vo), blurred together (mask --help)", mask_command},
    };
    return table;
}

// A command's line and summary; the summary starts at column 30, on the
// next line when the usage is longer.
std::string usage_text()
{
    constexpr std::size_t kSummaryColumn = 30;
    std::string text = "penumbra: shadow-filtering kernels on SIMD CPUs and OpenCL\n\nusage: penumbra <command> [options]\n";
    for (const Command& c : commands()) {
        std::string line = "  " + c.name + " " + c.arguments;
        if (line.size() + 1 < kSummaryColumn) line.resize(kSummaryColumn, ' ');
        else line += "\n" + std::string(kSummaryColumn, ' ');
        text += line + c.summary + "\n";
    }
    return text +
           "\n"
           "Every command that reads images takes --max-pixels N (default 268435456 = 16384^2): a larger\n"
           "data window is refused before anything is allocated.\n"
           "\n"
           "Environment: PENUMBRA_BACKEND=auto|simd|opencl|scalar overrides Auto;\n"
           "PENUMBRA_SIMD_ISA=sse4.2|avx2|avx512 forces an ISA.\n";
}

std::string one_line(std::string text)
{
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

// `--help` or `-h` anywhere asks for the command's help, whatever else is given.
bool asks_for_help(const std::vector<std::string>& args)
{
    for (const std::string& word : args)
        if (word == "--help" || word == "-h") return true;
    return false;
}

// Takes `--max-pixels N` out of any command line into the shared read limits.
void take_max_pixels(std::vector<std::string>& args)
{
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] != "--max-pixels") continue;
        if (i + 1 >= args.size()) throw penumbra::cli::UsageError{"option --max-pixels needs a value"};
        const std::string& value = args[i + 1];
        char* end = nullptr;
        errno = 0;
        const unsigned long long parsed = std::strtoull(value.c_str(), &end, 10);
        if (value.empty() || value[0] == '-' || *end != '\0' || errno == ERANGE || parsed == 0)
            throw penumbra::cli::UsageError{"option --max-pixels: '" + value + "' is not a positive integer"};
        penumbra::cli::exr_limits().max_pixels = parsed;
        args.erase(args.begin() + std::ptrdiff_t(i), args.begin() + std::ptrdiff_t(i) + 2);
        --i;
    }
}

int run(const std::string& command, std::vector<std::string> args)
{
    if (asks_for_help(args)) args = {"--help"};
    else take_max_pixels(args);
    for (const Command& c : commands())
        if (c.name == command) return c.run(args);
    std::cerr << "penumbra: unknown command '" << command << "' (see penumbra --help)\n";
    return 2;
}

// Ends the process without the static destructors of every library loaded:
// after a warm OpenCL `shade` those are LLVM's and Clang's (loaded by PoCL),
// the joins of OpenEXR's and TBB's worker threads and PoCL's teardown, which
// took 10 to 60 ms under load from our last file's rename to the process's
// end (strace -f --seccomp-bpf; docs/opencl_startup.md). Every output is
// published before a command returns; what must still happen at exit is
// registered with at_quick_exit (the library's record of PoCL's cache).
[[noreturn]] void finish(int status)
{
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
#if defined(__SANITIZE_ADDRESS__)
    std::exit(status);  // LeakSanitizer checks at exit
#else
    std::quick_exit(status);
#endif
}

int run_tool(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {  // a mistake, not a request: the usage line goes to stderr
        std::cerr << "usage: penumbra <command> [options] (penumbra --help lists the commands)\n";
        return 2;
    }
    if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::cout << usage_text();
        return 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        return run(command, std::move(args));
    } catch (const penumbra::cli::UsageError& e) {
        std::cerr << "penumbra " << command << ": " << one_line(e.message) << "\n";
        return 2;
    } catch (const penumbra::Error& e) {
        const bool bad_input = e.category() != penumbra::ErrorCategory::Backend;
        // The message starts with the operation that failed ("shade: ...").
        std::cerr << "penumbra " << (bad_input ? one_line(e.what()) : std::string(e.what())) << "\n";
        return bad_input ? 2 : 1;
    } catch (const std::bad_alloc&) {
        // Inputs are checked against their sizes and --max-pixels before any
        // large allocation, so this is a request the machine cannot meet.
        std::cerr << "penumbra " << command
                  << ": out of memory: the input or the sizes asked for need more memory than this machine has; "
                     "use smaller sizes\n";
        return 2;
    } catch (const std::filesystem::filesystem_error& e) {
        // A path the user gave that the file system refused (a name too long, a link loop...).
        std::cerr << "penumbra " << command << ": " << one_line(e.what()) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "penumbra " << command << ": internal error: " << one_line(e.what()) << "\n";
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) { finish(run_tool(argc, argv)); }
