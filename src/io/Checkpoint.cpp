#include "io/Checkpoint.hpp"

#include <fcntl.h>
#include <petscviewer.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/IoError.hpp"

namespace gf::io {

namespace fs = std::filesystem;

namespace {

// Version 2 headers end with their own checksum; version 1 (older granflow) had none and is
// still read.
constexpr const char* kMagic = "granflow-checkpoint 2";
constexpr const char* kMagicV1 = "granflow-checkpoint 1";
constexpr const char* kHeaderSum = "header.fnv1a64";
constexpr const char* kState = "state.bin";
constexpr const char* kHeader = "header.txt";

bool valid_key(const std::string& k) {
  if (k.empty()) return false;
  for (const char c : k)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '#') return false;
  return true;
}

// FNV-1a, 64 bit, over a whole file; false if it cannot be read.
bool fnv1a64(const std::string& path, std::uint64_t& hash, std::uint64_t& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  hash = 0xcbf29ce484222325ULL;
  bytes = 0;
  std::vector<unsigned char> buf(1 << 16);
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
    for (std::size_t k = 0; k < n; ++k) {
      hash ^= buf[k];
      hash *= 0x100000001b3ULL;
    }
    bytes += n;
  }
  const bool ok = !std::ferror(f);
  std::fclose(f);
  return ok;
}

std::uint64_t fnv1a64_text(const std::string& text) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::string hex64(std::uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%016" PRIx64, v);
  return b;
}

// fsync a file or a folder: the data (or the rename) reaches the disk before the next step.
std::string sync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return "cannot open '" + path + "' to sync it: " + std::strerror(errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) return "cannot sync '" + path + "' to disk: " + std::strerror(err);
  return {};
}

std::string write_text(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return "cannot open '" + path + "' for writing: " + std::strerror(errno);
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  int err = errno;
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (!ok) return "cannot write '" + path + "': " + std::strerror(err) + " (disk full?)";
  return sync_path(path);
}

// PETSc calls whose failure is a property of the file (not a bug): PETSc's error handler is
// silenced (no stack trace for a user's bad file), and the failure reduced over the ranks so
// that all throw together.
class QuietPetsc {
 public:
  QuietPetsc() { PetscPushErrorHandler(PetscReturnErrorHandler, nullptr); }
  ~QuietPetsc() { PetscPopErrorHandler(); }
  QuietPetsc(const QuietPetsc&) = delete;
  QuietPetsc& operator=(const QuietPetsc&) = delete;
};

void agree(MPI_Comm comm, int local_failed, const std::string& msg) {
  int any = 0;
  MPI_Allreduce(&local_failed, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any) throw IoError(msg);
}

}  // namespace

// ---------------------------------------------------------------------------- header
void CheckpointHeader::set(const std::string& key, double v) {
  char b[80];
  std::snprintf(b, sizeof b, "%a # %.17g", v, v);
  set_text(key, b);
}

void CheckpointHeader::set(const std::string& key, long long v) { set_text(key, std::to_string(v)); }

void CheckpointHeader::set_text(const std::string& key, const std::string& v) {
  if (!valid_key(key)) throw std::invalid_argument("checkpoint header: bad key '" + key + "'");
  if (v.find_first_of("\r\n") != std::string::npos)
    throw std::invalid_argument("checkpoint header: value of '" + key + "' has a line break");
  for (auto& [k, val] : entries_)
    if (k == key) {
      val = v;
      return;
    }
  entries_.emplace_back(key, v);
}

