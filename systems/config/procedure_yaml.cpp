#include "systems/config/procedure_yaml.hpp"

#include <filesystem>

#include "common/yaml_config.hpp"

namespace vcockpit {
namespace {

systems::Origin origin_of(const ConfigNode& node) {
  return node.file() + ":" + std::to_string(node.line()) + ":" + std::to_string(node.column()) +
         ": " + (node.key_path().empty() ? std::string("(top level)") : node.key_path());
}

systems::SourceExpression expression_of(const ConfigNode& node) {
  if (!node.is_scalar()) node.fail("expected a condition (a string)");
  const std::string text = node.as_string();
  try {
    return {systems::Expression::parse(text), origin_of(node)};
  } catch (const systems::ExpressionError& e) {
    node.fail(std::string(e.what()) + " in \"" + text + "\"");
  }
}

std::string text_of(const ConfigNode& node, const char* key) {
  const std::string text = node.get_string(key);
  if (text.empty() || text.size() > 60) node[key].fail("1 to 60 characters");
  return text;
}

systems::ProcedureStep step_of(const ConfigNode& node, int group) {
  node.expect_keys({"item", "action", "when", "within_s", "rises", "momentary"});
  systems::ProcedureStep s;
  s.item = text_of(node, "item");
  s.action = text_of(node, "action");
  s.when = expression_of(node["when"]);
  if (auto within = node.find("within_s")) {
    s.within_s = within->as_double();
    if (s.within_s < 0) within->fail("must be >= 0");
  }
  s.rises = node.get_bool("rises", false);
  s.momentary = node.get_bool("momentary", false);
  s.group = group;
  s.origin = origin_of(node);
  return s;
}

systems::Procedure parse_procedure(const ConfigNode& root, const std::string& path) {
  root.expect_keys({"title", "time_limit_s", "steps"});
  systems::Procedure p;
  p.name = std::filesystem::path(path).stem().string();
  p.title = text_of(root, "title");
  p.origin = origin_of(root);
  if (auto limit = root.find("time_limit_s")) {
    p.time_limit_s = limit->as_double();
    if (p.time_limit_s <= 0) limit->fail("must be positive");
  }
  int groups = 0;
  for (const ConfigNode& s : root["steps"].elements()) {
    if (s.has("any_order")) {
      s.expect_keys({"any_order"});
      const std::vector<ConfigNode> members = s["any_order"].elements();
      if (members.size() < 2) s["any_order"].fail("a group of at least 2 steps");
      for (const ConfigNode& m : members) p.steps.push_back(step_of(m, groups));
      ++groups;
    } else {
      p.steps.push_back(step_of(s, -1));
    }
  }
  if (p.steps.empty()) root["steps"].fail("no steps");
  if (p.steps.size() > 32) root["steps"].fail("at most 32 steps");
  return p;
}

}  // namespace

systems::Procedure load_procedure(const std::string& path) {
  return parse_procedure(ConfigNode::load_file(path), path);
}

systems::Lesson load_lesson(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  root.expect_keys({"title", "procedures"});
  systems::Lesson lesson;
  lesson.source = path;
  lesson.title = text_of(root, "title");
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  for (const ConfigNode& entry : root["procedures"].elements()) {
    entry.expect_keys({"file", "starts_when", "time_limit_s"});
    const ConfigNode file = entry["file"];
    const std::filesystem::path procedure_path = dir / file.as_string();
    if (!std::filesystem::is_regular_file(procedure_path))
      file.fail("no procedure file " + procedure_path.string());
    systems::Procedure p = load_procedure(procedure_path.string());
    if (auto starts = entry.find("starts_when")) p.starts_when = expression_of(*starts);
    if (auto limit = entry.find("time_limit_s")) {
      p.time_limit_s = limit->as_double();
      if (p.time_limit_s <= 0) limit->fail("must be positive");
    }
    lesson.procedures.push_back(std::move(p));
  }
  if (lesson.procedures.empty()) root["procedures"].fail("no procedures");
  if (lesson.procedures.size() > 16) root["procedures"].fail("at most 16 procedures");
  return lesson;
}

}  // namespace vcockpit
