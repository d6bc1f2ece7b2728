#pragma once
// The rules of a restart (`granflow run --restart DIR`): what it may change, and how the case it
// is given is compared with the one its checkpoint was written with.
#include <string>
#include <vector>

namespace gf {

// Restarts (`granflow run --restart DIR`). The keys a restart may change, by --set or by
// editing DIR/case.toml: the end time and the time-step controls (extend a run, retry a
// blown-up run with a smaller step), the checkpoint and progress schedule, the warning
// thresholds and the PETSc options. Every other key changes the physics, the grid or the
// output schedule that the files already written follow: a restart refuses it.
const std::vector<std::string>& restart_changeable_keys();
// The differences between two resolved cases (CaseConfig::resolved_toml), one line each
// ("grid.n: 16 at the checkpoint, 24 now"), skipping the keys in `ignore`. Empty: same case.
std::vector<std::string> case_differences(const std::string& checkpoint_toml,
                                          const std::string& now_toml,
                                          const std::vector<std::string>& ignore);

// InputError unless every --set of a restart of `dir` is a restart_changeable_keys() key and
// `dir` is an output folder (it has a case.toml).
void check_restart_request(const std::string& dir, const std::vector<std::string>& sets);
// InputError listing the differences unless the resolved case now is the checkpoint's but for
// the restart_changeable_keys().
void check_restart_case(const std::string& dir, const std::string& ckpt_dir,
                        const std::string& checkpoint_toml, const std::string& now_toml);

}  // namespace gf