const std::string* CheckpointHeader::find(const std::string& key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

bool CheckpointHeader::has(const std::string& key) const { return find(key) != nullptr; }

std::vector<std::string> CheckpointHeader::file_names() const {
  std::vector<std::string> names;
  const std::string pre = "file.", suf = ".fnv1a64";
  for (const auto& [k, v] : entries_)
    if (k.size() > pre.size() + suf.size() && k.compare(0, pre.size(), pre) == 0 &&
        k.compare(k.size() - suf.size(), suf.size(), suf) == 0)
      names.push_back(k.substr(pre.size(), k.size() - pre.size() - suf.size()));
  return names;
}

std::string CheckpointHeader::get_text(const std::string& key) const {
  const std::string* v = find(key);
  if (!v) throw IoError(source_ + ": the checkpoint header has no '" + key + "' (corrupt, or written by another granflow version)");
  return *v;
}

double CheckpointHeader::get_double(const std::string& key) const {
  const std::string v = get_text(key);
  const char* s = v.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(s, &end);
  while (end && *end == ' ') ++end;
  if (end == s || errno == ERANGE || (end && *end && *end != '#'))
    throw IoError(source_ + ": '" + key + "' is not a number: '" + v + "' (corrupt checkpoint)");
  return x;
}

long long CheckpointHeader::get_int(const std::string& key) const {
  const std::string v = get_text(key);
  char* end = nullptr;
  errno = 0;
  const long long x = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || errno == ERANGE || *end)
    throw IoError(source_ + ": '" + key + "' is not an integer: '" + v + "' (corrupt checkpoint)");
  return x;
}

std::string CheckpointHeader::str() const {
  std::string s = std::string(kMagic) + "\n";
  for (const auto& [k, v] : entries_) s += k + " " + v + "\n";
  // The checksum of every line above: an edit of the step, the time or dt (t nan) is caught.
  s += std::string(kHeaderSum) + " " + hex64(fnv1a64_text(s)) + "\n";
  s += "end\n";  // a header cut short is recognised as such
  return s;
}

CheckpointHeader CheckpointHeader::parse(const std::string& text, const std::string& source) {
  CheckpointHeader h;
  h.source_ = source;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || (line != kMagic && line != kMagicV1))
    throw IoError(source + ": not a granflow checkpoint header (first line '" + line +
                  "', expected '" + kMagic + "')");
  const bool summed = line == kMagic;
  std::string before = line + "\n";  // the text the header checksum covers
  bool ended = false, checked = false;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line == "end") {
      ended = true;
      break;
    }
    const auto sp = line.find(' ');
    const std::string key = line.substr(0, sp);
    if (sp == std::string::npos || !valid_key(key))
      throw IoError(source + ": line " + std::to_string(n) + " is malformed: '" + line +
                    "' (corrupt checkpoint)");
    if (summed && key == kHeaderSum) {
      const std::string want = line.substr(sp + 1), got = hex64(fnv1a64_text(before));
      if (got != want)
        throw IoError(source + ": the header fails its checksum (FNV-1a " + got + ", recorded " +
                      want + "): the header was edited or is corrupt");
      checked = true;
      continue;
    }
    if (checked)
      throw IoError(source + ": line " + std::to_string(n) + " follows the header's checksum: '" +
                    line + "' (the header was edited)");
    before += line + "\n";
    h.entries_.emplace_back(key, line.substr(sp + 1));
  }
  if (!ended)
    throw IoError(source + ": the header is incomplete (no 'end' line): the checkpoint is "
                  "truncated or corrupt");
  if (summed && !checked)
    throw IoError(source + ": the header has no checksum line (" + kHeaderSum +
                  "): the header was edited or is corrupt");
  return h;
}

