// SPDX-License-Identifier: Apache-2.0
// Issue 10, "Hardening the command line and outputs": every finding pinned by a test.
//   * a table of bad arguments: exit status 1, one line on stderr naming the problem, and nothing left in
//     the working directory (no output, no temporary file);
//   * outputs that are not ours to replace (symlink, FIFO, device, socket, /proc, /sys), two outputs naming
//     one file, all-or-nothing outputs when a later step fails or the run is interrupted;
//   * --threads 0 / caps, --version, unknown subcommands, progress on a terminal, the fit table.
// The simulator side (seeds, reproduce line, watchdog, banner, traces) is in test_cli_cosim_hardening.cpp.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

namespace {

struct BadCase {
  std::string args;    // run in a fresh empty directory (relative output paths land there)
  std::string needle;  // the one stderr line must contain this
};

// Status 1, exactly one stderr line with `needle`, no result printed, and the directory left empty.
void expect_rejected(const BadCase& c) {
  const TempDir d;
  const CliRun r = run_cli(c.args, d.str());
  EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
  EXPECT_EQ(lines(r.err), 1) << c.args << "\n" << r.err;
  EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
  EXPECT_EQ(r.out.find("evaluations in"), std::string::npos) << "the run started: " << c.args;
  EXPECT_TRUE(d.entries().empty()) << c.args << " left " << *d.entries().begin();
}

}  // namespace

TEST(CliHardening, BadArgumentsTable) {
  const std::vector<BadCase> cases = {
      // numbers: rejected, never wrapped, capped or replaced by a default
      {"sweep --threads 40000 --n 16 --frac 8 --json o.json", "--threads"},
      {"sweep --threads -1 --n 16 --frac 8", "--threads"},
      {"energy --threads 65 --n 16 --angles 0 --json o.json", "--threads"},
      {"cosim --shards 65", "--shards"},
      {"sweep --frac -16 --n 16 --json o.json", "fraction width -16 out of range"},
      {"sweep --frac -1 --n 16", "fraction width -1 out of range"},
      {"sweep --guard -3 --n 16", "guard width -3 out of range"},
      {"sweep --config '' --n 16", "empty config name"},
      {"energy --config '' --n 16", "empty config name"},
      {"cosim --config ''", "empty config name"},
      {"cosim --mode random --count -5 --json o.json", "--count: '-5' is not an integer"},
      {"cosim --mode random --count 0", "--count"},
      {"cosim --mode random --seed -1", "--seed: '-1' is not an integer"},
      {"cosim --mode random --seed 99999999999999999999999", "--seed"},
      {"cosim --in-stall nan", "--in-stall: 'nan' is not a probability"},
      {"cosim --out-stall -nan", "--out-stall: '-nan' is not a probability"},
      {"cosim --in-stall 1", "1 would stall forever"},
      {"cosim --out-stall 1", "1 would stall forever"},
      {"cosim --reset-at -5", "--reset-at"},
      {"sweep --n 16..99999999999999", "n = 99999999999999 out of range"},
      {"sweep --n 1024..16", "LO > HI"},
      {"sweep --n 16..x", "malformed range"},
      {"cosim --n 0..5", "n = 0 out of range"},
      // empty paths
      {"sweep --n 16 --frac 8 --json ''", "empty path"},
      {"sweep --n 16 --frac 8 --csv ''", "empty path"},
      {"fit --json ''", "empty path"},
      {"energy --plots ''", "empty path"},
      {"cosim --trace ''", "empty path"},
      // combinations that would be silently ignored
      {"cosim --coef classical", "apply with --norm only"},
      {"cosim --coef-model blinn", "apply with --norm only"},
      {"cosim --norm --coef classical", "--coef needs --coef-model"},
      {"cosim --norm --coef-model bogus", "unknown model 'bogus'"},
      {"cosim --norm --variant schlick_div", "--norm is built for --variant cs16 --cutoff theta_cr only"},
      {"cosim --norm --variant nosuch", "unknown variant 'nosuch'"},
      {"cosim --mode directed --n 16", "--n does not apply to --mode directed"},
      {"cosim --mode exhaustive --n 16 --count 5", "--count does not apply to --mode exhaustive"},
      {"cosim --mode directed --shards 2", "--shards applies to"},
      {"cosim --mode directed --mat-rate 0.1", "--mat-rate applies to --mode random only"},
      {"cosim --mode random --count 5 --mat-rate 1", "--mat-rate"},
      {"fit --lobe schlick --cutoff theta_cr", "--cutoff applies to --lobe cs16 only"},
      {"fit --lobe cos_pow --cutoff sign_clamp", "--cutoff applies to --lobe cs16 only"},
      {"energy --method cells --radial 50 --n 16 --angles 0", "--radial and --azimuth apply to --method grid only"},
      {"sweep --progress --no-progress --n 16 --frac 8", "excludes"},
      // usage errors: status 1 (CLI11 would use 104..114), one line
      {"sweep --no-such-option", "no-such-option"},
      {"sweep --threads many", "--threads"},
      {"sweep --json a.json --json b.json --n 16 --frac 8", "--json"},
      {"frobnicate", "unknown subcommand 'frobnicate'"},
      {"", "a subcommand is required"},
      // outputs that cannot be ours: refused before the run
      {"sweep --n 16 --frac 8 --json same.out --csv same.out", "--json and --csv name the same file"},
      {"sweep --n 16 --frac 8 --json ok.json --csv /proc/x.csv", "cannot write /proc/x.csv"},
      {"sweep --n 16 --frac 8 --json /sys/x.json", "cannot write /sys/x.json"},
      {"sweep --n 16 --frac 8 --json /nonexistent-dir/x.json", "no directory /nonexistent-dir"},
      {"sweep --n 16 --frac 8 --json .", "is a directory"},
      {"sweep --n 16 --frac 8 --plots /dev/null", "not a directory"},
      {"sweep --n 16 --frac 8 --plots /proc/plots", "cannot create directory /proc/plots"},
      {"fit --model phong --json ok.json --plots /proc/p", "cannot create directory /proc/p"},
      {"energy --n 16 --angles 0 --json /proc/x.json", "cannot write /proc/x.json"},
      {"cosim --trace /sys/x.fst", "cannot write /sys/x.fst"},
      {"cosim --trace /dev/null", "must be a regular file"},
      {"cosim --json o.json --trace o.json", "--json and --trace name the same file"},
      {"sweep --variant cs16 --bases --frac 8", "--bases applies to the cs16 forms only"},
      {"sweep --variant cs16_compact --bases --frac 8 --n 16", "--bases takes no --n"},
      {"sweep --variant cs16_faithful --bases --frac 8 --json /proc/x.json", "cannot write /proc/x.json"},
  };
  for (const auto& c : cases) expect_rejected(c);
}

