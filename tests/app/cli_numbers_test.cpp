// Every numeric option of every command, given hostile values (past every integer width, NaN,
// infinities, 1e999, hex, negative, empty, fractional): each run must end with exit 0, or exit
// 2 and a message, within 60 s; never a signal, a hang or a value silently wrapped. Values that
// no whole-number option can hold (NaN, ±inf, 1e999, 2^64 and beyond) must be refused (exit 2),
// and NaN by every option. Found: validate --spp 0 (SIGFPE), --ray origins past 1e18 (Embree
// aborted), NaN thresholds accepted, converge --spp 1,1e999 run as 1. Each case
// runs `glint`'s command line (runCli) in a forked child, so a crash or a hang is seen as such
// and the table of 512 cases costs no program start-up each; one option's 16 values run at once.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>
#include <chrono>
#include <fstream>
#include <thread>
#include <vector>

#include "app/commands.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exitCode = -1;  // -1 when it did not exit
  int signal = 0;
  bool hung = false;
  std::string output;
};

// Starts `glint ARGS` in a forked child with stdout and stderr in `log`.
pid_t startForked(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<std::string> argvStrings{"glint"};
    argvStrings.insert(argvStrings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argvStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = runCli(int(argvStrings.size()), argv.data());
    std::fflush(nullptr);
    ::_exit(rc);
  }
  return pid;
}

// Waits for the child until `deadline`, then kills it (a hang).
Outcome finishForked(pid_t pid, std::chrono::steady_clock::time_point deadline,
                     const std::string& log) {
  Outcome o;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      o.hung = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!o.hung && WIFEXITED(status)) o.exitCode = WEXITSTATUS(status);
  if (!o.hung && WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  std::ifstream in(log);
  o.output.assign(std::istreambuf_iterator<char>(in), {});
  return o;
}

// A 4×4 frame of one sphere and a point light: every accepted run is quick.
const char* kTinyScene = R"({"render": {"width": 4, "height": 4, "spp": 1},
  "camera": {"eye": [0,0,4], "look_at": [0,0,0]},
  "materials": {"m": {"type": "phong"}}, "lights": [{"type": "point", "position": [2,4,3]}],
  "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})";

// One numeric option: the command's other arguments, the option, and the text around the
// hostile value (for options taking several numbers, the value replaces one of them).
struct NumericOption {
  NumericOption(std::vector<std::string> b, std::string o, std::string p = "", std::string s = "",
                std::vector<std::string> a = {})
      : before(std::move(b)),
        option(std::move(o)),
        prefix(std::move(p)),
        suffix(std::move(s)),
        after(std::move(a)) {}
  std::vector<std::string> before;  // command and the arguments every case needs
  std::string option;
  std::string prefix, suffix;  // the value is given as prefix + VALUE + suffix
  std::vector<std::string> after;
};

const std::vector<std::string> kHostileValues = {"1e999",
                                                 "-1e999",
                                                 "nan",
                                                 "inf",
                                                 "-inf",
                                                 "0x10",
                                                 "",
                                                 "-1",
                                                 "0",
                                                 "1.5",
                                                 "2147483648",
                                                 "4294967296",
                                                 "9223372036854775808",
                                                 "18446744073709551616",
                                                 "99999999999999999999999999",
                                                 "-9223372036854775809"};

// Values that no whole-number option can hold: accepting one means it was wrapped, clamped or
// cut short (converge read "1e999" as 1). Real-valued options (--threshold, --min-agreement,
// --ray) hold 2^64 and, where meaningful, infinity (a ray's tmax); they must refuse NaN.
bool neverValid(const std::string& v, bool realValued) {
  if (realValued) return v == "nan";
  return v == "1e999" || v == "-1e999" || v == "nan" || v == "inf" || v == "-inf" ||
         v == "18446744073709551616" || v == "99999999999999999999999999" ||
         v == "-9223372036854775809";
}

