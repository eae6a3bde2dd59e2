// SPDX-License-Identifier: Apache-2.0
// Issue 10, co-simulation side: the simulator executables reject bad arguments with one line and status 1
// (no SystemC banner, not even for --help), a run that checked nothing is not a pass, the watchdog is
// named as the cause, the "reproduce with" line reproduces, the same --seed gives the same stimulus
// whatever the shard count, waveforms follow the output rules, and the CLI shows progress.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

#if defined(SHADECORE_COSIM_SIM) && defined(SHADECORE_BARE_SIM)

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

namespace {

// The banner is silenced by the simulator itself: run without the variable the ctest sim tests set.
CliRun run_sim(const std::string& args, const std::string& cwd = "") {
  return run_shell("env -u SYSTEMC_DISABLE_COPYRIGHT_MESSAGE " + std::string(SHADECORE_COSIM_SIM) + " " + args, cwd);
}

// A top-level field: in the CLI's indented JSON the top-level keys are indented by two spaces (nested
// shard results carry the same keys deeper); the simulator's one-line JSON has no nested copies.
std::string json_field(const std::string& json, const std::string& key) {
  std::smatch m;
  if (std::regex_search(json, m, std::regex("\n  \"" + key + "\": \"?([^,\"}\\n]*)"))) return m[1].str();
  if (std::regex_search(json, m, std::regex("\"" + key + "\":\"?([^,\"}\\n]*)"))) return m[1].str();
  return "";
}

}  // namespace

TEST(CosimHardening, SimulatorBadArgumentsTable) {
  struct Case {
    std::string args, needle;
  };
  const std::vector<Case> cases = {
      {"--mode random --count -1", "--count: '-1' is not an integer"},
      {"--mode random --count 0", "--count: '0' is not an integer in [1, "},
      {"--mode random --seed 99999999999999999999999", "--seed"},
      {"--inject value --inject-at 0", "--inject-at: '0' is not an integer in [1, 18446744073709551615]"},
      {"--inject-at 5", "--inject-at needs --inject"},
      {"--in-stall nan", "not a probability"},
      {"--out-stall 1", "1 would stall forever"},
      {"--mat-rate inf --mode random", "not a probability"},
      {"--reset-at -7", "--reset-at"},
      {"--no-such-option", "no-such-option"},
      {"--mode sideways", "unknown mode 'sideways'"},
      {"--n 16..99999999999999 --mode exhaustive", "out of range"},
      {"--mode directed --n 16", "--n does not apply"},
      {"--mode exhaustive --n 16 --count 3", "--count does not apply"},
      {"--mode directed --first 5", "--first applies to --mode random only"},
      {"--coef classical", "apply with --norm only"},
      {"--norm --coef-model bogus", "unknown model 'bogus'"},
      {"--norm --variant schlick_nr", "--norm is built for"},
      {"+trace=", "+trace=: empty path"},
      {"+trace=/nonexistent/x.fst", "cannot write /nonexistent/x.fst: no directory /nonexistent"},
      {"--trace /sys/x.fst", "cannot write /sys/x.fst"},
      {"+trace=a.fst --trace b.fst", "not both"},
      {"+foo", "unknown plusarg '+foo'"},
  };
  for (const auto& c : cases) {
    const TempDir d;
    const CliRun r = run_sim(c.args, d.str());
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_LT(r.err.size(), 300u) << "overlong message: " << r.err;
    EXPECT_EQ(r.out.find("COSIM-RESULT"), std::string::npos) << c.args;
    EXPECT_EQ((r.out + r.err).find("SystemC"), std::string::npos) << "banner printed: " << c.args;
    EXPECT_TRUE(d.entries().empty()) << c.args;
  }
}

TEST(CosimHardening, SimulatorHelpHasNoBanner) {
  const CliRun r = run_sim("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--mode"), std::string::npos);
  EXPECT_EQ((r.out + r.err).find("SystemC"), std::string::npos) << r.out << r.err;
  EXPECT_EQ((r.out + r.err).find("Copyright"), std::string::npos);
}

