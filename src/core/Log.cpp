#include "core/Log.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace gf::log {

namespace {
// The process's log file. A global on purpose: the log is a property of the process (like
// stderr, which it mirrors), and threading a handle through every layer that may report a
// message would only add parameters.
std::FILE* g_file = nullptr;
}  // namespace

std::string open(const std::string& path, bool append) {
  close();
  g_file = std::fopen(path.c_str(), append ? "a" : "w");
  if (!g_file) return "cannot open the log '" + path + "': " + std::strerror(errno);
  return {};
}

void close() {
  if (g_file) std::fclose(g_file);
  g_file = nullptr;
}

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const unsigned char c : text) {
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", static_cast<unsigned>(c));
      out += b;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

void message(const std::string& line) {
  std::fprintf(stderr, "%s\n", printable(line).c_str());
  to_file(line);
}

void to_file(const std::string& line) {
  if (!g_file) return;
  std::fprintf(g_file, "%s\n", printable(line).c_str());
  std::fflush(g_file);
}

}  // namespace gf::log
