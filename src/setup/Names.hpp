#pragma once
// Internal to setup/: the names written in case files for each choice, and the small helpers
// the schema, the case checks and the report share.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/Params.hpp"

namespace gf::setup_detail {

// Names as written in case files, indexed by the enumerators of CaseConfig: the schema's
// choices and the string -> enum conversion both come from these, so they cannot drift.
inline const std::vector<std::string> kDtModes{"adaptive", "fixed"};
inline const std::vector<std::string> kShapes{"none",   "rectangle", "layer",
                                       "circle", "zalesak",   "trapezoid"};
inline const std::vector<std::string> kPrescribed{"none", "rotation", "single_vortex"};
inline const std::vector<std::string> kInitialVelocities{"none", "vortex"};
inline const std::vector<std::string> kInitialStresses{"zero", "equilibrium"};
inline const std::vector<std::string> kInitialPressures{"projection", "hydrostatic"};
inline const std::vector<std::string> kWalls{"free_slip", "no_slip", "navier"};
inline const std::vector<std::string> kProbeFields{"phi", "rho",    "u",      "v",     "speed",
                                            "p",   "eta",    "D_norm", "S_norm", "kappa"};
inline const std::vector<std::string> kSides{"left", "right", "bottom", "top"};
inline const std::vector<std::string> kYields{"none", "bingham", "dp", "hp"};
inline const std::vector<std::string> kPlasticGrids{"cell", "cell_node"};
inline const std::vector<std::string> kPlasticSolvers{"fixed_point", "newton"};
inline const std::vector<std::string> kNewtonPressures{"coupled", "projection"};
inline const std::vector<std::string> kNewtonWallLoads{"iterate", "step_start"};
inline const std::vector<std::string> kYieldSupports{"phase", "mass"};
inline const std::vector<std::string> kRedistanceWalls{"drop", "extrapolate"};
inline const std::vector<std::string> kViscosities{"constant", "mu_i"};
inline const std::vector<std::string> kInterfaceMethods{"level_set", "clsvof"};
inline const std::vector<std::string> kInterfaceNormals{"level_set", "youngs"};

// Counts are stored as int; these bounds keep them (and nx * ny) far from overflow.
inline constexpr double kMaxCellsPerSide = 100000;
// The most steps and outputs a case may ask for to time.t_end (setup/Checks.cpp says why).
inline constexpr double kMaxSteps = 1e9;
inline constexpr double kMaxOutputs = 1e7;
inline constexpr double kMaxVtkOutputs = 1e5;

template <class E>
E enum_of(const std::vector<std::string>& names, const std::string& s) {
  const auto it = std::find(names.begin(), names.end(), s);
  // The registry has already checked s against the same list.
  return static_cast<E>(it == names.end() ? 0 : it - names.begin());
}

inline Range closed(double lo, double hi) {
  Range r = Range::ge(lo);
  r.hi = hi;
  return r;
}

// lo <= x < hi
inline Range closed_open(double lo, double hi) {
  Range r = closed(lo, hi);
  r.hi_open = true;
  return r;
}

// Compact number for reports: 4 significant digits.
inline std::string g4(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace gf::setup_detail