TEST(CosimHardening, BareHarnessArguments) {
  const std::string bare = SHADECORE_BARE_SIM;
  for (const auto& [args, needle] : std::vector<std::pair<std::string, std::string>>{
           {"--n abc", "malformed range 'abc'"},
           {"--n 0..5", "n = 0 out of range"},
           {"--n 1024..16", "LO > HI"},
           {"--n", "--n needs a value"},
           {"--frob", "unknown argument '--frob'"}}) {
    const CliRun r = run_shell(bare + " " + args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(r.out.find("PASS"), std::string::npos) << args;
  }
  const CliRun ok = run_shell(bare + " --n 16");
  EXPECT_EQ(ok.status, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("bare: PASS"), std::string::npos);
}

// A run that checked nothing (the only transaction dropped by the reset, not sent again) is not a pass.
TEST(CosimHardening, NothingCheckedIsNotAPass) {
  const CliRun r = run_sim("--mode random --count 1 --reset-at 1 --no-resend --seed 3");
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("cosim: FAIL (no vector was checked)"), std::string::npos) << r.out;
}

// --out-stall just below 1 (inside the range): the watchdog stops the run and is reported as the cause,
// by the simulator and by the CLI (one stderr line, status 2).
TEST(CosimHardening, WatchdogIsTheReportedCause) {
  const CliRun s = run_sim("--mode directed --count 10 --out-stall 0.99999999 --seed 3");
  EXPECT_EQ(s.status, 2);
  EXPECT_NE(s.out.find("cosim: FAIL (watchdog: no transfer for 200000 cycles)"), std::string::npos) << s.out;
  const TempDir d;
  const CliRun c = run_cli("cosim --config narrow --mode directed --out-stall 0.99999999 --seed 3 --json w.json", d.str());
  EXPECT_EQ(c.status, 2) << c.err;
  EXPECT_EQ(lines(c.err), 1) << c.err;
  EXPECT_NE(c.err.find("co-simulation FAILED: watchdog: no transfer for 200000 cycles"), std::string::npos) << c.err;
  // A FAIL verdict is a completed run: the JSON records it.
  EXPECT_EQ(json_field(slurp(d / "w.json"), "ok"), "false");
  EXPECT_NE(json_field(slurp(d / "w.json"), "cause").find("watchdog"), std::string::npos);
}

// The "reproduce with" line of a failing run (seed picked by the run) is a command that reproduces it.
TEST(CosimHardening, ReproduceLineReproduces) {
  const CliRun r = run_sim("--mode random --count 3000 --seed 0 --out-stall 0.3 --inject value --inject-at 200");
  ASSERT_EQ(r.status, 2) << r.out << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("cosim: reproduce with: ([^\\n]*)"))) << r.out;
  const std::string cmd = m[1].str();
  EXPECT_EQ(std::regex_search(cmd, std::regex("--seed .*--seed")), false) << cmd;
  std::smatch mm;
  ASSERT_TRUE(std::regex_search(r.out, mm, std::regex("MISMATCH [^\\n]*"))) << r.out;
  const CliRun again = run_shell(cmd);
  EXPECT_EQ(again.status, 2) << cmd << "\n" << again.err;
  EXPECT_NE(again.out.find(mm[0].str()), std::string::npos) << "not the same mismatch:\n" << again.out;
  EXPECT_EQ(json_field(again.out, "stimulus_digest"), json_field(r.out, "stimulus_digest"));
  EXPECT_EQ(json_field(again.out, "cycles"), json_field(r.out, "cycles"));
}

// One seed, one stimulus: the transactions are the same for 1, 2 and 3 shards (the digest sums a hash of
// every (index, n, code)); another seed gives another stimulus.
TEST(CosimHardening, SameSeedSameStimulusWhateverTheShardCount) {
  const TempDir d;
  std::vector<std::string> digests;
  for (const std::string shards : {"1", "2", "3"}) {
    const std::string j = d / ("r" + shards + ".json");
    const CliRun r = run_cli("cosim --config narrow --mode random --count 6000 --in-stall 0.2 --out-stall 0.2 --seed 77 "
                             "--shards " + shards + " --json " + j);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    const std::string js = slurp(j);
    EXPECT_EQ(json_field(js, "shards"), shards);
    digests.push_back(json_field(js, "stimulus_digest"));
  }
  EXPECT_FALSE(digests[0].empty());
  EXPECT_EQ(digests[0], digests[1]);
  EXPECT_EQ(digests[0], digests[2]);
  const CliRun other = run_cli("cosim --config narrow --mode random --count 6000 --seed 78 --shards 1 --json " +
                               (d / "o.json"));
  ASSERT_EQ(other.status, 0) << other.err;
  EXPECT_NE(json_field(slurp(d / "o.json"), "stimulus_digest"), digests[0]);
  // Exhaustive: the n range split over shards is the same set of vectors.
  std::vector<std::string> ex;
  for (const std::string shards : {"1", "3"}) {
    const std::string j = d / ("e" + shards + ".json");
    ASSERT_EQ(run_cli("cosim --config narrow --mode exhaustive --n 16..21 --shards " + shards + " --json " + j).status, 0);
    ex.push_back(json_field(slurp(j), "stimulus_digest"));
  }
  EXPECT_EQ(ex[0], ex[1]);
}

