// SPDX-License-Identifier: Apache-2.0
// The first hour of a new user (issue 38): help texts that list everything an option takes, a missing file
// called a missing file, a "did you mean" for a mistyped feature-set name.
#include <gtest/gtest.h>

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
