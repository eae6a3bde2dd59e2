// SPDX-License-Identifier: Apache-2.0
// shadecore — the apitrace capture reader (see shadecore/glfront/trace.hpp; the format: apitrace's
// docs/FORMAT.markdown).
#include "shadecore/glfront/trace.hpp"

#include <snappy.h>
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <sstream>

namespace shadecore::trace {

namespace {

std::string hex(unsigned v) {
  static const char* d = "0123456789abcdef";
  std::string s = "0x";
  s += d[(v >> 4) & 15];
  s += d[v & 15];
  return s;
}

void append_utf8(std::string& out, uint64_t cp) {
  if (cp > 0x10FFFF) cp = 0xFFFD;
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// Names from the capture in messages: printable ASCII only, at most 60 characters.
std::string printable(std::string_view s) {
  std::string out;
  for (unsigned char c : s) {
    if (out.size() >= 60) {
      out += "...";
      break;
    }
    if (c >= 0x20 && c < 0x7F) out += static_cast<char>(c);
    else out += "\\x" + hex(c).substr(2);
  }
  return out;
}

enum : uint8_t { kEnter = 0, kLeave = 1 };
enum : uint8_t { kEnd = 0, kArg = 1, kRet = 2, kThread = 3, kBacktrace = 4, kFlags = 5 };
enum : uint8_t { kFakeFlag = 1 };

}  // namespace

// ---- values ------------------------------------------------------------------------------------------

bool Value::is_number() const {
  switch (kind) {
    case Kind::Bool: case Kind::SInt: case Kind::UInt: case Kind::Float: case Kind::Double: case Kind::Enum:
    case Kind::Bitmask:
      return true;
    case Kind::Repr:
      return items.size() == 2 && items[1].is_number();
    default:
      return false;
  }
}

double Value::number() const {
  switch (kind) {
    case Kind::Bool: case Kind::SInt: case Kind::Enum:
      return static_cast<double>(i);
    case Kind::UInt: case Kind::Bitmask:
      return static_cast<double>(static_cast<uint64_t>(i));
    case Kind::Float: case Kind::Double:
      return d;
    case Kind::Repr:
      if (items.size() == 2) return items[1].number();
      break;
    default:
      break;
  }
  throw TraceError("a value that is not a number where one is expected");
}

int64_t Value::integer() const {
  if (kind == Kind::Float || kind == Kind::Double) {
    if (!std::isfinite(d) || std::fabs(d) > 9.2e18) throw TraceError("a floating-point value out of integer range");
    return static_cast<int64_t>(d);
  }
  if (kind == Kind::Repr && items.size() == 2) return items[1].integer();
  if (kind == Kind::Null || kind == Kind::Opaque) return i;  // NULL pointer = 0, an offset into a buffer object
  (void)number();  // throws for non-numbers
  return i;
}

const Value& Value::machine() const { return kind == Kind::Repr && items.size() == 2 ? items[1] : *this; }

const Value& Call::arg(size_t k) const {
  if (k >= args.size())
    throw TraceError("call " + std::to_string(no) + " " + printable(name()) + ": argument " + std::to_string(k) +
                     " is missing from the capture");
  return args[k];
}

// ---- the container -------------------------------------------------------------------------------------

std::string decompress(std::string_view f, const std::string& name, uint64_t* chunks) {
  if (f.size() >= 2 && static_cast<unsigned char>(f[0]) == 0x1f && static_cast<unsigned char>(f[1]) == 0x8b)
    throw TraceError(name + ": a gzip-compressed capture (apitrace before 3.0); `apitrace repack` rewrites it with Snappy");
  if (f.size() < 2 || f[0] != 'a' || f[1] != 't')
    throw TraceError(name + ": not an apitrace capture (no Snappy 'at' header)");
  std::string out;
  size_t pos = 2;
  uint64_t n = 0;
  while (pos < f.size()) {
    if (f.size() - pos < 4)
      throw TraceError(name + ": truncated: chunk " + std::to_string(n) + " at byte " + std::to_string(pos) +
                       " has " + std::to_string(f.size() - pos) + " of its 4 length bytes");
    const auto* b = reinterpret_cast<const unsigned char*>(f.data() + pos);
    const uint64_t len = uint64_t{b[0]} | uint64_t{b[1]} << 8 | uint64_t{b[2]} << 16 | uint64_t{b[3]} << 24;
    pos += 4;
    if (len == 0) throw TraceError(name + ": corrupt: chunk " + std::to_string(n) + " at byte " + std::to_string(pos - 4) + " is empty");
    if (len > f.size() - pos)
      throw TraceError(name + ": truncated: chunk " + std::to_string(n) + " at byte " + std::to_string(pos - 4) +
                       " declares " + std::to_string(len) + " compressed bytes, " + std::to_string(f.size() - pos) +
                       " remain");
    size_t ulen = 0;
    const char* src = f.data() + pos;
    if (!snappy::GetUncompressedLength(src, len, &ulen) || ulen > kMaxChunkBytes ||
        !snappy::IsValidCompressedBuffer(src, len))
      throw TraceError(name + ": corrupt: chunk " + std::to_string(n) + " at byte " + std::to_string(pos - 4) +
                       " is not valid Snappy data");
    const size_t at = out.size();
    out.resize(at + ulen);
    if (!snappy::RawUncompress(src, len, out.data() + at))
      throw TraceError(name + ": corrupt: chunk " + std::to_string(n) + " at byte " + std::to_string(pos - 4) +
                       " does not decompress");
    pos += len;
    ++n;
  }
  if (n == 0) throw TraceError(name + ": truncated: the capture has no data after its header");
  if (chunks) *chunks = n;
  return out;
}

// ---- the stream ----------------------------------------------------------------------------------------

struct EnumSig {
  std::vector<std::pair<std::string, int64_t>> values;
};
struct StructSig {
  std::string name;
  size_t members = 0;
};

struct Reader::Impl {
  const std::string& name;
  std::string_view s;
  size_t pos = 0;
  unsigned version = 0;
  uint64_t next_no = 0;
  std::vector<std::shared_ptr<const FunctionSig>> functions;
  std::vector<std::unique_ptr<EnumSig>> enums;
  std::vector<std::unique_ptr<StructSig>> structs;
  std::vector<char> bitmasks, frames;  // defined?
  std::deque<Call> open;               // entered, not yet left
  bool ended = false;
  uint64_t current = ~0ull;            // the call being parsed (messages)

