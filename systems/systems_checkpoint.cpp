#include "systems/systems_checkpoint.hpp"

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/atomic_file.hpp"

namespace vcockpit::systems {
namespace {

constexpr const char* kMagic = "# vcockpit systems checkpoint, version 1";

}  // namespace

void write_systems_checkpoint(const std::string& path, const Systems& systems,
                              const ProcedureRunner* procedures) {
  const SystemsState& s = systems.state();
  std::string text = std::string(kMagic) + "\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "model_hash %016" PRIx64 "\n", systems.model_hash());
  text += buf;
  text += "step " + std::to_string(s.step) + "\ntime_ns " + std::to_string(s.time_ns) + "\nvalue";
  for (double v : s.value) {
    std::snprintf(buf, sizeof buf, " %a", v);
    text += buf;
  }
  text += "\nsince_step";
  for (int64_t v : s.since_step) text += " " + std::to_string(v);
  text += "\nlast_input";
  for (double v : s.last_input) {
    std::snprintf(buf, sizeof buf, " %a", v);
    text += buf;
  }
  text += "\nfailure";
  for (uint8_t f : s.failure) text += f != 0 ? " 1" : " 0";
  text += "\n";
  const std::size_t n = procedures != nullptr ? procedures->scores().size() : 0;
  std::snprintf(buf, sizeof buf, " %016" PRIx64, procedures != nullptr ? procedures->lesson_hash() : 0);
  text += "procedures " + std::to_string(n) + buf + "\n";
  for (std::size_t p = 0; p < n; ++p) {
    const ProcedureScore& score = procedures->scores()[p];
    text += "procedure " + std::to_string(static_cast<int>(score.state)) + " " +
            std::to_string(score.started_ns) + " " + std::to_string(score.ended_ns) + " " +
            std::to_string(score.last_done_ns) + " " + std::to_string(score.steps.size()) + "\n";
    for (const StepScore& st : score.steps) {
      text += "step " + std::to_string(static_cast<int>(st.status)) + " " +
              std::to_string(st.out_of_order) + " " + std::to_string(st.late) + " " +
              std::to_string(st.undone) + " " + std::to_string(st.done_ns) + " " +
              std::to_string(st.since_previous_ns) + " " + std::to_string(st.undone_ns) + " " +
              std::to_string(st.held_at_start) + " " + std::to_string(st.held_last) + "\n";
    }
  }
  AtomicFile file(path);
  file.write(text);
  file.commit();
}

SystemsCheckpoint read_systems_checkpoint(const std::string& path, const Systems& systems,
                                          const ProcedureRunner* procedures) {
  std::ifstream in(path);
  if (!in) throw FileError(path + ": cannot read: " + std::strerror(errno));
  int n = 0;
  const auto fail = [&](const std::string& what) -> void {
    throw CheckpointError(path + ":" + std::to_string(n) + ": " + what);
  };
  std::string line;
  const auto next = [&](const char* key) {
    ++n;
    if (!std::getline(in, line)) fail(std::string("ends before '") + key + "'");
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word != key) fail(std::string("expected '") + key + "'");
    std::vector<std::string> rest;
    while (words >> word) rest.push_back(word);
    return rest;
  };
  ++n;
  if (!std::getline(in, line) || line != kMagic) fail("not a systems checkpoint");
  const auto number = [&](const std::string& text) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v)) fail("'" + text + "' is not a number");
    return v;
  };
  const auto whole = [&](const std::string& text) -> int64_t {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0) fail("'" + text + "' is not a whole number");
    return v;
  };
  const auto one = [&](const char* key) {
    const auto words = next(key);
    if (words.size() != 1) fail(std::string(key) + ": one value expected");
    return words[0];
  };
  const std::string hash = one("model_hash");
  char expected[32];
  std::snprintf(expected, sizeof expected, "%016" PRIx64, systems.model_hash());
  if (hash != expected) fail("saved for another aircraft model or scene (model_hash " + hash + ", this one " + expected + ")");
  SystemsState s;
  s.step = whole(one("step"));
  s.time_ns = whole(one("time_ns"));
  const std::size_t systems_count = systems.model().elements.size();
  const auto words_of = [&](const char* key, std::size_t count) {
    const auto words = next(key);
    if (words.size() != count) fail(std::string(key) + ": " + std::to_string(count) + " values expected");
    return words;
  };
  for (const std::string& w : words_of("value", systems_count)) s.value.push_back(number(w));
  for (const std::string& w : words_of("since_step", systems_count)) s.since_step.push_back(whole(w));
  for (const std::string& w : words_of("last_input", systems_count)) s.last_input.push_back(number(w));
  for (const std::string& w : words_of("failure", systems.model().failures.size())) {
    const int64_t v = whole(w);
    if (v != 0 && v != 1) fail("failure: 0 or 1 expected");
    s.failure.push_back(static_cast<uint8_t>(v));
  }
  if (s.step < 0) fail("step: negative");
  SystemsCheckpoint out;
  out.state = std::move(s);
  const std::size_t count = procedures != nullptr ? procedures->scores().size() : 0;
  const auto counted = next("procedures");
  char lesson[32];
  std::snprintf(lesson, sizeof lesson, "%016" PRIx64, procedures != nullptr ? procedures->lesson_hash() : 0);
  if (counted.size() != 2 || whole(counted[0]) != static_cast<int64_t>(count) || counted[1] != lesson)
    fail("procedures: saved for another lesson");
  const auto flag = [&](const std::string& w) {
    const int64_t v = whole(w);
    if (v != 0 && v != 1) fail("'" + w + "': 0 or 1 expected");
    return v == 1;
  };
  for (std::size_t p = 0; p < count; ++p) {
    const auto words = next("procedure");
    const std::size_t steps = procedures->scores()[p].steps.size();
    if (words.size() != 5 || whole(words[4]) != static_cast<int64_t>(steps))
      fail("procedure: saved for another lesson");
    ProcedureScore score;
    const int64_t state = whole(words[0]);
    if (state < 0 || state > 3) fail("procedure: no state " + words[0]);
    score.state = static_cast<ProcedureState>(state);
    score.started_ns = whole(words[1]);
    score.ended_ns = whole(words[2]);
    score.last_done_ns = whole(words[3]);
    for (std::size_t k = 0; k < steps; ++k) {
      const auto w = next("step");
      if (w.size() != 9) fail("step: 9 values expected");
      StepScore st;
      const int64_t status = whole(w[0]);
      if (status < 0 || status > 2) fail("step: no status " + w[0]);
      st.status = static_cast<StepStatus>(status);
      st.out_of_order = flag(w[1]);
      st.late = flag(w[2]);
      st.undone = flag(w[3]);
      st.done_ns = whole(w[4]);
      st.since_previous_ns = whole(w[5]);
      st.undone_ns = whole(w[6]);
      st.held_at_start = flag(w[7]);
      st.held_last = flag(w[8]);
      score.steps.push_back(st);
    }
    out.scores.push_back(std::move(score));
  }
  return out;
}

}  // namespace vcockpit::systems