TEST(CliHardening, ProcOutputIsRejectedBeforeTheRun) {
  // Was: accepted up front, failed after the whole 10 s run. Now: refused before anything is computed.
  const auto t0 = std::chrono::steady_clock::now();
  const CliRun r = run_cli("sweep --frac 20 --no-progress --json /proc/x.json");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_LT(s, 2.0) << "the sweep ran before the output was checked";
}

TEST(CliHardening, SocketOutputIsRefused) {
  const TempDir d;
  const std::string sock = d / "s.sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", sock.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  const CliRun r = run_cli("sweep --n 16 --frac 8 --no-progress --json " + sock);
  ::close(fd);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("not a regular file, device or FIFO"), std::string::npos) << r.err;
  struct stat st {};
  ASSERT_EQ(::lstat(sock.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode)) << "the socket was replaced";
}

TEST(CliHardening, SymlinkOutputsAreWrittenThrough) {
  const TempDir d;
  {
    std::ofstream(d / "target.json") << "old\n";
  }
  fs::create_symlink("target.json", d / "link.json");       // relative link to an existing file
  fs::create_symlink(d / "new.csv", d / "dangling.csv");    // link to a file that does not exist yet
  ::chmod((d / "target.json").c_str(), 0640);
  const CliRun r = run_cli("sweep --n 16..17 --frac 8 --no-progress --json link.json --csv dangling.csv", d.str());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(d / "link.json"));
  EXPECT_TRUE(fs::is_symlink(d / "dangling.csv"));
  EXPECT_NE(slurp(d / "target.json").find("\"quant_ulp\""), std::string::npos);
  EXPECT_EQ(slurp(d / "new.csv").rfind("n,approx_max", 0), 0u);
  struct stat st {};
  ASSERT_EQ(::stat((d / "target.json").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u) << "the target's mode bits were not kept";
  EXPECT_EQ(d.entries(), (std::set<std::string>{"dangling.csv", "link.json", "new.csv", "target.json"}));
}

