// cli_io_bench: is `penumbra shade` as fast as its I/O? (issue 10, item 10)
//
// Times, in one run, `penumbra shade --method vsm --radius 8` on a 4096^2 map
// and 2048^2 receivers against the same reads and the same write done with
// OpenEXR alone (Imf::InputFile / Imf::OutputFile, ZIP as the tool writes,
// OpenEXR's pool sized to the CPUs the child may use, as the tool sizes it).
// Every case is a child process: the tool by fork + exec, the I/O-only case
// by fork (it writes the tool's own output, read before the timed runs, so
// that both compress the same pixels). Runs are interleaved (the order of the
// cases rotates each run); the report gives medians, the ratio of the tool's
// median to the I/O-only median, and the tool's peak RSS (wait4's ru_maxrss)
// over the bytes of its inputs, table and output as the library holds them.
// Each case runs on CPU 0 only (1 thread, as `taskset -c 0`) and on every CPU.
//
//   cli_io_bench [--runs N] [--inputs DIR] [--tool NAME=PATH]...
// --tool may be given several times (e.g. before=/tmp/old/penumbra): every
// tool runs in the same interleaved rounds. A tool's directory is put first on
// its LD_LIBRARY_PATH, so that a copied build runs its own libpenumbra.so.
// Without --tool, the penumbra built beside this benchmark. The inputs are made
// once in DIR (default: $TMPDIR/penumbra-cli-io-bench) by `penumbra render-scene`.
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "exr_planes.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace fs = std::filesystem;
using penumbra::bench::FloatPlanes;

namespace {

constexpr int kMapSize = 4096, kViewSize = 2048;

struct Tool {
    std::string name, path;
};

struct Options {
    int runs = 5;
    fs::path inputs = fs::temp_directory_path() / "penumbra-cli-io-bench";
    std::vector<Tool> tools;
};

struct Sample {
    double seconds = 0;
    double peak_bytes = 0;
};

// ------------------------------------------------------------ child processes

// CPU 0 only, or every CPU this process may use (cpus == 0).
void restrict_to_cpus(int cpus)
{
    if (cpus != 1) return;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(0, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) std::_Exit(126);
}

// Runs `body` in a child on `cpus`; the wall time from fork to reaping, and the
// child's peak resident set. A child that fails ends the benchmark.
Sample in_child(int cpus, const std::function<void()>& body, const std::string& what)
{
    std::fflush(stdout);  // else the child's freopen would print the parent's buffer again
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        restrict_to_cpus(cpus);
        try {
            body();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cli_io_bench: %s: %s\n", what.c_str(), e.what());
            std::_Exit(1);
        }
        std::_Exit(0);
    }
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed");
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(what + " failed");
    return {wall.count(), double(usage.ru_maxrss) * 1024.0};  // ru_maxrss is in KiB on Linux
}

// exec's the tool (never returns), its stdout silenced.
void exec_tool(const Tool& tool, std::vector<std::string> args)
{
    const char* old_path = std::getenv("LD_LIBRARY_PATH");
    const std::string dir = fs::path(tool.path).parent_path().string();
    setenv("LD_LIBRARY_PATH", (old_path ? dir + ":" + old_path : dir).c_str(), 1);
    if (std::freopen("/dev/null", "w", stdout) == nullptr) std::_Exit(126);
    args.insert(args.begin(), tool.path);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(tool.path.c_str(), argv.data());
    std::_Exit(127);
}

std::vector<std::string> shade_args(const Options& o, const fs::path& out)
{
    return {"shade",        "--method", "vsm", "--radius", "8", "--shadow-map", (o.inputs / "sm.exr").string(),
            "--receivers", (o.inputs / "rx.exr").string(), "--out", out.string()};
}

Sample run_tool(const Options& o, const Tool& tool, int cpus, const fs::path& out)
{
    return in_child(cpus, [&] { exec_tool(tool, shade_args(o, out)); }, tool.name + " shade");
}

// The tool's reads and write with OpenEXR alone, its pool sized as the tool's.
Sample run_io_only(const Options& o, int cpus, const FloatPlanes& output)
{
    return in_child(cpus, [&] {
        cpu_set_t allowed;
        sched_getaffinity(0, sizeof allowed, &allowed);
        Imf::setGlobalThreadCount(CPU_COUNT(&allowed));
        const FloatPlanes map = penumbra::bench::read_exr_planes((o.inputs / "sm.exr").string(), {"Z"});
        const FloatPlanes rx = penumbra::bench::read_exr_planes((o.inputs / "rx.exr").string(), {"u", "v", "z"});
        if (map.width != kMapSize || rx.width != kViewSize) throw std::runtime_error("unexpected input sizes");
        penumbra::bench::write_exr_plane((o.inputs / "out_io.exr").string(), output, "Y");
    }, "io-only");
}

