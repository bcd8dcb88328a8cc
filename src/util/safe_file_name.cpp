#include "surface_nbv/util/safe_file_name.h"

#include <sys/stat.h>

namespace surface_nbv {

Status resolveFileName(const std::string& directory, const std::string& name, bool must_exist, std::string* path) {
  if (name.empty()) return Status::Error("file name is empty");
  if (name.size() > 128) return Status::Error("file name is longer than 128 bytes");
  if (name == "." || name == ".." || name[0] == '.') return Status::Error("file name '" + name + "' may not start with '.'");
  for (char c : name) {
    if (c == '/' || c == '\\') return Status::Error("file name '" + name + "' is a path: give a plain name");
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return Status::Error("file name has control characters");
  }
  if (directory.empty()) return Status::Error("no file directory is configured");
  const std::string full = directory + "/" + name;
  struct stat st;
  if (lstat(full.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode)) return Status::Error("'" + name + "' is a symbolic link: refused");
    if (!S_ISREG(st.st_mode)) return Status::Error("'" + name + "' exists and is not a regular file");
  } else if (must_exist) {
    return Status::Error("no file '" + name + "' in " + directory);
  }
  // Writers (saveMap, saveMesh) write <name>.tmp first and rename it: a link
  // planted there would be followed.
  if (!must_exist && lstat((full + ".tmp").c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    return Status::Error("the temporary file '" + name + ".tmp' exists and is not a regular file: refused");
  }
  *path = full;
  return Status::Ok();
}

}  // namespace surface_nbv