TEST(CliHardening, FifoOutputIsWrittenInPlace) {
  const TempDir d;
  const std::string fifo = d / "out.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return slurp(fifo); });
  const CliRun r = run_cli("sweep --n 16..17 --frac 8 --no-progress --json " + fifo);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(reader.wait_for(std::chrono::seconds(20)), std::future_status::ready);
  EXPECT_NE(reader.get().find("\"quant_ulp\""), std::string::npos);
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced by a regular file";
  EXPECT_EQ(d.entries(), std::set<std::string>{"out.fifo"});
}

TEST(CliHardening, DeviceOutputIsWrittenInPlace) {
  struct stat before {}, after {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  const CliRun r = run_cli("sweep --n 16 --frac 8 --no-progress --json /dev/null --csv /dev/null");
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode)) << "/dev/null is no longer a device";
  EXPECT_EQ(before.st_rdev, after.st_rdev);
  EXPECT_EQ(before.st_ino, after.st_ino);
  // A device that fails the write (/dev/full) is an error, and the regular output beside it is not left.
  const TempDir d;
  const CliRun f = run_cli("sweep --n 16 --frac 8 --no-progress --csv ok.csv --json /dev/full", d.str());
  EXPECT_EQ(f.status, 1);
  EXPECT_EQ(lines(f.err), 1) << f.err;
  EXPECT_NE(f.err.find("cannot write /dev/full"), std::string::npos) << f.err;
  EXPECT_TRUE(d.entries().empty());
}

// A step after the computation fails (here the plotting script): no output at all is left — not the JSON
// or CSV written before, not the plots directory (created by the run), not a temporary file.
TEST(CliHardening, FailureAfterTheRunLeavesNoOutput) {
  const TempDir d, scripts;
  {
    std::ofstream s(scripts / "plot_sweep.py");
    s << "import os, sys\n"
         "a = sys.argv\n"
         "d = a[a.index('--dir') + 1]\n"
         "open(os.path.join(d, 'fig3_n17.png'), 'w').write('partial')\n"  // Fig. 3 at n = 17 for --n 16..17
         "sys.exit('plot_sweep.py: error: simulated failure')\n";
  }
  const CliRun r = run_shell("SHADECORE_SCRIPTS=" + scripts.str() + " " + SHADECORE_CLI +
                                 " sweep --n 16..17 --frac 8 --no-progress --json s.json --csv s.csv --plots p/q",
                             d.str());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("plotting failed: plot_sweep.py: error: simulated failure"), std::string::npos) << r.err;
  EXPECT_TRUE(d.entries().empty()) << *d.entries().begin();
}

// An existing plots directory: a failed run leaves it as it was (the old plots untouched, nothing added).
TEST(CliHardening, FailureKeepsAnExistingPlotsDirectoryAsItWas) {
  const TempDir d, scripts;
  fs::create_directories(d / "plots");
  {
    std::ofstream(d / "plots/fig3_n128.png") << "old";
    std::ofstream(scripts / "plot_sweep.py") << "import sys\nsys.exit('boom')\n";
  }
  const CliRun r = run_shell("SHADECORE_SCRIPTS=" + scripts.str() + " " + SHADECORE_CLI +
                                 " sweep --n 16 --frac 8 --no-progress --plots plots",
                             d.str());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(slurp(d / "plots/fig3_n128.png"), "old");
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(d / "plots")) left.insert(e.path().filename().string());
  EXPECT_EQ(left, std::set<std::string>{"fig3_n128.png"});
}