// ------------------------------------------------------------ set-up

void make_inputs(const Options& o)
{
    if (fs::exists(o.inputs / "sm.exr") && fs::exists(o.inputs / "rx.exr")) return;
    fs::create_directories(o.inputs);
    const std::string map = std::to_string(kMapSize), view = std::to_string(kViewSize);
    in_child(0, [&] {
        exec_tool(o.tools.front(), {"render-scene", "contact", "--map-size", map, "--view-size", view + "x" + view,
                                    "--samples", "1", "--shadow-map", (o.inputs / "sm.exr").string(),
                                    "--receivers", (o.inputs / "rx.exr").string(),
                                    "--truth", (o.inputs / "gt.exr").string()});
    }, "render-scene");
}

// Bytes the library holds for the inputs, VSM's exact table and the output.
double data_bytes()
{
    const auto image = [](int size, int channels) {
        return double(penumbra::padded_pitch(size)) * size * channels * sizeof(float);
    };
    const penumbra::MomentTable table(kMapSize, kMapSize, 2, penumbra::Precision::Exact);
    return image(kMapSize, 1) + image(kViewSize, 3) + double(table.storage_elements()) * 4 + image(kViewSize, 1);
}

Options parse(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) throw std::runtime_error("usage: cli_io_bench [--runs N] [--inputs DIR] [--tool NAME=PATH]...");
        const std::string value = argv[++i];
        if (arg == "--runs") o.runs = std::max(1, std::atoi(value.c_str()));
        else if (arg == "--inputs") o.inputs = value;
        else if (arg == "--tool" && value.find('=') != std::string::npos)
            o.tools.push_back({value.substr(0, value.find('=')), fs::absolute(value.substr(value.find('=') + 1))});
        else throw std::runtime_error("unknown option " + arg);
    }
    if (o.tools.empty()) o.tools.push_back({"penumbra", PENUMBRA_TOOL_PATH});
    return o;
}

// ------------------------------------------------------------ report

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// samples[case][run]; case 0 is io-only, case i > 0 is tools[i - 1].
void report(const Options& o, int cpus, const std::vector<std::vector<Sample>>& samples, double bytes)
{
    const auto medians = [&](std::size_t c, double Sample::*field) {
        std::vector<double> v;
        for (const Sample& s : samples[c]) v.push_back(s.*field);
        return median(v);
    };
    const double io = medians(0, &Sample::seconds);
    const char* cpu_text = cpus == 1 ? "1 (CPU 0)" : "all";
    std::printf("%-10s %-10s %8.3f s %8s\n", cpu_text, "io-only", io, "1.00x");
    for (std::size_t c = 1; c < samples.size(); ++c) {
        const double wall = medians(c, &Sample::seconds), peak = medians(c, &Sample::peak_bytes);
        std::printf("%-10s %-10s %8.3f s %7.2fx   peak %7.1f MiB = %.3fx data\n", cpu_text,
                    o.tools[c - 1].name.c_str(), wall, wall / io, peak / 1048576.0, peak / bytes);
    }
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        const Options o = parse(argc, argv);
        make_inputs(o);
        // Untimed: warms the page cache and gives the pixels the I/O-only case writes.
        run_tool(o, o.tools.front(), 0, o.inputs / "out_reference.exr");
        const FloatPlanes output = penumbra::bench::read_exr_planes((o.inputs / "out_reference.exr").string(), {"Y"});
        const double bytes = data_bytes();
        std::printf("penumbra shade --method vsm --radius 8, map %d^2, receivers %d^2; medians of %d interleaved runs\n"
                    "inputs + table + output as held: %.1f MiB\n", kMapSize, kViewSize, o.runs, bytes / 1048576.0);
        std::printf("%-10s %-10s %10s %8s\n", "cpus", "case", "wall", "vs io");
        for (const int cpus : {1, 0}) {
            std::vector<std::vector<Sample>> samples(o.tools.size() + 1);
            for (int run = 0; run < o.runs; ++run)
                for (std::size_t k = 0; k < samples.size(); ++k) {
                    const std::size_t c = (k + std::size_t(run)) % samples.size();
                    samples[c].push_back(c == 0 ? run_io_only(o, cpus, output)
                                                : run_tool(o, o.tools[c - 1], cpus, o.inputs / "out_tool.exr"));
                }
            report(o, cpus, samples, bytes);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cli_io_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
