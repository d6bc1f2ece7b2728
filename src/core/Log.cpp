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

void message(const std::string& line) {
  std::fprintf(stderr, "%s\n", line.c_str());
  to_file(line);
}

void to_file(const std::string& line) {
  if (!g_file) return;
  std::fprintf(g_file, "%s\n", line.c_str());
  std::fflush(g_file);
}

}  // namespace gf::log
