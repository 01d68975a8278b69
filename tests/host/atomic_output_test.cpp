// All-or-nothing publication (penumbra/output_files.h; issue 11, defects 6 and
// 7): a failed set leaves every target as it was and no temporary behind; an
// interrupted process (SIGKILL, SIGINT, SIGTERM while writing a large file)
// leaves nothing either, because the data lives in an unnamed O_TMPFILE.
#include "penumbra/output_files.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "penumbra/error.h"
#include "support/cli.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

class AtomicOutput : public testing::CliFixture {
protected:
    static std::vector<std::string> entries_of(const fs::path& dir)
    {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    std::vector<std::string> entries() const { return entries_of(dir_); }
    void write_text(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
};

void write_text_to(const std::string& file, const std::string& text)
{
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("write failed");
}

TEST_F(AtomicOutput, PublishesEveryFileAndLeavesNoTemporary)
{
    write_text("a", "old a");
    OutputFiles out("test");
    out.stage(path("a"), [](const std::string& t) { write_text_to(t, "new a"); });
    out.stage(path("b"), [](const std::string& t) { write_text_to(t, "new b"); });
    EXPECT_EQ(testing::slurp(path("a")), "old a") << "replaced before publish()";
    EXPECT_FALSE(fs::exists(path("b")));
    out.publish();
    EXPECT_EQ(testing::slurp(path("a")), "new a");
    EXPECT_EQ(testing::slurp(path("b")), "new b");
    EXPECT_EQ(entries(), (std::vector<std::string>{"a", "b"}));
}

TEST_F(AtomicOutput, AFailingWriterLeavesEveryTargetAsItWas)
{
    write_text("a", "old a");
    write_text("b", "old b");
    {
        OutputFiles out("test");
        out.stage(path("a"), [](const std::string& t) { write_text_to(t, "new a"); });
        EXPECT_THROW(out.stage(path("b"), [](const std::string&) { throw std::runtime_error("disk full"); }), Error);
    }  // destroyed unpublished
    EXPECT_EQ(testing::slurp(path("a")), "old a");
    EXPECT_EQ(testing::slurp(path("b")), "old b");
    EXPECT_EQ(entries(), (std::vector<std::string>{"a", "b"}));
}

// rename(2) cannot put a file over a directory: the message says what was replaced.
TEST_F(AtomicOutput, AFailedRenameSaysWhatIsWhere)
{
    fs::create_directory(path("b"));
    OutputFiles out("test");
    out.stage(path("a"), [](const std::string& t) { write_text_to(t, "new a"); });
    out.stage(path("b"), [](const std::string& t) { write_text_to(t, "new b"); });
    try {
        out.publish();
        ADD_FAILURE() << "publish() over a directory succeeded";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::Io);
        EXPECT_NE(std::string(e.what()).find("already replaced: '" + path("a") + "'"), std::string::npos) << e.what();
    }
    EXPECT_EQ(testing::slurp(path("a")), "new a");
    EXPECT_TRUE(fs::is_directory(path("b")));
    EXPECT_EQ(entries(), (std::vector<std::string>{"a", "b"}));
}

TEST_F(AtomicOutput, UnsafeTargetsAreRefusedUpFront)
{
    write_text("in", "input");
    ASSERT_EQ(::link(path("in").c_str(), path("alias").c_str()), 0);
    ASSERT_EQ(::symlink(path("in").c_str(), path("symlink").c_str()), 0);
    auto refused = [&](const std::vector<std::string>& outs, const std::string& fragment) {
        try {
            require_safe_outputs(outs, {path("in")}, "test");
            ADD_FAILURE() << "accepted " << outs.front();
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    refused({path("in")}, "one of the inputs");
    refused({path("alias")}, "one of the inputs");
    refused({path("symlink")}, "one of the inputs");
    refused({path("x"), dir_.string() + "/./x"}, "two outputs");
    refused({"/dev/null"}, "character device");
    refused({dir_.string()}, "directory");
    refused({path("no/such/dir/x")}, "does not exist");
    EXPECT_NO_THROW(require_safe_outputs({path("new"), path("other")}, {path("in")}, "test"));
}

// Waits for the child's marker file.
bool appears_within_30_s(const fs::path& marker)
{
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(marker) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return fs::exists(marker);
}

// A child writes a large file through OutputFiles and is killed mid-write;
// the directory must hold only the marker it wrote before starting. With
// `named`, the child uses the named-temporary fallback (PENUMBRA_NO_O_TMPFILE).
void expect_nothing_left_after(int signal_number, const fs::path& dir, bool named = false)
{
    const fs::path marker = dir / "started";
    const pid_t child = ::fork();
    if (child == 0) {
        if (named) ::setenv("PENUMBRA_NO_O_TMPFILE", "1", 1);
        OutputFiles out("test");
        out.stage((dir / "big.bin").string(), [&](const std::string& temporary) {
            std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
            const std::string block(1 << 20, 'x');
            for (int i = 0; i < 64; ++i) file << block;
            file.flush();
            std::ofstream(marker) << "1";
            for (;;) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        });
        ::_exit(3);
    }
    ASSERT_TRUE(appears_within_30_s(marker)) << "the child never started writing";
    ::kill(child, signal_number);
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << "status " << status;
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
    EXPECT_EQ(left, (std::vector<std::string>{"started"})) << "signal " << signal_number;
    fs::remove(marker);
}

TEST_F(AtomicOutput, SigkillDuringAWriteLeavesNoTemporary) { expect_nothing_left_after(SIGKILL, dir_); }
TEST_F(AtomicOutput, SigintDuringAWriteLeavesNoTemporary) { expect_nothing_left_after(SIGINT, dir_); }
TEST_F(AtomicOutput, SigtermDuringAWriteLeavesNoTemporary) { expect_nothing_left_after(SIGTERM, dir_); }

// The fallback: named temporaries, removed by the signal handler.
TEST_F(AtomicOutput, NamedFallbackRemovesItsTemporaryOnSigint) { expect_nothing_left_after(SIGINT, dir_, true); }
TEST_F(AtomicOutput, NamedFallbackRemovesItsTemporaryOnSigterm) { expect_nothing_left_after(SIGTERM, dir_, true); }

TEST_F(AtomicOutput, NamedFallbackPublishesAndCleansUp)
{
    ::setenv("PENUMBRA_NO_O_TMPFILE", "1", 1);
    write_text("a", "old a");
    {
        OutputFiles out("test");
        out.stage(path("a"), [](const std::string& t) { write_text_to(t, "new a"); });
        out.stage(path("b"), [](const std::string& t) {
            EXPECT_EQ(t.find("/proc/self/fd/"), std::string::npos) << "not the fallback: " << t;
            write_text_to(t, "new b");
        });
        EXPECT_EQ(entries().size(), 3u) << "the fallback names its temporaries";
        out.publish();
    }
    {
        OutputFiles out("test");
        out.stage(path("a"), [](const std::string& t) { write_text_to(t, "newer a"); });
        EXPECT_THROW(out.stage(path("b"), [](const std::string&) { throw std::runtime_error("disk full"); }), Error);
    }
    ::unsetenv("PENUMBRA_NO_O_TMPFILE");
    EXPECT_EQ(testing::slurp(path("a")), "new a");
    EXPECT_EQ(testing::slurp(path("b")), "new b");
    EXPECT_EQ(entries(), (std::vector<std::string>{"a", "b"}));
}

// The real tool, killed while it writes a 256 MiB map.
TEST_F(AtomicOutput, KilledExampleLeavesNoTemporary)
{
    const pid_t child = ::fork();
    if (child == 0) {
        ::execl(PENUMBRA_CLI_PATH, PENUMBRA_CLI_PATH, "example", "--out", dir_.c_str(), "--map-size", "8192",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    for (const auto& entry : fs::directory_iterator(dir_)) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "shadow_map.exr" || name == "receivers.exr") << "left behind: " << name;
    }
}

// ---- SIGKILL inside publish(): named temporaries, swept by the next run
//
// PENUMBRA_TEST_SIGKILL_AT makes the child kill itself at the exact point, so
// each test hits the window every time (a timed signal would hit it rarely).

bool is_temporary(const std::string& name) { return name.find(".penumbra-tmp-") != std::string::npos; }

// A child publishes new "a" and "b" over old ones and SIGKILLs itself at `point`.
void publish_and_die_at(const char* point, const fs::path& dir, bool named = false)
{
    std::ofstream(dir / "a") << "old a";
    std::ofstream(dir / "b") << "old b";
    const pid_t child = ::fork();
    if (child == 0) {
        if (named) ::setenv("PENUMBRA_NO_O_TMPFILE", "1", 1);
        ::setenv("PENUMBRA_TEST_SIGKILL_AT", point, 1);
        OutputFiles out("test");
        out.stage((dir / "a").string(), [](const std::string& t) { write_text_to(t, "new a"); });
        out.stage((dir / "b").string(), [](const std::string& t) { write_text_to(t, "new b"); });
        out.publish();
        ::_exit(3);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
}

// What a later run of penumbra in the same folder leaves: it sweeps first.
void publish_c_in(const fs::path& dir)
{
    OutputFiles out("test");
    out.stage((dir / "c").string(), [](const std::string& t) { write_text_to(t, "c"); });
    out.publish();
}

TEST_F(AtomicOutput, SigkillBeforeTheFirstRenameLeavesEveryTargetOldAndTheNextRunSweeps)
{
    for (bool named : {false, true}) {
        SCOPED_TRACE(named ? "named fallback" : "O_TMPFILE");
        // A folder of its own each time: a process sweeps a folder only once.
        const fs::path dir = dir_ / (named ? "named" : "unnamed");
        fs::create_directories(dir);
        publish_and_die_at("linked", dir, named);
        const auto left = entries_of(dir);
        EXPECT_EQ(std::count_if(left.begin(), left.end(), is_temporary), 2) << "the window this test must hit";
        EXPECT_EQ(testing::slurp((dir / "a").string()), "old a");
        EXPECT_EQ(testing::slurp((dir / "b").string()), "old b");
        publish_c_in(dir);
        EXPECT_EQ(entries_of(dir), (std::vector<std::string>{"a", "b", "c"}));
    }
}

// The honest limit (docs/robustness.md): rename(2) replaces one name at a
// time, so a kill between two renames leaves a mix of new and old targets.
TEST_F(AtomicOutput, SigkillBetweenRenamesLeavesAMixThatIsNewThenOld)
{
    publish_and_die_at("renamed-1", dir_);
    EXPECT_EQ(testing::slurp(path("a")), "new a") << "targets are renamed in the order they were staged";
    EXPECT_EQ(testing::slurp(path("b")), "old b");
    publish_c_in(dir_);
    EXPECT_EQ(entries(), (std::vector<std::string>{"a", "b", "c"}));
}

// A temporary whose writer is alive holds its lock, so the sweep leaves it;
// names that are not penumbra's temporaries are never touched.
TEST_F(AtomicOutput, TheSweepSparesALiveWritersTemporaryAndOtherFiles)
{
    const std::vector<std::string> foreign{".a.tmp-1-2", ".a.penumbra-tmp-x-1", "a.penumbra-tmp-1-2"};
    for (const std::string& name : foreign) write_text(name, "not ours");
    const fs::path marker = dir_ / "started";
    const pid_t child = ::fork();
    if (child == 0) {
        ::setenv("PENUMBRA_NO_O_TMPFILE", "1", 1);  // a named temporary from the start
        OutputFiles out("test");
        out.stage((dir_ / "big").string(), [&](const std::string& temporary) {
            write_text_to(temporary, "being written");
            std::ofstream(marker) << "1";
            for (;;) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        });
        ::_exit(3);
    }
    ASSERT_TRUE(appears_within_30_s(marker)) << "the child never started writing";
    publish_c_in(dir_);
    const auto left = entries();
    EXPECT_EQ(std::count_if(left.begin(), left.end(), [](const std::string& name) { return name.rfind(".big.", 0) == 0; }),
              1) << "the live writer's temporary";
    for (const std::string& name : foreign) EXPECT_EQ(testing::slurp(path(name)), "not ours") << name;
    ::kill(child, SIGTERM);  // its handler removes its temporary
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_EQ(entries().size(), foreign.size() + 2) << "c, the marker and the foreign files";
}

// The real tool, killed inside render-scene's publication of three files, then
// run again: no temporary survives the second run.
TEST_F(AtomicOutput, KilledRenderSceneIsSweptByTheNextRun)
{
    const std::vector<std::string> args{"render-scene", "contact", "--map-size", "16", "--view-size", "8x6",
                                        "--samples", "1", "--shadow-map", path("sm.exr"), "--receivers",
                                        path("rx.exr"), "--truth", path("gt.exr")};
    const auto killed = testing::run_cli(args, {{"PENUMBRA_TEST_SIGKILL_AT", "linked"}});
    EXPECT_EQ(killed.signal, SIGKILL) << killed.err;
    const auto left = entries();
    EXPECT_EQ(std::count_if(left.begin(), left.end(), is_temporary), 3);
    EXPECT_EQ(left.size(), 3u) << "no target was replaced";
    EXPECT_EQ(testing::run_cli(args).exit_code, 0);
    EXPECT_EQ(entries(), (std::vector<std::string>{"gt.exr", "rx.exr", "sm.exr"}));
}

}  // namespace
}  // namespace penumbra
