#include "output.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must be defined by the build"
#endif
#ifndef SHADECORE_PYTHON
#define SHADECORE_PYTHON "/usr/bin/python3"
#endif

namespace fs = std::filesystem;

namespace shadecore::cli {

void check_writable_file(const std::string& path) {
  if (path.empty()) throw std::runtime_error("empty output path");
  const fs::path p(path);
  if (fs::is_directory(p)) throw std::runtime_error("cannot write " + path + ": is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) throw std::runtime_error("cannot write " + path + ": no directory " + dir.string());
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

void write_file_atomic(const std::string& path, const std::string& content) {
  check_writable_file(path);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write " + path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path + ": " + ec.message());
  }
}

void ensure_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error("cannot create directory " + dir + (ec ? ": " + ec.message() : ""));
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("cannot write to directory " + dir + ": " + std::strerror(errno));
}

std::pair<int, int> parse_range(const std::string& text) {
  static const std::regex re(R"(^\s*(-?\d{1,9})\s*(?:\.\.\s*(-?\d{1,9})\s*)?$)");
  std::smatch m;
  if (!std::regex_match(text, m, re))
    throw std::invalid_argument("malformed range '" + text + "' (expected N or LO..HI, e.g. 16..1024)");
  const int lo = std::stoi(m[1].str());
  const int hi = m[2].matched ? std::stoi(m[2].str()) : lo;
  if (lo > hi) throw std::invalid_argument("malformed range '" + text + "': LO > HI");
  return {lo, hi};
}

namespace {
std::string g_command_line = "shadecore";
}

void set_command_line(int argc, char** argv) {
  std::string s = "shadecore";
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    for (char& c : a)
      if (c == '\'' || c == '"') c = '_';  // the line is passed to a shell in single quotes
    s += " " + a;
  }
  g_command_line = s;
}

const std::string& command_line() { return g_command_line; }

void run_python_script(const std::string& script, const std::string& args) {
  const char* env_dir = std::getenv("SHADECORE_SCRIPTS");
  const std::string dir = env_dir ? env_dir : std::string(SHADECORE_SOURCE_DIR) + "/scripts";
  const std::string path = dir + "/" + script;
  if (!fs::exists(path)) throw std::runtime_error("plot script not found: " + path);
  const std::string cmd = std::string(SHADECORE_PYTHON) + " '" + path + "' " + args;
  const int rc = std::system(cmd.c_str());
  if (rc != 0) throw std::runtime_error("plotting failed (" + cmd + ")");
}

}  // namespace shadecore::cli
