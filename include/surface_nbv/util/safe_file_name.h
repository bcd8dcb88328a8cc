// Files that services may write or read live in one configured directory and
// are named by a plain file name, never a path: this resolves a requested
// name to a path inside the directory or says why it is refused.
#pragma once

#include <string>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Refuses empty names, names with '/', '\\', NUL or control characters, "." and
// "..", names starting with '.', and names longer than 128 bytes; with
// `must_exist`, a missing file; without it (a file to write), a <name>.tmp
// that exists and is not a regular file (the writers write it first and
// rename it); always, an existing symlink. On success
// *path = directory + "/" + name.
Status resolveFileName(const std::string& directory, const std::string& name, bool must_exist, std::string* path);

}  // namespace surface_nbv
