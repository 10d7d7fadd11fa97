// `tessera bench`, `tradeoff` and `render --repeat` stopped by SIGINT or SIGTERM part way (a
// user's Ctrl+C): what was measured reaches the log as it is measured, and is printed and
// written, marked as interrupted, with the exit status a shell gives a command the signal ended.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "tests/vulkan_fixture.h"

extern char** environ;

namespace tessera {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

size_t count_lines(const std::string& text) {
  return size_t(std::count(text.begin(), text.end(), '\n'));
}

struct Stopped {
  bool stopped = false;  // the signal was sent: `ready` appeared before the command ended
  int status = -1;       // the exit status, -1 if the command did not exit (a signal ended it)
  std::string out, err;
};

// Runs the tool with `args`, its stdout and stderr in files (as `> log`, where they are not a
// terminal), until `ready` appears in its stdout (or its stderr, with `ready_on_stderr`); then
// sends it `signal` and waits for it to end. Polls the files rather than sleeping a fixed time,
// so that a slow machine only makes the test slower. The command's own size keeps it from
// finishing before the signal: many more points than the one waited for.
Stopped run_and_stop(const std::vector<std::string>& args, const std::string& base,
                     const std::string& ready, bool ready_on_stderr, int signal) {
  const std::string out_path = base + ".out", err_path = base + ".err";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  std::vector<std::string> argv_strings = {TESSERA_BINARY};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  // The signals' default actions, whatever this process inherited: a shell starts a script's
  // background commands ignoring SIGINT, which the tool then leaves ignored.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  Stopped result;
  const int spawned = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) return result;
  int wait_status = 0;
  // A deadline only so that a command that never prints `ready` fails the test, not hangs it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  for (;;) {
    if (waitpid(pid, &wait_status, WNOHANG) == pid) break;  // ended before `ready`
    if (read_text(ready_on_stderr ? err_path : out_path).find(ready) != std::string::npos) {
      kill(pid, signal);
      result.stopped = true;
      waitpid(pid, &wait_status, 0);
      break;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &wait_status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  result.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  result.out = read_text(out_path);
  result.err = read_text(err_path);
  return result;
}

// Object counts 1..n, for a sweep of n points.
std::string counts_up_to(int n) {
  std::string out;
  for (int i = 1; i <= n; ++i) out += (i > 1 ? "," : "") + std::to_string(i);
  return out;
}

TEST(SweepInterrupt, BenchWritesThePointsMeasuredAndExits130) {
  const std::string base = test::output_path("bench");
  const int points = 100;  // each some tens of ms at 32x32: far more than the signal takes
  const Stopped run = run_and_stop({"bench",       "--device",
                                    "lavapipe",    "--validate",
                                    "--scene",     "grid",
                                    "--objects",   counts_up_to(points),
                                    "--size",      "32x32",
                                    "--backends",  "compute",
                                    "--repeat",    "1",
                                    "--warmup",    "0",
                                    "--warmup-ms", "0",
                                    "--csv",       base + ".csv",
                                    "--json",      base + ".json",
                                    "--chart",     base + ".svg"},
                                   base,
                                   // The first row, in the log while the sweep goes on.
                                   "\n        1   compute ", false, SIGINT);
  ASSERT_TRUE(run.stopped) << "the first row never reached the log before the end:\n"
                           << run.out << run.err;
  EXPECT_EQ(run.status, 130) << run.out << run.err;  // 128 + SIGINT (2)
  const std::regex said(
      "tessera: interrupted by SIGINT after ([0-9]+) of 100 points; wrote the ([0-9]+) measured "
      "to " +
      base + ".csv, " + base + ".json, " + base + ".svg\n");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.err, m, said)) << run.err;
  const size_t made = std::stoul(m[1]);
  EXPECT_EQ(std::stoul(m[2]), made);
  EXPECT_GE(made, 1u);
  EXPECT_LT(made, size_t(points));
  // Stdout: the heading's three lines, a row per point measured, the files written.
  size_t rows = 0;
  for (size_t at = run.out.find("   compute "); at != std::string::npos;
       at = run.out.find("   compute ", at + 1))
    ++rows;
  EXPECT_EQ(rows, made) << run.out;
  EXPECT_NE(run.out.find("wrote " + base + ".csv\n"), std::string::npos) << run.out;
  // The files hold those points: the CSV a header and a line each, the JSON says it stopped.
  EXPECT_EQ(count_lines(read_text(base + ".csv")), 1 + made);
  const nlohmann::json json = nlohmann::json::parse(read_text(base + ".json"));
  EXPECT_EQ(json["interrupted"], true);
  EXPECT_EQ(json["measurements_planned"], points);
  EXPECT_EQ(json["measurements_made"], made);
  ASSERT_EQ(json["results"].size(), made);
  for (size_t i = 0; i < made; ++i) EXPECT_EQ(json["results"][i]["objects"], i + 1);
  EXPECT_NE(read_text(base + ".svg").find("interrupted (" + std::to_string(made) + " of 100"),
            std::string::npos);
}