// Ctrl-C while the plots are drawn: one line, status 130, no traceback, no partial plot set, no JSON.
// The terminal sends SIGINT to the whole foreground process group; so does this test.
TEST(CliHardening, InterruptDuringPlotsIsCleanAndLeavesNothing) {
  const TempDir d, scripts;
  const std::string marker = scripts / "started";
  {
    std::ofstream s(scripts / "plot_sweep.py");
    s << "import os, sys, time\n"
         "a = sys.argv\n"
         "d = a[a.index('--dir') + 1]\n"
         "for name in ('fig3_n17.png', 'fig4_delta.png'):\n"  // --n 16..17: Fig. 3 at n = 17
         "    open(os.path.join(d, name), 'w').write('partial')\n"
         "open('" << marker << "', 'w').write('x')\n"
         "time.sleep(30)\n";
  }
  const std::string out = scripts / "out", err = scripts / "err";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    if (::chdir(d.str().c_str()) != 0) ::_exit(99);
    ::setenv("SHADECORE_SCRIPTS", scripts.str().c_str(), 1);
    std::freopen(out.c_str(), "w", stdout);
    std::freopen(err.c_str(), "w", stderr);
    ::execl(SHADECORE_CLI, SHADECORE_CLI, "sweep", "--n", "16..17", "--frac", "8", "--no-progress", "--json", "s.json",
            "--plots", "plots", static_cast<char*>(nullptr));
    ::_exit(98);
  }
  ::setpgid(pid, pid);
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(marker) && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(marker)) << slurp(err);
  ::kill(-pid, SIGINT);
  int st = 0;
  ::waitpid(pid, &st, 0);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 128 + SIGINT);
  const std::string e = slurp(err);
  EXPECT_EQ(e, "shadecore: interrupted\n");
  EXPECT_EQ(e.find("Traceback"), std::string::npos);
  EXPECT_LT(s, 20.0) << "the plotting child was not stopped";
  EXPECT_TRUE(d.entries().empty()) << *d.entries().begin();
}

// SIGTERM during the computation (nothing on disk yet) stops at once with one line.
TEST(CliHardening, TerminateDuringTheRunLeavesNothing) {
  const TempDir d;
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (::chdir(d.str().c_str()) != 0) ::_exit(99);
    std::freopen("/dev/null", "w", stdout);
    std::freopen((d / "..err").c_str(), "w", stderr);
    ::execl(SHADECORE_CLI, SHADECORE_CLI, "sweep", "--frac", "22", "--threads", "1", "--no-progress", "--json",
            "s.json", "--plots", "plots", static_cast<char*>(nullptr));
    ::_exit(98);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGTERM);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 128 + SIGTERM);
  EXPECT_EQ(slurp(d / "..err"), "shadecore: terminated by a signal\n");
  EXPECT_EQ(d.entries(), std::set<std::string>{"..err"});
}

TEST(CliHardening, ThreadsZeroMeansEveryCoreEverywhere) {
  const int cores = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 64);
  const TempDir d;
  const CliRun s = run_cli("sweep --n 16..17 --frac 8 --threads 0 --no-progress --json s.json", d.str());
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_NE(slurp(d / "s.json").find("\"threads\": " + std::to_string(cores)), std::string::npos);
  const CliRun e = run_cli("energy --model phong --n 16..17 --angles 0 --threads 0");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_NE(e.out.find("on " + std::to_string(cores) + " thread(s)"), std::string::npos) << e.out;
  const CliRun big = run_cli("sweep --n 16 --frac 8 --threads 64 --no-progress");
  EXPECT_EQ(big.status, 0) << big.err;  // the cap itself is accepted (and does not abort)
}

