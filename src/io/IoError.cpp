#include "io/IoError.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace gf::io {

void raise_on_all_ranks(MPI_Comm comm, const std::string& error_on_root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string msg = rank == 0 ? error_on_root : std::string();
  int len = static_cast<int>(msg.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  if (len == 0) return;
  msg.resize(len);
  MPI_Bcast(msg.data(), len, MPI_CHAR, 0, comm);
  throw IoError(msg);
}

std::string write_file_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f)
    return "cannot open '" + tmp + "' for writing: " + std::strerror(errno) +
           " (check that the output folder exists and is writable)";
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  int err = ok ? 0 : errno;
  // fclose flushes: its failure (e.g. disk full) is a write failure too.
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    return "cannot write '" + tmp + "': " + std::strerror(err) + " (disk full?)";
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    return "cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno);
  return {};
}

std::string make_directories(const std::string& dir) {
  if (dir.empty()) return {};  // the current folder
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create output folder '" + dir + "': " + ec.message();
  return {};
}

}  // namespace gf::io