TEST(SweepInterrupt, TradeoffFinishesTheSettingsTimedAndExits143OnSigterm) {
  const std::string base = test::output_path("tradeoff");
  const int rounds = 100;  // each of a few settings at 32x32, one frame: far more than one
  const Stopped run = run_and_stop({"tradeoff",        "--device",
                                    "lavapipe",        "--validate",
                                    "--scene",         "spheres",
                                    "--knob",          "tessellation",
                                    "--size",          "32x32",
                                    "--rounds",        std::to_string(rounds),
                                    "--repeat",        "1",
                                    "--warmup",        "0",
                                    "--warmup-ms",     "0",
                                    "--truth-samples", "1",
                                    "--json",          base + ".json",
                                    "--chart",         base + ".svg"},
                                   base,
                                   // Into a log, a line per round measured.
                                   "measured ", true, SIGTERM);
  ASSERT_TRUE(run.stopped) << "no round was reported before the end:\n" << run.out << run.err;
  EXPECT_EQ(run.status, 143) << run.out << run.err;  // 128 + SIGTERM (15)
  const std::regex said(
      "tessera: interrupted by SIGTERM after ([0-9]+) of ([0-9]+) measurements \\(([0-9]+) "
      "settings x 100 rounds\\); wrote the ([0-9]+) settings timed( \\([0-9]+ in fewer "
      "rounds\\))? to " +
      base + ".json, " + base + ".svg\n");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.err, m, said)) << run.err;
  const size_t made = std::stoul(m[1]), planned = std::stoul(m[2]), settings = std::stoul(m[3]);
  EXPECT_EQ(planned, settings * rounds);
  // A line said a whole round was measured: every setting has a time.
  EXPECT_EQ(std::stoul(m[4]), settings);
  EXPECT_GE(made, settings);
  EXPECT_LT(made, planned);
  const nlohmann::json json = nlohmann::json::parse(read_text(base + ".json"));
  EXPECT_EQ(json["interrupted"], true);
  EXPECT_EQ(json["measurements_made"], made);
  ASSERT_EQ(json["points"].size(), settings);
  // Rounds interleave the settings: the first ones timed in one round more than the others.
  size_t rounds_made = 0;
  for (const auto& p : json["points"]) {
    EXPECT_EQ(p["rounds"], p["warmups"].size());
    EXPECT_LE(p["rounds"].get<size_t>(), made / settings + 1);
    EXPECT_GE(p["rounds"].get<size_t>(), made / settings);
    EXPECT_NE(p["mean_relative_error"], nullptr);  // measured against the truth
    rounds_made += p["rounds"].get<size_t>();
  }
  EXPECT_EQ(rounds_made, made);
  EXPECT_NE(run.out.find("knob"), std::string::npos) << run.out;  // the table
}

// A long --repeat on either kind of device: a progress line every 2 s or more, and a stop
// between frames that still writes the image and prints the times of the frames rendered.
TEST(SweepInterrupt, RenderRepeatWritesTheImageAndTheFramesRenderedOnEitherDevice) {
  struct Case {
    const char* device;
    int signal, status;
    const char* signal_name;
    const char* times;  // the line of the frames after the first
  };
  for (const Case& c : {Case{"lavapipe", SIGINT, 130, "SIGINT", "GPU time, median of "},
                        Case{"reference", SIGTERM, 143, "SIGTERM", "CPU time, median of "}}) {
    SCOPED_TRACE(c.device);
    const std::string base = test::output_path(std::string("render_") + c.device);
    // 1,000 frames at 128x128 take far longer than the 2 s before the first progress line.
    const Stopped run = run_and_stop({"render", "--device", c.device, "--size", "128x128",
                                      "--repeat", "1000", "--out", base + ".png"},
                                     base, "rendered ", false, c.signal);
    ASSERT_TRUE(run.stopped) << "no progress line before the end:\n" << run.out << run.err;
    EXPECT_EQ(run.status, c.status) << run.out << run.err;
    const std::regex said(std::string("tessera: interrupted by ") + c.signal_name +
                          " after ([0-9]+) of 1000 frames after the first: the image and the "
                          "times of the frames rendered are written and printed\n");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(run.err, m, said)) << run.err;
    const size_t made = std::stoul(m[1]);
    EXPECT_GE(made, 1u);  // the progress line came after one frame at least
    EXPECT_LT(made, 1000u);
    const std::regex progress("rendered ([0-9]+) of 1000 frames after the first\n");
    ASSERT_TRUE(std::regex_search(run.out, m, progress)) << run.out;
    EXPECT_LE(std::stoul(m[1]), made);
    EXPECT_NE(run.out.find(c.times + std::to_string(made) + " frame"), std::string::npos)
        << run.out;
    const Image8 image = read_png(base + ".png");
    EXPECT_EQ(image.width, 128u);
    EXPECT_EQ(image.height, 128u);
  }
}

}  // namespace
}  // namespace tessera
