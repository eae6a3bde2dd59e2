// SPDX-License-Identifier: Apache-2.0
// The first hour of a new user (issue 38): help texts that list everything an option takes, a missing file
// called a missing file, a "did you mean" for a mistyped feature-set name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_run.hpp"
#include "shadecore/analysis/sweep.hpp"

namespace shadecore::testing {
namespace {

TEST(CliFriction, SweepHelpListsEveryVariant) {
  const CliRun r = run_cli("sweep --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const std::string& v : sweep_variants())
    EXPECT_NE(r.out.find(v), std::string::npos) << "sweep --help does not name " << v << "\n" << r.out;
}

TEST(CliFriction, MissingFeatureFileSaysNoSuchFile) {
  for (const std::string f : {"nope.json", "/nonexistent-dir/set.json", "./set"}) {
    expect_one_line_error("light-sweep --features " + f, "No such file or directory");
    const CliRun r = run_cli("light-sweep --features " + f);
    EXPECT_EQ(r.err.find("unknown feature set"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("feature set file '" + f + "'"), std::string::npos) << r.err;
  }
}

TEST(CliFriction, UnknownFeatureSetNameSuggestsTheNearest) {
  expect_one_line_error("light-sweep --features difuse", "unknown feature set 'difuse' (did you mean 'diffuse'?)");
  expect_one_line_error("light-sweep --features ful", "(did you mean 'full'?)");
  const CliRun r = run_cli("light-sweep --features zzzzzzzz");
  EXPECT_NE(r.err.find("unknown feature set 'zzzzzzzz'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace shadecore::testing

namespace shadecore::testing {
namespace {

// light-sweep --specular all: units whose rows print the same figures get a note saying each was run.
TEST(CliFriction, LightSweepNotesIdenticalRows) {
  const CliRun r = run_cli("light-sweep --features gl_default --specular all --seed 1 --programs 5 --per-program 100");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("note: schlick_div, schlick_nr, schlick_iter print identical rows. Each unit was run in turn"),
            std::string::npos)
      << r.out;
  const CliRun one = run_cli("light-sweep --features gl_default --seed 1 --programs 5 --per-program 100");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(one.out.find("identical rows"), std::string::npos) << one.out;
}

// A refusal says what the user can do instead.
TEST(CliFriction, CosimLightingRefusalSaysWhatToDo) {
  expect_one_line_error("cosim --core lighting --variant cs16", "(choose one with --features NAME|FILE");
  const CliRun r = run_cli("cosim --core lighting --n 64");
  EXPECT_EQ(r.err.find("says it"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace shadecore::testing

namespace shadecore::testing {
namespace {

// An option typo: the unknown option named, with the subcommand's nearest option.
TEST(CliFriction, UnknownOptionSuggestsTheNearest) {
  expect_one_line_error("eval --varient cs16 --n 16 --code 0",
                        "unknown option '--varient' (did you mean '--variant'?) (see shadecore eval --help)");
  expect_one_line_error("sweep --thread 2", "unknown option '--thread' (did you mean '--threads'?)");
  expect_one_line_error("light-sweep --program=3", "unknown option '--program' (did you mean '--programs'?)");
  const CliRun r = run_cli("eval --zzzzzzzz --n 16 --code 0");
  EXPECT_NE(r.err.find("unknown option '--zzzzzzzz' (see shadecore eval --help)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace shadecore::testing

namespace shadecore::testing {
namespace {

// One name for one thing: `cosim --core specular|lighting` as `vectors` and `handoff`; `unit` kept as an alias.
TEST(CliFriction, CosimCoreIsSpecularOrLightingWithUnitAsAlias) {
  const CliRun h = run_cli("cosim --help");
  ASSERT_EQ(h.status, 0);
  EXPECT_NE(h.out.find("specular (default"), std::string::npos) << h.out;
  EXPECT_NE(h.out.find("'unit' is a deprecated alias"), std::string::npos) << h.out;
  for (const char* core : {"specular", "unit"})
    expect_one_line_error(std::string("cosim --core ") + core + " --variant nosuch", "unknown variant 'nosuch'");
  expect_one_line_error("cosim --core spec", "--core");
}

}  // namespace
}  // namespace shadecore::testing

#ifdef SHADECORE_COSIM_SIM  // with the RTL: the lighting core's build
namespace shadecore::testing {
namespace {

// The first RTL use of a feature set says that it builds the core, where it is cached and how long the last core
// build took. The build is started in a scratch cache and stopped (its whole process group) once the line is out.
TEST(CliFriction, FirstRtlUseSaysItBuildsWhereAndHowLong) {
  const TempDir d;
  std::filesystem::create_directories(d / "cache");
  std::ofstream(d / "cache/.last_build_seconds") << "71";
  const std::string cmd = "SHADECORE_CORE_CACHE=" + (d / "cache") + " setsid " + SHADECORE_CLI +
                          " cosim --core lighting --features diffuse --mode random --count 10 --seed 1 >" + (d / "out") +
                          " 2>" + (d / "err") + " & pid=$!; i=0; while [ $i -lt 150 ] && ! grep -q 'building its core' " +
                          (d / "err") + "; do sleep 0.2; i=$((i+1)); done; kill -TERM -$pid; wait $pid; cat " + (d / "err");
  const CliRun r = run_shell(cmd);
  EXPECT_NE(r.out.find("shadecore: first use of this feature set: building its core into " + (d / "cache") + "/"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("(cached there for later runs); the last core build here took 71 s"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace shadecore::testing
#endif