  Impl(const std::string& n, std::string_view stream) : name(n), s(stream) {}

  [[noreturn]] void fail(const std::string& what) const {
    std::string where = "stream byte " + std::to_string(pos);
    if (current != ~0ull) where = "call " + std::to_string(current) + ", " + where;
    throw TraceError(name + ": " + what + " (" + where + ")");
  }
  // Thrown by truncated() while an event is being read; next() turns it into the end of the capture.
  struct EventCut {};
  bool in_event = false;
  Reader::Cut cut;
  [[noreturn]] void truncated() const {
    if (in_event) throw EventCut{};
    fail("truncated: the stream ends inside an event");
  }

  uint8_t byte() {
    if (pos >= s.size()) truncated();
    return static_cast<uint8_t>(s[pos++]);
  }
  uint64_t uint() {
    uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      const uint8_t c = byte();
      if (shift >= 64 || (shift == 63 && (c & 0x7e))) fail("corrupt: a variable-length integer longer than 64 bits");
      v |= static_cast<uint64_t>(c & 0x7f) << shift;
      if (!(c & 0x80)) return v;
    }
  }
  size_t count(size_t min_bytes_each) {
    const uint64_t n = uint();
    if (n > (s.size() - pos) / min_bytes_each) truncated();  // each element takes at least that many bytes
    return static_cast<size_t>(n);
  }
  std::string string() {
    const uint64_t n = uint();
    if (n > s.size() - pos) truncated();
    std::string out(s.substr(pos, static_cast<size_t>(n)));
    pos += static_cast<size_t>(n);
    return out;
  }
  int64_t sint_value() {  // a signed number written as a tagged value (enum signatures and values)
    const uint8_t t = byte();
    if (t == 3) return -static_cast<int64_t>(uint());
    if (t == 4) return static_cast<int64_t>(uint());
    pos -= 1;
    fail("corrupt: an enum value tagged " + hex(t) + ", not a signed or unsigned integer");
  }
  template <typename T>
  T raw() {
    if (s.size() - pos < sizeof(T)) truncated();
    T v;
    std::memcpy(&v, s.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  uint64_t sig_id(size_t table_size, const char* what) {
    const uint64_t id = uint();
    if (id > table_size + (uint64_t{1} << 20)) fail(std::string("corrupt: ") + what + " signature id " + std::to_string(id) + " out of range");
    return id;
  }

  std::shared_ptr<const FunctionSig> function_sig() {
    const uint64_t id = sig_id(functions.size(), "function");
    if (id < functions.size() && functions[id]) return functions[id];
    auto sig = std::make_shared<FunctionSig>();
    sig->id = id;
    sig->name = string();
    const size_t n = count(1);
    for (size_t k = 0; k < n; ++k) sig->arg_names.push_back(string());
    if (id >= functions.size()) functions.resize(id + 1);
    functions[id] = sig;
    return sig;
  }

  Value value(int depth) {
    if (depth > kMaxNesting) fail("corrupt: values nested more than " + std::to_string(kMaxNesting) + " deep");
    Value v;
    const uint8_t t = byte();
    switch (t) {
      case 0x00: v.kind = Value::Kind::Null; break;
      case 0x01: v.kind = Value::Kind::Bool; v.i = 0; break;
      case 0x02: v.kind = Value::Kind::Bool; v.i = 1; break;
      case 0x03: v.kind = Value::Kind::SInt; v.i = -static_cast<int64_t>(uint()); break;
      case 0x04: v.kind = Value::Kind::UInt; v.i = static_cast<int64_t>(uint()); break;
      case 0x05: v.kind = Value::Kind::Float; v.d = raw<float>(); break;
      case 0x06: v.kind = Value::Kind::Double; v.d = raw<double>(); break;
      case 0x07: v.kind = Value::Kind::String; v.s = string(); break;
      case 0x08: v.kind = Value::Kind::Blob; v.s = string(); break;
      case 0x09: {
        v.kind = Value::Kind::Enum;
        const uint64_t id = sig_id(enums.size(), "enum");
        const bool known = id < enums.size() && enums[id];
        if (!known) {
          auto e = std::make_unique<EnumSig>();
          if (version >= 3) {
            const size_t n = count(2);
            for (size_t k = 0; k < n; ++k) {
              std::string nm = string();
              e->values.emplace_back(std::move(nm), sint_value());
            }
          } else {
            std::string nm = string();
            e->values.emplace_back(std::move(nm), sint_value());
          }
          if (id >= enums.size()) enums.resize(id + 1);
          enums[id] = std::move(e);
        }
        const EnumSig& e = *enums[id];
        if (version >= 3) {
          v.i = sint_value();
        } else {
          v.i = e.values.front().second;
        }
        for (const auto& [nm, val] : e.values)
          if (val == v.i) {
            v.s = nm;
            break;
          }
        break;
      }
      case 0x0a: {
        v.kind = Value::Kind::Bitmask;
        const uint64_t id = sig_id(bitmasks.size(), "bitmask");
        if (!(id < bitmasks.size() && bitmasks[id])) {
          const size_t n = count(2);
          for (size_t k = 0; k < n; ++k) {
            (void)string();
            (void)uint();
          }
          if (id >= bitmasks.size()) bitmasks.resize(id + 1, 0);
          bitmasks[id] = 1;
        }
        v.i = static_cast<int64_t>(uint());
        break;
      }
      case 0x0b: {
        v.kind = Value::Kind::Array;
        const size_t n = count(1);
        v.items.reserve(n);
        for (size_t k = 0; k < n; ++k) v.items.push_back(value(depth + 1));
        break;
      }
      case 0x0c: {
        v.kind = Value::Kind::Struct;
        const uint64_t id = sig_id(structs.size(), "struct");
        if (!(id < structs.size() && structs[id])) {
          auto st = std::make_unique<StructSig>();
          st->name = string();
          const size_t n = count(1);
          for (size_t k = 0; k < n; ++k) (void)string();
          st->members = n;
          if (id >= structs.size()) structs.resize(id + 1);
          structs[id] = std::move(st);
        }
        v.s = structs[id]->name;
        for (size_t k = 0; k < structs[id]->members; ++k) v.items.push_back(value(depth + 1));
        break;
      }
      case 0x0d: v.kind = Value::Kind::Opaque; v.i = static_cast<int64_t>(uint()); break;
      case 0x0e:
        v.kind = Value::Kind::Repr;
        v.items.push_back(value(depth + 1));
        v.items.push_back(value(depth + 1));
        break;
      case 0x0f: {
        v.kind = Value::Kind::WString;
        const size_t n = count(1);
        for (size_t k = 0; k < n; ++k) append_utf8(v.s, uint());
        break;
      }
      default:
        pos -= 1;
        fail("corrupt: unknown value tag " + hex(t));
    }
    return v;
  }

  void backtrace() {
    const size_t n = count(1);
    for (size_t k = 0; k < n; ++k) {
      const uint64_t id = sig_id(frames.size(), "backtrace frame");
      if (id < frames.size() && frames[id]) continue;
      for (;;) {
        const uint8_t d = byte();
        if (d == 0) break;
        if (d >= 1 && d <= 3) (void)string();
        else if (d == 4 || d == 5) (void)uint();
        else {
          pos -= 1;
          fail("corrupt: unknown backtrace detail " + hex(d));
        }
      }
      if (id >= frames.size()) frames.resize(id + 1, 0);
      frames[id] = 1;
    }
  }

  void details(Call& c) {
    for (;;) {
      const uint8_t d = byte();
      switch (d) {
        case kEnd:
          return;
        case kArg: {
          const uint64_t k = uint();
          if (k > 4096) fail("corrupt: argument index " + std::to_string(k));
          Value v = value(0);
          if (k >= c.args.size()) c.args.resize(k + 1);
          c.args[k] = std::move(v);
          break;
        }
        case kRet:
          c.ret = value(0);
          c.has_ret = true;
          break;
        case kThread:
          c.thread = uint();
          break;
        case kBacktrace:
          backtrace();
          break;
        case kFlags:
          if (uint() & kFakeFlag) c.fake = true;
          break;
        default:
          pos -= 1;
          fail("corrupt: unknown call detail " + hex(d));
      }
    }
  }

  bool next(Call& out) {
    while (!ended) {
      if (pos == s.size()) {
        ended = true;
        break;
      }
      const size_t event_at = pos;
      const uint64_t next_before = next_no;
      in_event = true;
      try {
        if (event(out)) {
          in_event = false;
          return true;
        }
      } catch (const EventCut&) {
        // the last event is cut: drop it (an enter's call number is not used), end the capture there
        cut = {true, current, event_at};
        next_no = next_before;
        ended = true;
      }
      in_event = false;
      current = ~0ull;
    }
    if (open.empty()) return false;
    out = std::move(open.front());
    open.pop_front();
    out.incomplete = true;
    return true;
  }

  // One event: true with `out` set for a leave, false for an enter (the call stays open).
  bool event(Call& out) {
    const uint8_t e = byte();
    if (e == kEnter) {
      Call c;
      c.no = next_no++;
      current = c.no;
      if (version >= 4) c.thread = uint();
      c.sig = function_sig();
      details(c);
      open.push_back(std::move(c));
      return false;
    }
    if (e == kLeave) {
      const uint64_t no = uint();
      current = no;
      auto it = open.begin();
      while (it != open.end() && it->no != no) ++it;
      if (it == open.end()) fail("corrupt: leave of call " + std::to_string(no) + ", which is not open");
      details(*it);  // a cut here leaves the call open: it is returned incomplete
      out = std::move(*it);
      open.erase(it);
      return true;
    }
    pos -= 1;
    fail("corrupt: unknown event " + hex(e));
  }
};

Reader::Reader(const std::string& path) : name_(path) {
  struct stat st{};
  if (::stat(path.c_str(), &st) != 0) throw TraceError(path + ": cannot read the capture (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode)) throw TraceError(path + ": not a regular file");
  if (static_cast<uint64_t>(st.st_size) > kMaxFileBytes)
    throw TraceError(path + ": " + std::to_string(st.st_size) + " bytes, more than the limit of 4 GiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TraceError(path + ": cannot open the capture");
  std::string bytes(static_cast<size_t>(st.st_size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (static_cast<size_t>(in.gcount()) != bytes.size()) throw TraceError(path + ": read error");
  open(bytes);
}

Reader::Reader(std::string_view file_bytes, std::string name) : name_(std::move(name)) { open(file_bytes); }

Reader::~Reader() = default;

void Reader::open(std::string_view file_bytes) {
  stream_ = decompress(file_bytes, name_, &chunks_);
  impl_ = std::make_unique<Impl>(name_, stream_);
  Impl& p = *impl_;
  const uint64_t v = p.uint();
  if (v > kMaxVersion)
    throw TraceError(name_ + ": trace version " + std::to_string(v) + " is not read (versions " +
                     std::to_string(kMinVersion) + " to " + std::to_string(kMaxVersion) + " are)");
  version_ = semantic_version_ = static_cast<unsigned>(v);
  p.version = version_;
  if (version_ >= 6) {
    const uint64_t sv = p.uint();
    if (sv > version_) p.fail("corrupt: semantic version " + std::to_string(sv) + " above the version " + std::to_string(version_));
    semantic_version_ = static_cast<unsigned>(sv);
    for (;;) {
      std::string k = p.string();
      if (k.empty()) break;
      properties_[k] = p.string();
    }
  }
}

bool Reader::next(Call& call) { return impl_->next(call); }

Reader::Cut Reader::cut() const { return impl_->cut; }

}  // namespace shadecore::trace