TEST(CliNumbers, HostileValuesOfEveryNumericOptionAreRefusedOrUsed) {
  const std::string scene = test::writeTemp("numbers-scene.json", kTinyScene);
  const std::string exr = (test::tempDir() / "numbers.exr").string();
  ASSERT_EQ(test::runGlint("render " + scene + " --quiet -o " + exr).exitCode, 0);
  const std::string out = (test::tempDir() / "numbers-out.exr").string();
  const std::vector<std::string> render = {"render", scene, "--quiet", "-o", out};
  const std::vector<std::string> validate = {"validate", scene, "--rays", "64", "--no-brute"};
  const std::vector<std::string> converge = {"converge",        scene, "--spp", "1,2",
                                             "--reference-spp", "4"};
  const std::vector<std::string> bench = {"bench",         scene, "--random-rays", "256",
                                          "--render-runs", "0",   "--accel",       "bvh"};
  const std::vector<std::string> plan = {"plan", scene};
  const std::vector<std::string> rayclass = {"render", scene,     "--quiet", "-o",
                                             out,      "--accel", "rayclass"};
  std::vector<std::string> adaptive = render;  // 8 spp: room for adaptive sampling's passes
  adaptive.insert(adaptive.end(), {"--spp", "8"});
  std::vector<std::string> cropLast = render;
  cropLast.insert(cropLast.end(), {"--crop", "0", "4", "0"});
  const std::vector<NumericOption> options = {
      {render, "--spp"},
      {render, "--seed"},
      {render, "--frame"},
      {render, "--threads"},
      {render, "--width"},
      {render, "--height"},
      {render, "--max-depth"},
      {render, "--tile-size"},
      {adaptive, "--target-rmse"},
      {adaptive, "--target-relmse"},
      {adaptive, "--time-limit"},
      {adaptive, "--min-spp"},
      {adaptive, "--max-spp"},
      {adaptive, "--preview-every"},
      {render, "--crop", "", "", {"4", "0", "4"}},  // X0
      {cropLast, ""},                               // Y1, after "--crop 0 4 0"
      {{"validate", scene, "--no-brute"}, "--rays"},
      {validate, "--seed"},
      {validate, "--spp"},
      {validate, "--min-agreement"},
      {rayclass, "--rayclass-n-min"},
      {rayclass, "--rayclass-w-min"},
      {validate, "--rayclass-n-min"},
      {validate, "--rayclass-w-min"},
      {{"validate", scene}, "--ray", "0 0 5 0 0 -1 0 ", " 0"},    // tmax
      {{"validate", scene}, "--ray", "", " 0 5 0 0 -1 0 100 0"},  // the origin's x
      {{"compare", exr, exr}, "--threshold"},
      {{"converge", scene, "--reference-spp", "4"}, "--spp", "1,"},
      {{"converge", scene, "--spp", "1,2"}, "--reference-spp"},
      {converge, "--width"},
      {converge, "--height"},
      {converge, "--threads"},
      {{"bench", scene, "--random-rays", "256", "--render-runs", "0"}, "--procedural"},
      {bench, "--threads"},
      {bench, "--width"},
      {bench, "--height"},
      {{"bench", scene, "--render-runs", "0", "--accel", "bvh"}, "--random-rays"},
      {{"bench", scene, "--random-rays", "256", "--accel", "bvh"}, "--render-runs"},
      {{"merge", out, exr}, "--scene-hash"},  // a string: any value, but no crash
      {plan, "--tiles"},
      {plan, "--frames"},
      {plan, "--frames", "1-"},
      {plan, "--width"},
      {plan, "--height"}};
  const auto logOf = [](size_t i) {
    return (test::tempDir() / ("cli-number-" + std::to_string(i) + ".log")).string();
  };
  size_t cases = 0;
  for (const NumericOption& o : options) {
    // The 16 values of one option run at once (bench's accepted runs take seconds each).
    std::vector<std::vector<std::string>> argsOf;
    std::vector<pid_t> pids;
    for (size_t i = 0; i < kHostileValues.size(); ++i) {
      std::vector<std::string> args = o.before;
      if (!o.option.empty()) args.push_back(o.option);
      args.push_back(o.prefix + kHostileValues[i] + o.suffix);
      args.insert(args.end(), o.after.begin(), o.after.end());
      // Each child its own output file (and merge output), so that they do not share one.
      for (std::string& a : args)
        if (a == out)
          a = (test::tempDir() / ("numbers-out-" + std::to_string(i) + ".exr")).string();
      argsOf.push_back(args);
      pids.push_back(startForked(args, logOf(i)));
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    for (size_t i = 0; i < pids.size(); ++i) {
      const std::string& v = kHostileValues[i];
      const Outcome r = finishForked(pids[i], deadline, logOf(i));
      std::string shown;
      for (const std::string& a : argsOf[i]) shown += " '" + a + "'";
      ++cases;
      EXPECT_FALSE(r.hung) << "glint" << shown << " ran for 60 s";
      EXPECT_EQ(r.signal, 0) << "glint" << shown << " was killed by signal " << r.signal << "\n"
                             << r.output;
      EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 2 || r.hung)
          << "glint" << shown << ": exit " << r.exitCode << "\n"
          << r.output;
      if (r.exitCode == 2) {
        EXPECT_FALSE(r.output.empty()) << "glint" << shown << ": no message";
      }
      const bool realValued = o.option == "--threshold" || o.option == "--min-agreement" ||
                              o.option == "--ray" || o.option == "--target-rmse" ||
                              o.option == "--target-relmse" || o.option == "--time-limit" ||
                              o.option == "--preview-every";
      if (neverValid(v, realValued) && o.option != "--scene-hash") {
        EXPECT_EQ(r.exitCode, 2) << "glint" << shown << " accepted " << v << "\n" << r.output;
      }
    }
  }
  EXPECT_GT(cases, 400u);
}

}  // namespace
}  // namespace glint