// Issue 22: the material changes and the mid-stream reset are stimulus, functions of (seed, transaction
// index): split into 1, 2 or 3 shards (the reset falls inside one of them, different timing per shard) the
// run checks the same number of vectors — every index once, the flushed ones sent again — with the same
// digest, and the reset shard reports the transactions it sent again.
TEST(CosimHardening, ShardedRunChecksTheSameVectorsAsOneProcess) {
  const TempDir d;
  std::vector<std::string> vectors, digests, mism;
  uint64_t replayed = 0;
  for (const std::string shards : {"1", "2", "3"}) {
    const std::string j = d / ("m" + shards + ".json");
    const CliRun r = run_cli("cosim --config narrow --variant table256 --mode random --count 7001 --mat-rate 0.02 "
                             "--in-stall 0.3 --out-stall 0.4 --seed 2222 --shards " + shards + " --json " + j);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    const std::string js = slurp(j);
    vectors.push_back(json_field(js, "vectors"));
    digests.push_back(json_field(js, "stimulus_digest"));
    mism.push_back(json_field(js, "mismatches"));
    for (size_t at = 0; (at = js.find("\"replayed_after_reset\": ", at)) != std::string::npos; ++at)
      replayed += std::stoull(js.substr(at + 24));
  }
  EXPECT_EQ(vectors[0], "7001");  // every transaction checked once, the reset's flushed ones included
  EXPECT_EQ(vectors[1], vectors[0]);
  EXPECT_EQ(vectors[2], vectors[0]);
  EXPECT_EQ(digests[1], digests[0]);
  EXPECT_EQ(digests[2], digests[0]);
  EXPECT_EQ(mism[0], "0");
  EXPECT_GT(replayed, 0u) << "with out_ready low 40 % of the cycles the reset must catch transactions in flight";
}

// One stimulus generator (stimulus/specular.hpp): `shadecore vectors --seed S` writes the codes that
// `shadecore cosim --seed S` drives, transaction for transaction (the same stimulus digest), for cs16 and a
// Schlick unit; another seed, another digest.
TEST(CosimHardening, VectorsAndCosimDriveTheSameStimulus) {
  const TempDir d;
  auto digest_line = [](const std::string& out) {
    std::smatch m;
    return std::regex_search(out, m, std::regex("stimulus digest ([0-9]+)")) ? m[1].str() : std::string();
  };
  for (const std::string variant : {"cs16", "schlick_nr"}) {
    SCOPED_TRACE(variant);
    const std::string j = d / ("c_" + variant + ".json"), hex = d / ("v_" + variant + ".hex");
    const CliRun c = run_cli("cosim --variant " + variant + " --config narrow --mode random --count 3000 --seed 77 "
                             "--in-stall 0.2 --out-stall 0.2 --shards 2 --json " + j);
    ASSERT_EQ(c.status, 0) << c.out << c.err;
    const CliRun v = run_cli("vectors --variant " + variant + " --config narrow --mode random --count 3000 --seed 77 --out " + hex);
    ASSERT_EQ(v.status, 0) << v.out << v.err;
    const std::string dv = digest_line(v.out);
    ASSERT_FALSE(dv.empty()) << v.out;
    EXPECT_EQ(dv, json_field(slurp(j), "stimulus_digest"));
    EXPECT_EQ(digest_line(slurp(hex)), dv);  // the file's header records it
    const CliRun o = run_cli("vectors --variant " + variant + " --config narrow --mode random --count 3000 --seed 78 --out " +
                             (d / "o.hex"));
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_NE(digest_line(o.out), dv);
  }
}

