// SPDX-License-Identifier: Apache-2.0
// The one subprocess runner (common/include/shadecore/common/subprocess.hpp, issue 22): captured and
// interleaved streams, line callbacks, log files, a missing program, several children at once, and a
// child leading its own process group stopped with its whole tree.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "shadecore/common/subprocess.hpp"

namespace {
using shadecore::proc::Options;
using shadecore::proc::Pool;
using shadecore::proc::run;

TEST(Subprocess, CapturesStdoutAndStderrApartOrInterleaved) {
  const auto r = run({"sh", "-c", "echo out1; echo err1 >&2; echo out2; exit 3"});
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(r.out, "out1\nout2\n");
  EXPECT_EQ(r.err, "err1\n");
  EXPECT_EQ(r.last_line(), "err1");
  Options o;
  o.merge_stderr = true;
  const auto m = run({"sh", "-c", "echo a; sleep 0.05; echo b >&2; sleep 0.05; echo c"}, o);
  EXPECT_EQ(m.status, 0);
  EXPECT_EQ(m.out, "a\nb\nc\n");  // in the order the child wrote them
  EXPECT_TRUE(m.err.empty());
}

TEST(Subprocess, LineCallbackLogFileEnvironmentAndMissingProgram) {
  std::vector<std::string> lines;
  Options o;
  o.on_line = [&](const std::string& l) { lines.push_back(l); };
  o.env = {{"SC_TEST_VALUE", "42"}};
  const auto r = run({"sh", "-c", "echo one; printf 'two\\nthree'; echo $SC_TEST_VALUE >&2"}, o);
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(lines, (std::vector<std::string>{"one\n", "two\n", "three"}));
  EXPECT_EQ(r.err, "42\n");
  char tmpl[] = "/tmp/sc_subproc_XXXXXX";
  const int fd = ::mkstemp(tmpl);
  ASSERT_GE(fd, 0);
  ::close(fd);
  Options l;
  l.log_path = tmpl;
  EXPECT_EQ(run({"sh", "-c", "echo to-log; echo err-log >&2"}, l).status, 0);
  std::ifstream in(tmpl);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "to-log\nerr-log\n");
  std::remove(tmpl);
  const auto missing = run({"/nonexistent/shadecore-no-such-tool"});
  EXPECT_EQ(missing.status, 127);
  EXPECT_NE(missing.err.find("cannot run"), std::string::npos);
}

TEST(Subprocess, PoolRunsSeveralAtOnceAndStopsAWholeGroup) {
  Pool p;
  const auto t0 = std::chrono::steady_clock::now();
  const size_t a = p.start({"sh", "-c", "sleep 0.3; echo A"});
  const size_t b = p.start({"sh", "-c", "sleep 0.3; echo B"});
  while (p.running() > 0) p.poll(-1);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, 0.55) << "the two children ran one after the other";
  EXPECT_EQ(p.result(a).out, "A\n");
  EXPECT_EQ(p.result(b).out, "B\n");
  // A child leading its own group, with a grandchild holding the pipe: terminate() stops both, and the
  // pool sees the end (a grandchild left alive would keep the pipe open and the poll loop waiting).
  Options g;
  g.own_group = true;
  const size_t c = p.start({"sh", "-c", "sleep 30 & sleep 30; echo never"}, g);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  p.terminate(c);
  const auto t1 = std::chrono::steady_clock::now();
  while (!p.finished(c)) p.poll(200);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), 5.0);
  EXPECT_EQ(p.result(c).status, 128 + SIGTERM);
  EXPECT_TRUE(p.result(c).out.empty());
}

}  // namespace
