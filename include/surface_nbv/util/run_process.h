// Runs a program and waits for it (posix_spawn, no shell): argv[0] is the
// program's path. `quiet` sends its stdout and stderr to /dev/null. Returns
// its exit status, or -1 when it could not start or did not exit normally.
#pragma once

#include <string>
#include <vector>

namespace surface_nbv {

int runProcess(std::vector<std::string> argv, bool quiet);

}  // namespace surface_nbv
