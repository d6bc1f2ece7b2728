#pragma once
// The run log: every progress line and message that granflow prints on stderr also goes to
// OUT/granflow.log, so that a run on a cluster (stderr lost or split by the batch system)
// still leaves its story in its output folder.
//
// One log per process, opened by apps/ once the output folder exists (not before: a case
// with errors must leave no output behind). Only the caller decides which rank prints; by
// convention rank 0 (the time loop and apps/ call message() on rank 0 only). Each line is
// flushed at once, so a killed run keeps its log up to the kill.
#include <string>

namespace gf::log {

// Opens (append = true: appends, as on a restart; false: truncates) `path`. Returns an error
// message, empty on success; without a file, message() still prints to stderr.
[[nodiscard]] std::string open(const std::string& path, bool append);
void close();
// Prints `line` (a newline is added) to stderr and, if open, to the log file.
void message(const std::string& line);
// Only to the log file (e.g. the full command line, already known to the user).
void to_file(const std::string& line);
// `text` with every control character but the line feed and the tab shown as \xHH (ESC, CR,
// BEL...): what granflow prints never reaches a terminal raw, whatever a case file or a
// command line held. message() and to_file() apply it.
std::string printable(const std::string& text);

}  // namespace gf::log
