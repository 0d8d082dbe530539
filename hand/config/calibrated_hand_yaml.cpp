#include "hand/config/calibrated_hand_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include "common/atomic_file.hpp"
#include "common/config_error.hpp"
#include "hand/config/hand_yaml.hpp"

namespace vcockpit {
namespace {

YAML::Node flow_vector(const Eigen::Vector3d& v) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (int i = 0; i < 3; ++i) n.push_back(v[i]);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

}  // namespace

void write_calibrated_hand_yaml(const std::string& source_yaml, const hand::HandModel& hand,
                                const std::string& out_path, const std::vector<std::string>& comments) {
  (void)load_hand_model(source_yaml);  // a bad source fails here, with its file and line
  YAML::Node root = YAML::LoadFile(source_yaml);
  // the file describes a right hand; a left one is its mirror image
  const hand::HandModel right = hand.left ? hand::mirrored(hand) : hand;
  root["side"] = hand.left ? "left" : "right";
  root["palm"]["tracking_point"] = flow_vector(right.p_H_palm_joint);
  root["palm"]["wrist_tracking_point"] = flow_vector(right.p_H_wrist_joint);
  static const char* kFingers[hand::kFingerCount] = {"thumb", "index", "middle", "ring", "little"};
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const hand::FingerChain& chain = right.fingers[static_cast<std::size_t>(f)];
    YAML::Node finger = root["fingers"][kFingers[f]];
    finger["base"]["position"] = flow_vector(chain.X_HB.translation());
    YAML::Node rows = finger["chain"];
    if (!rows.IsSequence() || rows.size() != chain.rows.size())
      throw ConfigError(source_yaml + ": fingers." + kFingers[f] + ".chain: not the chain the hand was calibrated from");
    for (std::size_t i = 0; i < chain.rows.size(); ++i) rows[i]["a"] = chain.rows[i].a_m;
  }
  YAML::Emitter out;
  out.SetDoublePrecision(9);
  out << root;
  std::string text;
  for (const std::string& c : comments) text += "# " + c + "\n";
  text += out.c_str();
  text += "\n";
  AtomicFile file(out_path);
  file.write(text);
  file.commit();
}

}  // namespace vcockpit
