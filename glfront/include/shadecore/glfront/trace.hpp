// SPDX-License-Identifier: Apache-2.0
// shadecore — a reader of apitrace captures (`apitrace trace`'s .trace files), written from apitrace's
// docs/FORMAT.markdown; host software for `shadecore replay` (docs/replay.md).
//
// The file: the two bytes 'a' 't', then chunks of a little-endian uint32 compressed length and that many bytes of
// raw Snappy data (each chunk decompresses to at most a few MiB; apitrace writes 1 MiB). The decompressed stream:
// version_no (a variable-length uint), for version 6 also semantic_version_no and the properties (name/value
// strings up to an empty name), then events: enter (0x00 [thread_no, version >= 4] call_sig details…) and leave
// (0x01 call_no details…), the details ending in 0x00; arguments and return values are tagged values
// (null, false, true, sint, uint, float, double, string, blob, enum, bitmask, array, struct, opaque pointer, repr,
// wide string) with their signatures given at the first use of an id.
//
// Versions read: 0 to 6 (apitrace 11.1 in Debian 12 writes 6; 0..2 have single-name enum signatures, 0..3 no
// thread number on enter, the thread then a call detail). Anything else is refused: a gzip or other container,
// version 7 and later, an unknown event, detail or value tag, a length past the end of the data, a signature id
// used before it was defined, values nested deeper than kMaxNesting, a chunk that does not decompress or one cut
// short. Each is a TraceError with a one-line message "FILE: what (where)". A stream that ends between events is a
// complete capture; calls entered but not left are returned last with `incomplete` set, as apitrace does. A stream
// whose chunks are all whole but whose last event is cut (the traced program was killed while apitrace had an
// event half written, or before it wrote the chunk the event continues in: `timeout PROGRAM` leaves such files)
// is read up to that event, which is dropped, as glretrace does; cut() then says where. A cut inside the header
// is still an error.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace shadecore::trace {

class TraceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr unsigned kMinVersion = 0, kMaxVersion = 6;  // the trace versions read
inline constexpr int kMaxNesting = 64;                       // arrays / structs / reprs nested at most this deep
inline constexpr std::uint64_t kMaxFileBytes = 4ull << 30;   // a capture file: at most 4 GiB compressed
inline constexpr std::uint64_t kMaxChunkBytes = 64ull << 20; // one chunk: at most 64 MiB decompressed

struct Value {
  enum class Kind : uint8_t { Null, Bool, SInt, UInt, Float, Double, String, Blob, Enum, Bitmask, Array, Struct,
                              Opaque, Repr, WString };
  Kind kind = Kind::Null;
  int64_t i = 0;       // Bool (0/1), SInt, UInt (as the unsigned value's bits), Enum, Bitmask, Opaque (address)
  double d = 0;        // Float, Double
  std::string s;       // String, Blob (the bytes), Enum (its name, "" if the signature has none for the value),
                       // Struct (the structure's name), WString (UTF-32 code points as UTF-8)
  std::vector<Value> items;  // Array elements, Struct members, Repr {human, machine}

  [[nodiscard]] bool is_number() const;     // Bool, SInt, UInt, Float, Double, Enum, Bitmask
  [[nodiscard]] double number() const;      // the number (Repr: its machine value); throws if none
  [[nodiscard]] int64_t integer() const;    // the number as an integer (floats truncated toward zero)
  [[nodiscard]] uint64_t uinteger() const { return static_cast<uint64_t>(integer()); }
  [[nodiscard]] const Value& machine() const;  // Repr: its machine value; else itself
};

struct FunctionSig {
  uint64_t id = 0;
  std::string name;
  std::vector<std::string> arg_names;
};

struct Call {
  uint64_t no = 0;                          // numbered from 0 in enter order (apitrace's call numbers)
  uint64_t thread = 0;
  std::shared_ptr<const FunctionSig> sig;
  std::vector<Value> args;                  // by argument index (Null where the capture gives none)
  bool has_ret = false;
  Value ret;
  bool fake = false;                        // flag FAKE: a call the tracer inserted (e.g. glViewport at MakeCurrent)
  bool incomplete = false;                  // entered but never left (the program stopped inside it)
  [[nodiscard]] const std::string& name() const { return sig->name; }
  [[nodiscard]] const Value& arg(size_t k) const;  // throws TraceError (one line) if the capture lacks it
};

// Reads a capture. Construction reads the header (version, properties); next() then parses one call at a time.
class Reader {
 public:
  explicit Reader(const std::string& path);                           // the file (at most kMaxFileBytes)
  Reader(std::string_view file_bytes, std::string name);              // the file's bytes (tests); `name` in messages
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  [[nodiscard]] unsigned version() const { return version_; }
  [[nodiscard]] unsigned semantic_version() const { return semantic_version_; }
  [[nodiscard]] const std::map<std::string, std::string>& properties() const { return properties_; }
  [[nodiscard]] uint64_t chunks() const { return chunks_; }
  [[nodiscard]] uint64_t stream_bytes() const { return stream_.size(); }
  // After next() returned false: whether the stream ended inside an event (dropped), the call that event belonged
  // to (~0 for a leave cut before its call number) and the stream byte where the event began.
  struct Cut {
    bool cut = false;
    uint64_t call = ~0ull;
    uint64_t event_byte = 0;
  };
  [[nodiscard]] Cut cut() const;

  // The next call left (in leave order; calls still open at the end of the stream follow, incomplete). False at
  // the end. Throws TraceError on anything malformed.
  bool next(Call& call);

 private:
  struct Impl;
  void open(std::string_view file_bytes);
  std::string name_;
  std::string stream_;  // the decompressed stream
  unsigned version_ = 0, semantic_version_ = 0;
  uint64_t chunks_ = 0;
  std::map<std::string, std::string> properties_;
  std::unique_ptr<Impl> impl_;
};

// The raw Snappy container of a capture decompressed (exposed for tests and the fuzzer).
std::string decompress(std::string_view file_bytes, const std::string& name, uint64_t* chunks = nullptr);

}  // namespace shadecore::trace