// ---------------------------------------------------------------------------- write
void write_checkpoint(MPI_Comm comm, const std::string& out_dir, CheckpointHeader header,
                      const std::vector<CheckpointField>& fields,
                      const std::vector<std::pair<std::string, std::string>>& files) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string final_dir = out_dir + "/checkpoint", tmp = out_dir + "/checkpoint.tmp",
                    prev = out_dir + "/checkpoint.prev";
  std::string err;
  if (rank == 0) {
    std::error_code ec;
    fs::remove_all(tmp, ec);  // a checkpoint that was being written when a run died
    // Not create_directories: an output folder removed during the run must not be made again
    // (with the checkpoint and summary.json in it, the run would look complete).
    if (!ec) fs::create_directory(tmp, ec);
    if (ec)
      err = "cannot create '" + tmp + "': " + ec.message() +
            (fs::is_directory(out_dir) ? "" : " (the output folder was removed?)");
  }
  raise_on_all_ranks(comm, err);

  // 1. The fields, into one PETSc binary file (rank 0 writes, the others send).
  std::string names;
  for (const auto& f : fields) {
    PetscInt n = 0;
    if (VecGetSize(f.vec, &n)) throw std::runtime_error("checkpoint: VecGetSize failed");
    names += (names.empty() ? "" : " ") + f.name;
    header.set("field." + f.name + ".size", static_cast<long long>(n));
  }
  header.set_text("fields", names);
  {
    const std::string path = tmp + "/" + kState;
    QuietPetsc quiet;
    PetscViewer v = nullptr;
    PetscErrorCode ierr = PetscViewerCreate(comm, &v);
    if (!ierr) ierr = PetscViewerSetType(v, PETSCVIEWERBINARY);
    if (!ierr) ierr = PetscViewerFileSetMode(v, FILE_MODE_WRITE);
    if (!ierr) ierr = PetscViewerBinarySetSkipInfo(v, PETSC_TRUE);
    if (!ierr) ierr = PetscViewerFileSetName(v, path.c_str());
    for (const auto& f : fields)
      if (!ierr) ierr = VecView(f.vec, v);
    if (v) {
      const PetscErrorCode e2 = PetscViewerDestroy(&v);
      if (!ierr) ierr = e2;
    }
    agree(comm, ierr != 0, "cannot write the checkpoint fields to '" + path +
                               "' (PETSc error " + std::to_string(static_cast<int>(ierr)) +
                               "; disk full?); the previous checkpoint is kept");
  }

  // 2. Rank 0: checksum, header, caller's files, fsync; then the two renames.
  if (rank == 0) {
    const std::string state = tmp + "/" + kState;
    std::uint64_t hash = 0, bytes = 0;
    if (!fnv1a64(state, hash, bytes)) err = "cannot read back '" + state + "'";
    if (err.empty()) err = sync_path(state);
    if (err.empty()) {
      header.set("state.bytes", static_cast<long long>(bytes));
      header.set_text("state.fnv1a64", hex64(hash));
      for (const auto& [name, text] : files) {
        header.set_text("file." + name + ".fnv1a64", hex64(fnv1a64_text(text)));
        if (err.empty()) err = write_text(tmp + "/" + name, text);
      }
      // The header last: its presence with an 'end' line marks a complete folder.
      if (err.empty()) err = write_text(tmp + "/" + kHeader, header.str());
      if (err.empty()) err = sync_path(tmp);
    }
    std::error_code ec;
    if (err.empty() && fs::exists(final_dir)) {
      fs::remove_all(prev, ec);
      if (!ec) fs::rename(final_dir, prev, ec);
      if (ec) err = "cannot move the previous checkpoint aside: " + ec.message();
    }
    if (err.empty()) {
      fs::rename(tmp, final_dir, ec);
      if (ec) err = "cannot rename '" + tmp + "' to '" + final_dir + "': " + ec.message();
    }
    if (err.empty()) err = sync_path(out_dir);
    // checkpoint.prev stays: if the new one is damaged later, a restart falls back to it.
    if (!err.empty()) err += " (the previous checkpoint is kept)";
  }
  raise_on_all_ranks(comm, err);
}

// ---------------------------------------------------------------------------- read
std::string find_checkpoint(MPI_Comm comm, const std::string& out_dir) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string found;
  if (rank == 0) {
    for (const char* name : {"/checkpoint", "/checkpoint.prev"})
      if (fs::is_directory(out_dir + name)) {
        found = out_dir + name;
        break;
      }
  }
  int len = static_cast<int>(found.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  found.resize(len);
  MPI_Bcast(found.data(), len, MPI_CHAR, 0, comm);
  return found;
}

std::string read_checkpoint_file(MPI_Comm comm, const std::string& ckpt_dir,
                                 const std::string& name) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string text, err;
  if (rank == 0) {
    const std::string path = ckpt_dir + "/" + name;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      err = "cannot read '" + path + "': " + std::strerror(errno) + " (incomplete checkpoint)";
    } else {
      std::ostringstream os;
      os << in.rdbuf();
      text = os.str();
    }
  }
  raise_on_all_ranks(comm, err);
  long long len = static_cast<long long>(text.size());
  MPI_Bcast(&len, 1, MPI_LONG_LONG, 0, comm);
  text.resize(static_cast<std::size_t>(len));
  MPI_Bcast(text.data(), static_cast<int>(len), MPI_CHAR, 0, comm);
  return text;
}

