#pragma once
// No NaN or infinity reaches an output file or a topic. The body check (physics/body_check.hpp)
// already puts a broken body back before anything reads it, so this is the last line: a writer
// asks the guard before it writes a value, and a value that is not finite is refused (the row or
// sample left out, or the field left out of a JSON record), counted, and named in the log (warn)
// the first time for each subject and field: "<output>: refused a non-finite <field> of
// <subject> at <t> s".
//
// Remembering what was named takes no allocation for the first kNamed subject-field pairs;
// after that refusals are still counted but no longer named.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vcockpit::physics_io {

class NonFiniteGuard {
 public:
  static constexpr std::size_t kNamed = 64;

  // `output`: what is written, for the log ("trajectories.csv", "cockpit/object_state").
  explicit NonFiniteGuard(std::string output);

  // Returns `finite`. When false: one refusal counted, and named if this subject's field is new.
  bool pass(bool finite, std::string_view subject, std::string_view field, int64_t t_ns);

  // Leaves out of a JSON record whatever holds a non-finite number (remove_non_finite in
  // common/json_file.hpp), each a refusal of `subject`'s field at that place.
  void scrub(nlohmann::ordered_json& record, std::string_view subject, int64_t t_ns);

  uint64_t refused() const { return refused_; }

 private:
  void name_once(std::string_view subject, std::string_view field, int64_t t_ns);

  std::string output_;
  uint64_t refused_ = 0;
  std::vector<uint64_t> named_;  // FNV-1a of subject and field, for those already named
};

}  // namespace vcockpit::physics_io
