#include "physics_node/io/non_finite_guard.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "common/json_file.hpp"

namespace vcockpit::physics_io {
namespace {

uint64_t fnv1a(uint64_t h, std::string_view text) {
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

uint64_t key_of(std::string_view subject, std::string_view field) {
  return fnv1a(fnv1a(fnv1a(14695981039346656037ull, subject), std::string_view("\0", 1)), field);
}

}  // namespace

NonFiniteGuard::NonFiniteGuard(std::string output) : output_(std::move(output)) {
  named_.reserve(kNamed);
}

bool NonFiniteGuard::pass(bool finite, std::string_view subject, std::string_view field,
                          int64_t t_ns) {
  if (finite) return true;
  ++refused_;
  name_once(subject, field, t_ns);
  return false;
}

void NonFiniteGuard::scrub(nlohmann::ordered_json& record, std::string_view subject,
                           int64_t t_ns) {
  for (const std::string& where : remove_non_finite(record)) pass(false, subject, where, t_ns);
}

void NonFiniteGuard::name_once(std::string_view subject, std::string_view field, int64_t t_ns) {
  const uint64_t key = key_of(subject, field);
  if (std::find(named_.begin(), named_.end(), key) != named_.end()) return;
  if (named_.size() == kNamed) return;  // counted only: the log has named plenty already
  named_.push_back(key);
  spdlog::warn("{}: refused a non-finite {} of {} at {:.3f} s (left out; further refusals of it "
               "are counted, not logged)",
               output_, field, subject, static_cast<double>(t_ns) * 1e-9);
}

}  // namespace vcockpit::physics_io
