// A success flag with a message, returned by every fallible core call instead
// of throwing. The message names what was wrong (a file, a key, a value).
#pragma once

#include <string>
#include <utility>

namespace surface_nbv {

class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status Error(std::string message) { return Status(false, std::move(message)); }

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  Status(bool ok, std::string message) : ok_(ok), message_(std::move(message)) {}
  bool ok_ = true;
  std::string message_;
};

}  // namespace surface_nbv