TEST(CliHardening, VersionAndHelp) {
  const CliRun v = run_cli("--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_TRUE(std::regex_search(v.out, std::regex(R"(^shadecore \d+\.\d+\.\d+\n$)"))) << v.out;
  const CliRun h = run_cli("cosim --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.out.find("--seed"), std::string::npos);
  EXPECT_TRUE(h.err.empty());
}

// Progress: drawn on stderr when it is a terminal (and erased at the end), never otherwise.
TEST(CliHardening, ProgressOnATerminalOnly) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "util-linux script not installed";
  const std::string cmd = std::string(SHADECORE_CLI) + " energy --model phong --n 16..1024 --n-step 2 --angles 0,60";
  // On a pseudo-terminal (script(1)): a bar with an ETA.
  const CliRun tty = run_shell("script -qec '" + cmd + "' /dev/null");
  ASSERT_EQ(tty.status, 0) << tty.out;
  EXPECT_NE(tty.out.find("ETA"), std::string::npos) << "no progress bar on a terminal";
  const CliRun off = run_shell("script -qec '" + cmd + " --no-progress' /dev/null");
  EXPECT_EQ(off.out.find("ETA"), std::string::npos);
  // Not a terminal: nothing on stderr.
  const CliRun pipe = run_shell(cmd);
  ASSERT_EQ(pipe.status, 0) << pipe.err;
  EXPECT_TRUE(pipe.err.empty()) << pipe.err;
  // --progress forces it (logs); the line is erased at the end.
  const CliRun forced = run_shell(cmd + " --progress");
  EXPECT_NE(forced.err.find("ETA"), std::string::npos);
  EXPECT_EQ(forced.err.substr(forced.err.size() >= 4 ? forced.err.size() - 4 : 0), "\r\033[K");
  // The sweep's bar has an ETA too.
  const CliRun sweep = run_shell("script -qec '" + std::string(SHADECORE_CLI) + " sweep --n 16..300 --frac 12' /dev/null");
  ASSERT_EQ(sweep.status, 0) << sweep.out;
  EXPECT_NE(sweep.out.find("ETA"), std::string::npos);
}

TEST(CliHardening, FitTableIsClean) {
  const CliRun s = run_cli("fit --lobe schlick --model phong");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(s.out.find("nan"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("n/a"), std::string::npos);
  EXPECT_NE(s.out.find("\n1 case in "), std::string::npos) << s.out;
  // Phong's fitted b is zero up to rounding, and some of those values are negative: the table must not
  // print them as "-0.00000".
  const TempDir d;
  const CliRun ph = run_cli("fit --model phong --json f.json", d.str());
  ASSERT_EQ(ph.status, 0) << ph.err;
  const std::string js = slurp(d / "f.json");
  bool negative_tiny = false;
  const std::regex b_re("\"b\": (-[0-9.eE+-]+)");
  for (auto it = std::sregex_iterator(js.begin(), js.end(), b_re); it != std::sregex_iterator(); ++it)
    negative_tiny |= std::fabs(std::stod((*it)[1].str())) < 5e-6;
  ASSERT_TRUE(negative_tiny) << "precondition: a negative b that rounds to zero";
  EXPECT_EQ(ph.out.find("-0.00000"), std::string::npos) << ph.out;
  EXPECT_NE(ph.out.find(" 0.00000 "), std::string::npos) << ph.out;
  const CliRun all = run_cli("fit --n 16..64");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_NE(all.out.find(" cases in "), std::string::npos);
  // Every row of the table has its column bars at the same places, double_capped rows included.
  std::stringstream ss(all.out);
  std::string line;
  std::vector<size_t> bars;
  int rows = 0, capped = 0;
  bool in_table = false;
  while (std::getline(ss, line)) {
    if (line.rfind("----", 0) == 0) {
      in_table = !in_table;
      continue;
    }
    if (!in_table && line.rfind("case ", 0) != 0) continue;
    std::vector<size_t> b;
    for (size_t i = line.find('|'); i != std::string::npos; i = line.find('|', i + 1)) b.push_back(i);
    if (bars.empty()) bars = b;
    EXPECT_EQ(b, bars) << "misaligned: " << line;
    ++rows;
    capped += line.find("double_capped") != std::string::npos;
  }
  EXPECT_GT(rows, 10);
  EXPECT_GT(capped, 0);
}

// Issue 23: a usage error of a subcommand points at that subcommand's help (`shadecore eval --help`, not
// `shadecore --help`), for every subcommand `shadecore --help` lists: unknown options, bad values, missing
// required options and bad combinations found by the subcommand itself. Errors before a subcommand is
// named keep pointing at `shadecore --help`.
TEST(CliHardening, UsageErrorsNameTheSubcommandsHelp) {
  const CliRun help = run_cli("--help");
  ASSERT_EQ(help.status, 0);
  std::vector<std::string> subs;
  const auto at = help.out.find("Subcommands:");
  ASSERT_NE(at, std::string::npos) << help.out;
  std::istringstream in(help.out.substr(at));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string name;
    if (line.rfind("  ", 0) == 0 && (ls >> name)) subs.push_back(name);
  }
  for (const char* want : {"sweep", "eval", "light-sweep", "render", "cosim"})
    EXPECT_NE(std::find(subs.begin(), subs.end(), want), subs.end()) << want << " not listed in\n" << help.out;
  for (const auto& s : subs) {
    const CliRun r = run_cli(s + " --no-such-option");
    EXPECT_EQ(r.status, 1) << s;
    EXPECT_EQ(lines(r.err), 1) << s << ": " << r.err;
    EXPECT_NE(r.err.find("(see shadecore " + s + " --help)"), std::string::npos) << s << ": " << r.err;
  }
  const std::vector<BadCase> eval_cases = {
      {"eval --code 5", "--n is required"},                  // a required option missing
      {"eval --n 5 --code 1", "out of range"},               // a bad value, found by the subcommand
      {"eval --n 64", "give exactly one of --code K and --cos X"},  // a combination
      {"eval --n 64 --code 1 --cutoff nosuch", "nosuch"},
      {"eval --n 64 --code 1 --json ''", "empty path"},
  };
  for (const auto& c : eval_cases) {
    expect_rejected(c);
    const CliRun r = run_cli(c.args);
    EXPECT_NE(r.err.find("(see shadecore eval --help)"), std::string::npos) << c.args << ": " << r.err;
  }
  for (const char* top : {"--no-such-option", "frobnicate", ""}) {
    const CliRun r = run_cli(top);
    EXPECT_NE(r.err.find("see shadecore --help)"), std::string::npos) << top << ": " << r.err;
  }
}

// Issue 23: names and paths given explicitly must not be empty (docs/cli.md) — in every subcommand but
// render (its --json and --size are cli/cmd_render.cpp's). Before, e.g. `eval --json ''` wrote nothing
// silently and `cosim --features ''` meant the full set.
TEST(CliHardening, EmptyValuesAreErrorsEverywhere) {
  const std::vector<BadCase> cases = {
      {"eval --n 64 --code 1 --json ''", "--json: empty path"},
      {"eval --n 64 --code ''", "--code: empty code"},
      {"eval --n 64 --code 1 --variant ''", "--variant: empty unit name"},
      {"eval --n 64 --code 1 --config ''", "--config: empty config name"},
      {"eval --n 64 --code 1 --cutoff ''", "--cutoff: empty cut-off"},
      {"eval --n 64 --code 1 --norm ''", "--norm: empty model"},
      {"eval --n 64 --code 1 --coef ''", "--coef: empty coefficient kind"},
      {"sweep --variant '' --n 16 --frac 8", "--variant: empty unit name"},
      {"sweep --cutoff '' --n 16 --frac 8", "--cutoff: empty cut-off"},
      {"sweep --n '' --frac 8", "--n: empty range"},
      {"cosim --variant ''", "--variant: empty unit name"},
      {"cosim --cutoff ''", "--cutoff: empty cut-off"},
      {"cosim --n ''", "--n: empty range"},
      {"cosim --mode ''", "--mode: empty mode"},
      {"cosim --norm --coef-model ''", "--coef-model: empty model"},
      {"cosim --norm --coef ''", "--coef: empty coefficient kind"},
      {"cosim --core lighting --features ''", "--features: empty feature set"},
      {"energy --model '' --n 16 --angles 0", "--model: empty model"},
      {"energy --n '' --angles 0", "--n: empty range"},
      {"energy --n 16 --angles ''", "--angles: empty angle list"},
      {"energy --n 16 --angles 0 --coef ''", "--coef: empty coefficient kind"},
      {"energy --n 16 --angles 0 --cutoff ''", "--cutoff: empty cut-off"},
      {"energy --n 16 --angles 0 --method ''", "--method: empty method"},
      {"fit --lobe ''", "--lobe: empty lobe"},
      {"fit --cutoff ''", "--cutoff: empty cut-off"},
      {"fit --model ''", "--model: empty model"},
      {"fit --n ''", "--n: empty range"},
      {"vectors --out ''", "--out: empty path"},
      {"vectors --out v.txt --mode ''", "--mode: empty mode"},
      {"vectors --out v.txt --core ''", "--core: empty core"},
      {"vectors --out v.txt --core lighting --features ''", "--features: empty feature set"},
      {"vectors --out v.txt --mode random --n ''", "--n: empty range"},
      {"vectors --out v.txt --variant ''", "--variant: empty unit name"},
      {"handoff --out ''", "--out: empty path"},
      {"handoff --out b --top ''", "--top: empty module name"},
      {"handoff --out b --synth ''", "--synth: empty synthesis mode"},
      {"handoff --out b --core ''", "--core: empty core"},
      {"handoff --out b --core lighting --features ''", "--features: empty feature set"},
      {"handoff --out b --config ''", "--config: empty config name"},
      {"light-sweep --features ''", "--features: empty feature set"},
      {"light-sweep --json ''", "--json: empty path"},
  };
  for (const auto& c : cases) expect_rejected(c);
}