CheckpointHeader read_checkpoint_header(MPI_Comm comm, const std::string& ckpt_dir) {
  const std::string source = ckpt_dir + "/" + kHeader;
  const CheckpointHeader h =
      CheckpointHeader::parse(read_checkpoint_file(comm, ckpt_dir, kHeader), source);
  // Every rank has the same header: the checks below throw on all ranks together, except the
  // checksum, which rank 0 computes and shares.
  const long long bytes = h.get_int("state.bytes");
  const std::string want = h.get_text("state.fnv1a64");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string err;
  if (rank == 0) {
    const std::string state = ckpt_dir + "/" + kState;
    std::uint64_t hash = 0, got = 0;
    if (!fnv1a64(state, hash, got))
      err = "cannot read '" + state + "': " + std::strerror(errno) + " (incomplete checkpoint)";
    else if (static_cast<long long>(got) != bytes)
      err = "'" + state + "' has " + std::to_string(got) + " bytes, the header says " +
            std::to_string(bytes) + ": the checkpoint is truncated or corrupt";
    else if (hex64(hash) != want)
      err = "'" + state + "' fails its checksum (FNV-1a " + hex64(hash) + ", header " + want +
            "): the checkpoint is corrupt";
  }
  raise_on_all_ranks(comm, err);
  // The caller's files (e.g. the resolved case), where the header records their checksums.
  for (const std::string& name : h.file_names()) {
    const std::string text = read_checkpoint_file(comm, ckpt_dir, name);
    const std::string want_f = h.get_text("file." + name + ".fnv1a64");
    if (hex64(fnv1a64_text(text)) != want_f)
      throw IoError("'" + ckpt_dir + "/" + name + "' fails its checksum (FNV-1a " +
                    hex64(fnv1a64_text(text)) + ", header " + want_f +
                    "): the checkpoint is corrupt or was edited");
  }
  return h;
}

void read_checkpoint_fields(MPI_Comm comm, const std::string& ckpt_dir,
                            const CheckpointHeader& header,
                            const std::vector<CheckpointField>& fields) {
  const std::string src = header.source();
  std::string names;
  for (const auto& f : fields) names += (names.empty() ? "" : " ") + f.name;
  const std::string have = header.get_text("fields");
  if (have != names)
    throw IoError(src + ": the checkpoint holds the fields '" + have + "', this run needs '" +
                  names + "' (written by another granflow version or another kind of case)");
  for (const auto& f : fields) {
    PetscInt n = 0;
    if (VecGetSize(f.vec, &n)) throw std::runtime_error("checkpoint: VecGetSize failed");
    const long long stored = header.get_int("field." + f.name + ".size");
    if (stored != n)
      throw IoError(src + ": field '" + f.name + "' has " + std::to_string(stored) +
                    " values in the checkpoint, " + std::to_string(n) + " in this run's grid");
  }
  const std::string path = ckpt_dir + "/" + kState;
  QuietPetsc quiet;
  PetscViewer v = nullptr;
  PetscErrorCode ierr = PetscViewerCreate(comm, &v);
  if (!ierr) ierr = PetscViewerSetType(v, PETSCVIEWERBINARY);
  if (!ierr) ierr = PetscViewerFileSetMode(v, FILE_MODE_READ);
  if (!ierr) ierr = PetscViewerBinarySetSkipInfo(v, PETSC_TRUE);
  if (!ierr) ierr = PetscViewerFileSetName(v, path.c_str());
  for (const auto& f : fields)
    if (!ierr) ierr = VecLoad(f.vec, v);
  if (v) {
    const PetscErrorCode e2 = PetscViewerDestroy(&v);
    if (!ierr) ierr = e2;
  }
  agree(comm, ierr != 0, "cannot load the fields from '" + path + "' (PETSc error " +
                             std::to_string(static_cast<int>(ierr)) + "): corrupt checkpoint");
}

}  // namespace gf::io