// Waveforms: written through a temporary file and renamed (no stray file), also when the run FAILS (the
// waveform is its evidence); the CLI's --trace likewise.
TEST(CosimHardening, TraceFollowsTheOutputRules) {
  const TempDir d;
  const CliRun ok = run_sim("--mode directed --count 50 +trace=w.fst", d.str());
  ASSERT_EQ(ok.status, 0) << ok.out << ok.err;
  EXPECT_GT(fs::file_size(d / "w.fst"), 0u);
  EXPECT_NE(ok.out.find("waveform written to w.fst"), std::string::npos);
  const CliRun bad = run_sim("--mode random --count 500 --seed 5 --inject drop --inject-at 10 --trace f.fst", d.str());
  EXPECT_EQ(bad.status, 2);
  EXPECT_GT(fs::file_size(d / "f.fst"), 0u);
  const CliRun cli = run_cli("cosim --config narrow --mode random --count 200 --seed 4 --trace c.fst --json c.json", d.str());
  ASSERT_EQ(cli.status, 0) << cli.err;
  EXPECT_GT(fs::file_size(d / "c.fst"), 0u);
  EXPECT_EQ(d.entries(), (std::set<std::string>{"c.fst", "c.json", "f.fst", "w.fst"}));
}

TEST(CosimHardening, CliShowsProgressAndNamesTheNormModel) {
  const CliRun r = run_cli("cosim --config narrow --mode random --count 400000 --shards 2 --seed 9 --progress");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("ETA"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cosim ["), std::string::npos);
  const CliRun quiet = run_cli("cosim --config narrow --mode random --count 1000 --seed 9");
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
  const CliRun n = run_cli("cosim --config narrow --norm --coef-model blinn --coef classical --mode exhaustive --n 16");
  ASSERT_EQ(n.status, 0) << n.err;
  EXPECT_NE(n.out.find("norm: blinn classical coefficient"), std::string::npos) << n.out;
  const CliRun all = run_cli("cosim --config narrow --norm --mode exhaustive --n 16");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_NE(all.out.find("norm: every model and kind"), std::string::npos) << all.out;
}

// The simulators themselves show progress on stderr (on a terminal, or with --progress), never in a pipe.
TEST(CosimHardening, SimulatorsShowProgress) {
  const CliRun sim = run_sim("--mode random --count 300000 --seed 5 --progress");
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;
  EXPECT_NE(sim.err.find("ETA"), std::string::npos) << sim.err;
  const CliRun quiet = run_sim("--mode random --count 300000 --seed 5");
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
  if (std::system("command -v script >/dev/null 2>&1") == 0) {
    const CliRun tty = run_shell("script -qec '" + std::string(SHADECORE_COSIM_SIM) +
                                 " --mode random --count 300000 --seed 5' /dev/null");
    EXPECT_NE(tty.out.find("ETA"), std::string::npos) << "no progress on a terminal";
  }
  const CliRun bare = run_shell(std::string(SHADECORE_BARE_SIM) + " --n 16..60 --progress");
  ASSERT_EQ(bare.status, 0) << bare.err;
  EXPECT_NE(bare.err.find("ETA"), std::string::npos) << bare.err;
}

// Ctrl-C during a co-simulation with a waveform: the simulators are stopped, one line, status 130, and
// neither the waveform nor the JSON nor a temporary file is left.
TEST(CosimHardening, InterruptLeavesNoWaveform) {
  const TempDir d;
  const std::string err = d.str() + ".err";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    if (::chdir(d.str().c_str()) != 0) ::_exit(99);
    std::freopen("/dev/null", "w", stdout);
    std::freopen(err.c_str(), "w", stderr);
    ::execl(SHADECORE_CLI, SHADECORE_CLI, "cosim", "--config", "narrow", "--mode", "random", "--count", "50000000",
            "--seed", "3", "--trace", "t.fst", "--json", "t.json", static_cast<char*>(nullptr));
    ::_exit(98);
  }
  ::setpgid(pid, pid);
  // Wait until the simulator is writing its waveform (its temporary file is in the directory).
  const auto writing = [&] {
    for (const auto& e : d.entries())
      if (e.find(".part.") != std::string::npos) return true;
    return false;
  };
  const auto t0 = std::chrono::steady_clock::now();
  while (!writing() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(writing()) << slurp(err);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(-pid, SIGINT);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 128 + SIGINT);
  EXPECT_EQ(slurp(err), "shadecore: interrupted\n");
  EXPECT_TRUE(d.entries().empty()) << *d.entries().begin();
  fs::remove(err);
}

#endif
