// SPDX-License-Identifier: Apache-2.0
// The apitrace capture reader (shadecore/glfront/trace.hpp): captures built byte by byte (every value tag, the
// version differences, signatures given once and reused) and every way a file can be bad; and a real capture of
// glxgears made here (skipped with a note without apitrace, mesa-utils and xvfb).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "replay_capture.hpp"
#include "shadecore/glfront/trace.hpp"

namespace {

using shadecore::trace::Call;
using shadecore::trace::Reader;
using shadecore::trace::TraceError;
using shadecore::trace::Value;
using Kind = Value::Kind;

using shadecore::test::container;
using shadecore::test::Stream;

// Version 6 header with one property.
Stream header6() {
  Stream s;
  s.uint(6).uint(6).str("process.name").str("/usr/bin/test").str("");
  return s;
}

std::vector<Call> read_all(const std::string& file) {
  Reader r(file, "t.trace");
  std::vector<Call> out;
  Call c;
  while (r.next(c)) out.push_back(c);
  return out;
}

std::string error_of(const std::string& file) {
  try {
    (void)read_all(file);
  } catch (const TraceError& e) {
    return e.what();
  }
  return "";
}

TEST(ReplayTrace, ReadsEveryValueTagOfVersion6) {
  Stream s = header6();
  // call 0: glLightfv(light = enum GL_LIGHT0, pname = enum GL_POSITION, params = {5.f, 5.f, 10.0, 0}) — enum
  // signature 0 with two names, the second enum use of id 0 with only its value
  s.byte(0).uint(0).uint(0).str("glLightfv").uint(3).str("light").str("pname").str("params");
  s.byte(1).uint(0).byte(9).uint(0).uint(2).str("GL_LIGHT0").byte(4).uint(0x4000).str("GL_LIGHT1").byte(4).uint(0x4001)
      .byte(4).uint(0x4000);
  s.byte(1).uint(1).byte(9).uint(1).uint(1).str("GL_POSITION").byte(4).uint(0x1203).byte(4).uint(0x1203);
  s.byte(1).uint(2).byte(0x0b).uint(4).byte(5).f32(5).byte(5).f32(5).byte(6).f64(10).byte(4).uint(0);
  s.byte(0);
  s.byte(1).uint(0).byte(0);  // leave
  // call 1: glLightfv again (signature by id), GL_LIGHT1 by the enum id alone, a negative int, a blob, a struct, a
  // repr, an opaque pointer, a bitmask, a wide string, null, true/false; a return value; the fake flag
  s.byte(0).uint(0).uint(0);
  s.byte(1).uint(0).byte(9).uint(0).byte(4).uint(0x4001);
  s.byte(1).uint(1).byte(0x0b).uint(7).byte(3).uint(7).byte(8).str(std::string("\x01\x00\x02", 3)).byte(0x0c).uint(0)
      .str("Visual").uint(2).str("depth").str("id").byte(4).uint(24).byte(4).uint(9)
      .byte(0x0e).byte(7).str("GL_FOO").byte(4).uint(42).byte(0x0d).uint(0xdead).byte(0x0a).uint(0).uint(1).str("BIT0")
      .uint(1).uint(5).byte(0x0f).uint(2).uint(0x41).uint(0x416);
  s.byte(1).uint(2).byte(0);
  s.byte(5).uint(1);
  s.byte(0);
  s.byte(1).uint(1).byte(2).byte(2).byte(0);
  const auto calls = read_all(container(s.b));
  ASSERT_EQ(calls.size(), 2u);
  const Call& a = calls[0];
  EXPECT_EQ(a.no, 0u);
  EXPECT_EQ(a.name(), "glLightfv");
  ASSERT_EQ(a.sig->arg_names.size(), 3u);
  EXPECT_EQ(a.sig->arg_names[2], "params");
  EXPECT_EQ(a.arg(0).kind, Kind::Enum);
  EXPECT_EQ(a.arg(0).s, "GL_LIGHT0");
  EXPECT_EQ(a.arg(0).integer(), 0x4000);
  EXPECT_EQ(a.arg(1).s, "GL_POSITION");
  ASSERT_EQ(a.arg(2).items.size(), 4u);
  EXPECT_EQ(a.arg(2).items[0].kind, Kind::Float);
  EXPECT_EQ(a.arg(2).items[2].kind, Kind::Double);
  EXPECT_DOUBLE_EQ(a.arg(2).items[2].number(), 10.0);
  EXPECT_FALSE(a.fake);
  const Call& b = calls[1];
  EXPECT_EQ(b.no, 1u);
  EXPECT_EQ(b.sig.get(), a.sig.get());  // one signature, shared
  EXPECT_EQ(b.arg(0).s, "GL_LIGHT1");
  const auto& it = b.arg(1).items;
  ASSERT_EQ(it.size(), 7u);
  EXPECT_EQ(it[0].integer(), -7);
  EXPECT_EQ(it[1].kind, Kind::Blob);
  EXPECT_EQ(it[1].s, std::string("\x01\x00\x02", 3));
  EXPECT_EQ(it[2].kind, Kind::Struct);
  EXPECT_EQ(it[2].s, "Visual");
  ASSERT_EQ(it[2].items.size(), 2u);
  EXPECT_EQ(it[2].items[1].integer(), 9);
  EXPECT_EQ(it[3].kind, Kind::Repr);
  EXPECT_EQ(it[3].integer(), 42);  // the machine value
  EXPECT_EQ(it[4].kind, Kind::Opaque);
  EXPECT_EQ(it[4].i, 0xdead);
  EXPECT_EQ(it[5].kind, Kind::Bitmask);
  EXPECT_EQ(it[5].integer(), 5);
  EXPECT_EQ(it[6].kind, Kind::WString);
  EXPECT_EQ(it[6].s, "A\xd0\x96");  // U+0041, U+0416 as UTF-8
  EXPECT_EQ(b.arg(2).kind, Kind::Null);
  EXPECT_TRUE(b.fake);
  ASSERT_TRUE(b.has_ret);
  EXPECT_EQ(b.ret.kind, Kind::Bool);
  EXPECT_EQ(b.ret.integer(), 1);
  EXPECT_THROW((void)b.arg(5), TraceError);
}

TEST(ReplayTrace, ChunksSplitAnywhereReadTheSame) {
  Stream s = header6();
  for (int k = 0; k < 50; ++k) {
    s.byte(0).uint(0).uint(0);
    if (k == 0) s.str("glVertex3f").uint(3).str("x").str("y").str("z");
    s.byte(1).uint(0).byte(5).f32(static_cast<float>(k)).byte(1).uint(1).byte(5).f32(1).byte(1).uint(2).byte(5).f32(2)
        .byte(0);
    s.byte(1).uint(k).byte(0);
  }
  const auto one = read_all(container(s.b));
  const auto tiny = read_all(container(s.b, 7));  // values and strings cut across chunks
  ASSERT_EQ(one.size(), 50u);
  ASSERT_EQ(tiny.size(), 50u);
  for (size_t k = 0; k < 50; ++k) {
    EXPECT_EQ(tiny[k].no, k);
    EXPECT_EQ(tiny[k].arg(0).number(), static_cast<double>(k));
  }
}

TEST(ReplayTrace, OlderVersionsThreadDetailAndSingleNameEnums) {
  // version 2: no properties, no thread on enter (a thread detail instead), enum signatures of one name/value
  Stream s;
  s.uint(2);
  s.byte(0).uint(0).str("glEnable").uint(1).str("cap");
  s.byte(3).uint(4).byte(1).uint(0).byte(9).uint(3).str("GL_LIGHTING").byte(4).uint(0x0B50).byte(0);
  s.byte(1).uint(0).byte(0);
  s.byte(0).uint(0).byte(1).uint(0).byte(9).uint(3).byte(0);  // the enum by id: its one value
  s.byte(1).uint(1).byte(0);
  Reader r(container(s.b), "v2.trace");
  EXPECT_EQ(r.version(), 2u);
  EXPECT_TRUE(r.properties().empty());
  Call c;
  ASSERT_TRUE(r.next(c));
  EXPECT_EQ(c.thread, 4u);
  EXPECT_EQ(c.arg(0).s, "GL_LIGHTING");
  ASSERT_TRUE(r.next(c));
  EXPECT_EQ(c.arg(0).integer(), 0x0B50);
  EXPECT_FALSE(r.next(c));
}

TEST(ReplayTrace, CallsLeftOpenAtTheEndAreIncomplete) {
  Stream s = header6();
  s.byte(0).uint(0).uint(0).str("glXSwapBuffers").uint(0).byte(0);  // entered, never left (program killed)
  const auto calls = read_all(container(s.b));
  ASSERT_EQ(calls.size(), 1u);
  EXPECT_TRUE(calls[0].incomplete);
  EXPECT_EQ(calls[0].name(), "glXSwapBuffers");
}

// A program killed while apitrace writes leaves its last event cut: at the end of a chunk (the event goes on in a
// chunk never written: what `timeout 3 glxgears` left on a loaded CI machine) or inside the last chunk. The calls
// before it are read, the cut event is dropped (a cut leave leaves its call open, so it comes back incomplete) and
// cut() says where, as glretrace plays such files; a cut inside the header stays an error.
TEST(ReplayTrace, LastEventCutIsDroppedAndReported) {
  Stream s = header6();
  s.byte(0).uint(0).uint(0).str("glFlush").uint(0).byte(0).byte(1).uint(0).byte(0);  // call 0, whole
  const size_t whole = s.b.size();
  s.byte(0).uint(0).uint(0).byte(0).byte(1).uint(1).byte(0);  // call 1 = glFlush again, whole
  const size_t second = s.b.size();
  s.byte(0).uint(0).uint(1).str("glClear").uint(1).str("mask").byte(1).uint(0).byte(4).uint(0x4100).byte(0);
  s.byte(1).uint(2).byte(0);  // call 2, whole
  const std::string full = s.b;
  for (size_t end = second + 1; end < full.size(); ++end) {  // every cut inside call 2's two events
    if (end == full.size() - 3) continue;                     // between them: below
    const std::string cut_stream = full.substr(0, end);
    for (size_t chunk : {size_t{7}, size_t{1} << 20}) {  // many small chunks, or one
      Reader r(container(cut_stream, chunk), "t.trace");
      std::vector<Call> calls;
      Call c;
      while (r.next(c)) calls.push_back(c);
      const bool leave_cut = end > full.size() - 3;  // the enter was whole: call 2 stays open
      ASSERT_EQ(calls.size(), leave_cut ? 3u : 2u) << end;
      EXPECT_FALSE(calls[1].incomplete);
      if (leave_cut) {
        EXPECT_TRUE(calls[2].incomplete);
        EXPECT_EQ(calls[2].name(), "glClear");
      }
      const Reader::Cut k = r.cut();
      EXPECT_TRUE(k.cut) << end;
      EXPECT_EQ(k.call, end == full.size() - 2 ? ~0ull : 2u) << end;  // a leave cut before its call number
      EXPECT_EQ(k.event_byte, leave_cut ? full.size() - 3 : second) << end;
    }
  }
  // the whole stream and a stream cut between events (after call 2's enter: it comes back incomplete): no cut
  for (const std::string& b : {full, full.substr(0, whole), full.substr(0, second), full.substr(0, full.size() - 3)}) {
    Reader r(container(b), "t.trace");
    Call c;
    while (r.next(c)) {
    }
    EXPECT_FALSE(r.cut().cut);
  }
  // the chunk the cut event goes on in is missing entirely: the file ends on a whole chunk
  const std::string two = container(full, second + 4);
  const uint32_t first_len = static_cast<uint8_t>(two[2]) | static_cast<uint8_t>(two[3]) << 8 |
                             static_cast<uint8_t>(two[4]) << 16 | static_cast<uint8_t>(two[5]) << 24;
  const auto calls = read_all(two.substr(0, 6 + first_len));
  EXPECT_EQ(calls.size(), 2u);
}

TEST(ReplayTrace, RejectsBadFilesWithOneLine) {
  Stream good = header6();
  good.byte(0).uint(0).uint(0).str("glFlush").uint(0).byte(0).byte(1).uint(0).byte(0);
  const std::string file = container(good.b);
  std::map<std::string, std::pair<std::string, std::string>> cases;  // name → (bytes, expected message part)
  cases["empty"] = {"", "not an apitrace capture"};
  cases["text"] = {"hello world", "not an apitrace capture"};
  cases["gzip"] = {std::string("\x1f\x8b\x08\x00", 4), "gzip-compressed"};
  cases["header only"] = {"at", "no data after its header"};
  cases["length cut"] = {file.substr(0, 4), "truncated: chunk 0"};
  cases["data cut"] = {file.substr(0, file.size() - 3), "truncated: chunk 0"};
  std::string corrupt = file;
  corrupt[6] = static_cast<char>(0xff);  // the Snappy preamble (uncompressed length) becomes nonsense
  corrupt[7] = static_cast<char>(0xff);
  cases["snappy"] = {corrupt, "not valid Snappy data"};
  cases["version 7"] = {container(Stream().uint(7).uint(7).str("").b), "trace version 7 is not read (versions 0 to 6 are)"};
  cases["event"] = {container(header6().byte(7).b), "unknown event 0x07"};
  cases["header cut"] = {container(Stream().uint(6).uint(6).str("process.name").uint(40).b),
                         "truncated: the stream ends inside an event"};
  cases["tag"] = {container(header6().byte(0).uint(0).uint(0).str("f").uint(1).str("a").byte(1).uint(0).byte(0x1f).b),
                  "unknown value tag 0x1f"};
  cases["detail"] = {container(header6().byte(0).uint(0).uint(0).str("f").uint(0).byte(9).b), "unknown call detail 0x09"};
  cases["leave"] = {container(header6().byte(1).uint(5).byte(0).b), "leave of call 5, which is not open"};
  Stream deep = header6();
  deep.byte(0).uint(0).uint(0).str("f").uint(1).str("a").byte(1).uint(0);
  for (int k = 0; k < 100; ++k) deep.byte(0x0b).uint(1);
  cases["nesting"] = {container(deep.b), "nested more than 64 deep"};
  cases["varint"] = {container(Stream().byte(0xff).byte(0xff).byte(0xff).byte(0xff).byte(0xff).byte(0xff).byte(0xff)
                                   .byte(0xff).byte(0xff).byte(0xff).byte(0x01).b),
                     "longer than 64 bits"};
  for (const auto& [name, c] : cases) {
    const std::string msg = error_of(c.first);
    EXPECT_NE(msg.find(c.second), std::string::npos) << name << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << name;
    EXPECT_EQ(msg.rfind("t.trace: ", 0), 0u) << name << ": " << msg;
  }
  EXPECT_NO_THROW((void)read_all(file));
}

TEST(ReplayTrace, RealGlxgearsCapture) {
  const auto cap = shadecore::test::glxgears_capture();
  if (!cap.ok) GTEST_SKIP() << cap.note;
  Reader r(cap.path);
  EXPECT_EQ(r.version(), 6u);  // apitrace 11.1 (Debian 12)
  EXPECT_NE(r.properties().at("process.name").find("glxgears"), std::string::npos);
  // `timeout` ends glxgears wherever it is, often inside a frame (a glPushMatrix without its glPopMatrix yet):
  // the pairing checks count the frames that ended (up to the last glXSwapBuffers), the rest counts everything.
  std::map<std::string, uint64_t> n, at_swap;
  Call c;
  uint64_t calls = 0, last = 0;
  bool numbered = true;
  while (r.next(c)) {
    if (!c.incomplete) numbered = numbered && c.no == calls;  // single thread: leave order = call order
    ++n[c.name()];
    if (c.name() == "glXSwapBuffers") at_swap = n;
    last = c.no;
    ++calls;
    if (c.name() == "glLightfv") {
      EXPECT_EQ(c.arg(0).s, "GL_LIGHT0");
      EXPECT_EQ(c.arg(1).s, "GL_POSITION");
      ASSERT_EQ(c.arg(2).items.size(), 4u);
      EXPECT_EQ(c.arg(2).items[2].number(), 10.0);  // glxgears: {5, 5, 10, 0}
    }
  }
  EXPECT_TRUE(numbered);
  EXPECT_EQ(last + 1, calls);
  EXPECT_EQ(n["glNewList"], 3u);  // the three gears
  EXPECT_EQ(n["glLightfv"], 1u);
  EXPECT_EQ(n["glFrustum"], 1u);
  EXPECT_GT(n["glXSwapBuffers"], 20u);
  EXPECT_GT(at_swap["glBegin"], 0u);
  EXPECT_EQ(at_swap["glBegin"], at_swap["glEnd"]);
  EXPECT_GT(at_swap["glPushMatrix"], 0u);
  EXPECT_EQ(at_swap["glPushMatrix"], at_swap["glPopMatrix"]);
}

}  // namespace
