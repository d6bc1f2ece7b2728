#pragma once
// Internal to setup/: the cross-key checks of a case (Checks.cpp), run by load_case after the
// registry has checked each key alone.
#include "core/Params.hpp"
#include "setup/Case.hpp"

namespace gf {

// Adds every problem to `errors` and the legal but probably unintended settings to c.warnings.
void check_case(const Params& p, CaseConfig& c, InputErrors& errors);

}  // namespace gf
