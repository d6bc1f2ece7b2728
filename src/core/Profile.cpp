#include "core/Profile.hpp"

#include <sys/resource.h>

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

double peak_rss_mib() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux: kilobytes
}

}  // namespace gf::prof
