// Status: the error tier for user input and failed solves (DESIGN.md, "Errors").
//
// Library code that can fail on bad input returns a Status; Status::Ok() means
// success, otherwise message() is a single line naming the file, line or field
// and what was expected ("walk.bvh:12: expected OFFSET, got 'OFSET'"). Programmer
// errors are CHECKed instead. No exceptions cross the library boundary.
#ifndef MOCAPSOLVE_KINEMATICS_STATUS_H_
#define MOCAPSOLVE_KINEMATICS_STATUS_H_

#include <string>
#include <utility>

namespace mocapsolve {

class [[nodiscard]] Status {
 public:
  static Status Ok() { return Status(); }
  static Status Error(std::string message) { return Status(std::move(message)); }

  bool ok() const { return !failed_; }
  const std::string& message() const { return message_; }

 private:
  Status() = default;
  explicit Status(std::string message) : failed_(true), message_(std::move(message)) {}

  bool failed_ = false;
  std::string message_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_STATUS_H_
