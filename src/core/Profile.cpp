#include "core/Profile.hpp"

#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace gf::prof {

namespace {
constexpr const char* kNames[kCount] = {"LevelSetAdvect", "Redistance",  "Properties",
                                        "Assemble",       "FixedPoint",  "ViscousSolve",
                                        "Plastic",        "Anderson",    "Pressure",
                                        "Output",         "Checkpoint"};
}

const char* name(Phase p) { return kNames[p]; }

PetscLogEvent event(Phase p) {
  static std::array<PetscLogEvent, kCount> ev = [] {
    std::array<PetscLogEvent, kCount> e{};
    PetscClassId cid;
    PetscClassIdRegister("granflow", &cid);
    for (int k = 0; k < kCount; ++k) PetscLogEventRegister(kNames[k], cid, &e[k]);
    return e;
  }();
  return ev[p];
}

std::array<double, kCount>& seconds() {
  static std::array<double, kCount> s{};
  return s;
}

namespace {
// The first number in `path` (a /sys or /proc file), or -1 (missing, or "max").
double read_number(const char* path, const char* key = nullptr) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (key && line.rfind(key, 0) != 0) continue;
    const char* p = line.c_str() + (key ? std::strlen(key) : 0);
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end != p) return key ? v * 1024 : v;  // /proc/meminfo is in kB
    return -1;
  }
  return -1;
}
}  // namespace

double available_memory_bytes() {
  double avail = read_number("/proc/meminfo", "MemAvailable:");
  // cgroup v2, then v1: the limit less what the group already uses.
  const double lim2 = read_number("/sys/fs/cgroup/memory.max");
  const double use2 = read_number("/sys/fs/cgroup/memory.current");
  if (lim2 > 0 && use2 >= 0 && (avail < 0 || lim2 - use2 < avail)) avail = lim2 - use2;
  const double lim1 = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");
  const double use1 = read_number("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  if (lim1 > 0 && lim1 < 1e18 && use1 >= 0 && (avail < 0 || lim1 - use1 < avail))
    avail = lim1 - use1;
  return avail > 0 ? avail : 0;
}

double peak_rss_mib() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux: kilobytes
}

}  // namespace gf::prof
