#include "bench/mujoco_scene.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace vcockpit::bench {
namespace {

using hand::kLinkCount;

// Collision filter: (contype1 & conaffinity2) || (contype2 & conaffinity1) lets a pair collide.
// Static and hand geoms accept nothing, so they meet only dynamic geoms, which accept everyone.
// A control's geom accepts the hand only: as in ours, it never meets its panel or another control
// (and free objects meet it through their own affinity).
constexpr int kStaticType = 1, kStaticAffinity = 0;
constexpr int kHandType = 2, kHandAffinity = 0;
constexpr int kControlType = 8, kControlAffinity = kHandType;
constexpr int kDynamicType = 4,
              kDynamicAffinity = kStaticType | kHandType | kDynamicType | kControlType;

// MuJoCo 2.2.2 sizes its contact and constraint buffers at compile time (nconmax, njmax; 2.3
// grows them), and mjData holds njmax x njmax and njmax x nv arrays that it clears: 500 loose
// objects cost about 1 GB at the budget below. Resting bodies need 2 contacts each on average
// (a box on a box 4, a capsule 2, a sphere or a cylinder 1; measured: 1056 contacts for the
// crowded cockpit's 516 dynamic objects), so 3 per dynamic body and hand link leave 50% spare;
// step() throws when they do not fit. A pyramidal condim-3 contact is 4 constraint rows.
constexpr int kContactsPerBody = 3;
constexpr int kRowsPerContact = 4;
constexpr int kMinContacts = 200;

constexpr double kParkedHeight_m = 100.0;  // hand links until the first set_hand: far from all

// Tests and benchmarks run in processes that must not exit() on a MuJoCo error or write
// MUJOCO_LOG.TXT on a warning (MuJoCo's defaults): errors become exceptions (as in MuJoCo's
// Python bindings), warnings go to stderr and are also read from mjData by step().
void throw_error(const char* message) {
  throw std::runtime_error(std::string("MuJoCo error: ") + message);
}
void print_warning(const char* message) { std::fprintf(stderr, "MuJoCo warning: %s\n", message); }
void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = throw_error;
    mju_user_warning = print_warning;
  });
}

// XML-safe, MuJoCo-unique names: [A-Za-z0-9_] only, a suffix on a clash.
struct Names {
  std::vector<std::string> objects;
  std::array<std::string, kLinkCount> links;
};

std::string unique_name(const std::string& wanted, std::set<std::string>& used) {
  std::string name = wanted.empty() ? std::string("unnamed") : wanted;
  for (char& c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
      c = '_';
  std::string candidate = name;
  for (int n = 1; used.count(candidate) > 0; ++n) candidate = name + "_" + std::to_string(n);
  used.insert(candidate);
  return candidate;
}

Names scene_names(const physics::Scene& scene) {
  Names names;
  std::set<std::string> used;
  for (int l = 0; l < kLinkCount; ++l)
    names.links[static_cast<std::size_t>(l)] =
        unique_name("hand_" + std::string(hand::link_name(static_cast<hand::Link>(l))), used);
  for (const physics::ObjectSpec& o : scene.objects) names.objects.push_back(unique_name(o.name, used));
  return names;
}

int dynamic_count(const physics::Scene& scene) {
  int n = 0;
  for (const physics::ObjectSpec& o : scene.objects) n += o.dynamic ? 1 : 0;
  return n;
}

// Numbers written to round-trip exactly.
class Xml {
 public:
  Xml() { out_.precision(std::numeric_limits<double>::max_digits10); }
  std::ostringstream& out() { return out_; }
  std::string str() const { return out_.str(); }

  Xml& vec(const Eigen::Vector3d& v) {
    out_ << v.x() << ' ' << v.y() << ' ' << v.z();
    return *this;
  }
  // pos and quat (w x y z, MuJoCo's order) attributes of a frame.
  Xml& frame(const Eigen::Isometry3d& X) {
    const Eigen::Quaterniond q(X.linear());
    out_ << " pos=\"";
    vec(X.translation());
    out_ << "\" quat=\"" << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << '"';
    return *this;
  }

 private:
  std::ostringstream out_;
};

void write_shape(Xml& xml, const physics::Shape& shape) {
  auto& out = xml.out();
  switch (shape.kind) {
    case physics::ShapeKind::kBox:
      out << " type=\"box\" size=\"";
      xml.vec(0.5 * shape.box_size_m);  // MJCF box size is half extents
      out << '"';
      return;
    case physics::ShapeKind::kSphere:
      out << " type=\"sphere\" size=\"" << shape.radius_m << '"';
      return;
    case physics::ShapeKind::kCapsule:  // both: radius, half length along z, caps excluded
      out << " type=\"capsule\" size=\"" << shape.radius_m << ' ' << 0.5 * shape.length_m << '"';
      return;
    case physics::ShapeKind::kCylinder:
      out << " type=\"cylinder\" size=\"" << shape.radius_m << ' ' << 0.5 * shape.length_m << '"';
      return;
    case physics::ShapeKind::kMesh:  // (MJCF meshes are assets of their own: not compared yet)
      throw std::invalid_argument("mjcf_from_scene: a mesh shape has no MJCF geom here");
  }
  throw std::invalid_argument("mjcf_from_scene: unknown shape kind");
}

void write_contact(Xml& xml, int type, int affinity, double mu_s) {
  xml.out() << " contype=\"" << type << "\" conaffinity=\"" << affinity << "\" friction=\"" << mu_s
            << " 0.005 0.0001\"";
}

void write_rgba(Xml& xml, const std::array<float, 4>& rgba) {
  xml.out() << " rgba=\"" << rgba[0] << ' ' << rgba[1] << ' ' << rgba[2] << ' ' << rgba[3] << '"';
}

void write_inertial(Xml& xml, const physics::ObjectSpec& o) {
  const Eigen::Matrix3d& I = o.I_O;
  auto& out = xml.out();
  out << "      <inertial pos=\"0 0 0\" mass=\"" << o.mass_kg << '"';
  if (I(0, 1) == 0.0 && I(0, 2) == 0.0 && I(1, 2) == 0.0)  // our shapes: principal axes = O
    out << " diaginertia=\"" << I(0, 0) << ' ' << I(1, 1) << ' ' << I(2, 2) << "\"/>\n";
  else
    out << " fullinertia=\"" << I(0, 0) << ' ' << I(1, 1) << ' ' << I(2, 2) << ' ' << I(0, 1)
        << ' ' << I(0, 2) << ' ' << I(1, 2) << "\"/>\n";
}

// A control: a body at its joint frame with a slide or hinge joint along z (its limits, spring,
// damper and Coulomb friction as MuJoCo's range, stiffness / springref, damping, frictionloss),
// the moving part's inertia and geom at X_JO. Detents, snaps and gates have no MuJoCo
// counterpart (they would be a user force), so MuJoCo steps the linear mechanism only.
void write_control(Xml& xml, const physics::ControlSpec& c, const physics::ObjectSpec& o,
                   const std::string& name) {
  auto& out = xml.out();
  out << "    <body name=\"" << name << '"';
  xml.frame(c.X_GJ);
  out << ">\n      <joint name=\"" << name << "\" type=\""
      << (c.joint == physics::JointKind::kPrismatic ? "slide" : "hinge") << "\" axis=\"0 0 1\"";
  if (c.limited) out << " limited=\"true\" range=\"" << c.q_min << ' ' << c.q_max << '"';
  out << " stiffness=\"" << c.stiffness << "\" springref=\"" << c.q_rest << "\" damping=\""
      << c.damping << "\" frictionloss=\"" << c.friction << "\"/>\n";
  // the inertia about the centroid in the joint frame's axes (fullinertia fixes the orientation)
  const Eigen::Matrix3d I = c.X_JO.linear() * o.I_O * c.X_JO.linear().transpose();
  const Eigen::Vector3d p = c.X_JO.translation();
  out << "      <inertial pos=\"" << p.x() << ' ' << p.y() << ' ' << p.z() << "\" mass=\""
      << o.mass_kg << "\" fullinertia=\"" << I(0, 0) << ' ' << I(1, 1) << ' ' << I(2, 2) << ' '
      << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 2) << "\"/>\n";
  out << "      <geom name=\"" << name << '"';
  write_shape(xml, o.shape);
  xml.frame(c.X_JO);
  write_contact(xml, kControlType, kControlAffinity, o.material.mu_s);
  write_rgba(xml, o.color_rgba);
  out << "/>\n    </body>\n";
}

void write_hand(Xml& xml, const physics::Scene& scene, const Names& names) {
  const hand::HandModel& hand = scene.hands[0];
  const double mu_s = scene.hand_material.mu_s;
  const std::array<float, 4> skin{0.85f, 0.7f, 0.6f, 1.0f};
  auto& out = xml.out();
  for (int l = 0; l < kLinkCount; ++l) {
    const std::string& name = names.links[static_cast<std::size_t>(l)];
    out << "    <body name=\"" << name << "\" mocap=\"true\" pos=\"0 0 " << kParkedHeight_m
        << "\">\n      <geom name=\"" << name << '"';
    if (l == static_cast<int>(hand::Link::kPalm)) {
      write_shape(xml, physics::Shape::box(hand.palm_size_m));  // centred on the palm frame
    } else {
      // the capsule spans [0, length] on x_L: centred at length / 2, its z axis turned onto x_L
      // by Ry(+90 deg)
      const hand::Capsule& c = hand.capsules[static_cast<std::size_t>(l)];
      const double s = std::sqrt(0.5);
      write_shape(xml, physics::Shape::capsule(c.radius_m, c.length_m));
      out << " pos=\"" << 0.5 * c.length_m << " 0 0\" quat=\"" << s << " 0 " << s << " 0\"";
    }
    write_contact(xml, kHandType, kHandAffinity, mu_s);
    write_rgba(xml, skin);
    out << "/>\n    </body>\n";
  }
}

}  // namespace

std::string mjcf_from_scene(const physics::Scene& scene) {
  const Names names = scene_names(scene);
  const int bodies = dynamic_count(scene) + (scene.has_hands() ? kLinkCount : 0);
  const int nconmax = std::max(kMinContacts, kContactsPerBody * bodies);

  Xml xml;
  auto& out = xml.out();
  out << "<mujoco model=\"vcockpit\">\n"
      << "  <compiler angle=\"radian\"/>\n"
      << "  <option timestep=\"" << scene.step_s << "\" gravity=\"";
  xml.vec(scene.gravity_mps2);
  out << "\" integrator=\"Euler\"/>\n"
      << "  <size nconmax=\"" << nconmax << "\" njmax=\"" << kRowsPerContact * nconmax << "\"/>\n"
      << "  <worldbody>\n";
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const physics::ObjectSpec& o = scene.objects[i];
    if (o.dynamic) continue;
    out << "    <geom name=\"" << names.objects[i] << '"';
    write_shape(xml, o.shape);
    xml.frame(o.X_GO);
    write_contact(xml, kStaticType, kStaticAffinity, o.material.mu_s);
    write_rgba(xml, o.color_rgba);
    out << "/>\n";
  }
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const physics::ObjectSpec& o = scene.objects[i];
    if (!o.dynamic) continue;
    if (o.control >= 0) {
      write_control(xml, scene.controls[static_cast<std::size_t>(o.control)], o, names.objects[i]);
      continue;
    }
    // body frame = our centroid frame O: inertial and geom at its origin
    out << "    <body name=\"" << names.objects[i] << '"';
    xml.frame(o.X_GO);
    out << ">\n      <joint name=\"" << names.objects[i] << "\" type=\"free\"/>\n";
    write_inertial(xml, o);
    out << "      <geom name=\"" << names.objects[i] << '"';
    write_shape(xml, o.shape);
    write_contact(xml, kDynamicType, kDynamicAffinity, o.material.mu_s);
    write_rgba(xml, o.color_rgba);
    out << "/>\n    </body>\n";
  }
  if (scene.has_hands()) write_hand(xml, scene, names);
  out << "  </worldbody>\n";
  if (scene.has_hands()) {
    // one weld per dynamic object to the palm, off until the object is held (set_object_states)
    out << "  <equality>\n";
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      if (!scene.objects[i].dynamic || scene.objects[i].control >= 0) continue;
      out << "    <weld name=\"hold_" << names.objects[i] << "\" body1=\""
          << names.links[static_cast<std::size_t>(hand::Link::kPalm)] << "\" body2=\""
          << names.objects[i] << "\" active=\"false\"/>\n";
    }
    out << "  </equality>\n";
  }
  out << "</mujoco>\n";
  return xml.str();
}

MujocoWorld::MujocoWorld(const physics::Scene& scene) {
  install_handlers();
  const std::string mjcf = mjcf_from_scene(scene);

  // Load from memory: a one-file virtual file system (2 MB of names: on the heap).
  constexpr const char* kFile = "vcockpit_scene.xml";
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kFile, static_cast<int>(mjcf.size())) != 0)
    throw std::runtime_error("MujocoWorld: cannot make the in-memory MJCF file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), kFile)], mjcf.data(), mjcf.size());
  std::array<char, 1024> error{};
  m_ = mj_loadXML(kFile, vfs.get(), error.data(), static_cast<int>(error.size()));
  mj_deleteVFS(vfs.get());
  if (m_ == nullptr) throw std::runtime_error(std::string("MuJoCo: ") + error.data());
  d_ = mj_makeData(m_);
  if (d_ == nullptr) {
    mj_deleteModel(m_);
    throw std::runtime_error("MuJoCo: mj_makeData failed");
  }

  const Names names = scene_names(scene);
  const std::size_t n = scene.objects.size();
  X_GO_spec_.resize(n);
  object_body_.assign(n, -1);
  object_geom_.assign(n, -1);
  object_qpos_.assign(n, -1);
  object_qvel_.assign(n, -1);
  object_control_.assign(n, std::nullopt);
  for (std::size_t i = 0; i < n; ++i) {
    X_GO_spec_[i] = scene.objects[i].X_GO;
    object_geom_[i] = mj_name2id(m_, mjOBJ_GEOM, names.objects[i].c_str());
    if (!scene.objects[i].dynamic) continue;
    const int body = mj_name2id(m_, mjOBJ_BODY, names.objects[i].c_str());
    const int joint = m_->body_jntadr[body];
    object_body_[i] = body;
    object_qpos_[i] = m_->jnt_qposadr[joint];
    object_qvel_[i] = m_->jnt_dofadr[joint];
    if (scene.objects[i].control >= 0) {
      const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(scene.objects[i].control)];
      object_control_[i] = c;
      d_->qpos[object_qpos_[i]] = c.q_initial;
    }
  }
  object_weld_.assign(n, -1);
  if (scene.has_hands())
    for (std::size_t i = 0; i < n; ++i)
      if (scene.objects[i].dynamic && scene.objects[i].control < 0)
        object_weld_[i] = mj_name2id(m_, mjOBJ_EQUALITY, ("hold_" + names.objects[i]).c_str());
  has_hand_ = scene.has_hands();
  hand_mocap_.fill(-1);
  hand_geom_.fill(-1);
  if (has_hand_)
    for (std::size_t l = 0; l < kLinkCount; ++l) {
      hand_mocap_[l] = m_->body_mocapid[mj_name2id(m_, mjOBJ_BODY, names.links[l].c_str())];
      hand_geom_[l] = mj_name2id(m_, mjOBJ_GEOM, names.links[l].c_str());
    }
  mj_forward(m_, d_);
}

MujocoWorld::~MujocoWorld() {
  mj_deleteData(d_);
  mj_deleteModel(m_);
}

void MujocoWorld::set_hand(const std::array<Eigen::Isometry3d, kLinkCount>& X_GL) {
  if (!has_hand_) throw std::logic_error("MujocoWorld::set_hand: the scene has no hand");
  for (std::size_t l = 0; l < kLinkCount; ++l) {
    const Eigen::Quaterniond q(X_GL[l].linear());
    mjtNum* pos = d_->mocap_pos + 3 * hand_mocap_[l];
    mjtNum* quat = d_->mocap_quat + 4 * hand_mocap_[l];
    for (int k = 0; k < 3; ++k) pos[k] = X_GL[l].translation()[k];
    quat[0] = q.w();
    quat[1] = q.x();
    quat[2] = q.y();
    quat[3] = q.z();
  }
}

void MujocoWorld::set_object_states(const std::vector<physics::BodyState>& bodies) {
  if (bodies.size() != object_body_.size())
    throw std::invalid_argument("MujocoWorld::set_object_states: one state per scene object");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (object_body_[i] < 0) continue;
    const physics::BodyState& b = bodies[i];
    if (const auto& c = object_control_[i]) {
      // the joint coordinate of the pose: X_GJ^-1 X_GO X_JO^-1 is the joint's motion
      const Eigen::Isometry3d M = c->X_GJ.inverse() * b.X_GO * c->X_JO.inverse();
      const Eigen::Vector3d a = physics::joint_axis_G(*c);
      const bool slide = c->joint == physics::JointKind::kPrismatic;
      d_->qpos[object_qpos_[i]] = slide ? M.translation().z() : std::atan2(M.linear()(1, 0), M.linear()(0, 0));
      d_->qvel[object_qvel_[i]] = slide ? a.dot(b.v_G) : a.dot(b.w_G);
      continue;
    }
    const Eigen::Quaterniond q(b.X_GO.linear());
    mjtNum* qpos = d_->qpos + object_qpos_[i];
    mjtNum* qvel = d_->qvel + object_qvel_[i];
    for (int k = 0; k < 3; ++k) qpos[k] = b.X_GO.translation()[k];
    qpos[3] = q.w();
    qpos[4] = q.x();
    qpos[5] = q.y();
    qpos[6] = q.z();
    // free joint: linear velocity of the body origin in world, angular velocity in the body frame
    const Eigen::Vector3d w_O = b.X_GO.linear().transpose() * b.w_G;
    for (int k = 0; k < 3; ++k) {
      qvel[k] = b.v_G[k];
      qvel[3 + k] = w_O[k];
    }
    weld_to_palm(static_cast<int>(i), b);
  }
}

// MuJoCo 2.2's weld data (mjNEQDATA = 11): anchor (3, on body2), relpose (3 + quaternion 4: body2's
// pose in body1's frame), torquescale (1).
void MujocoWorld::weld_to_palm(int object, const physics::BodyState& body) {
  const int weld = object_weld_[static_cast<std::size_t>(object)];
  if (weld < 0) return;
  const bool held = body.held_by != physics::kNotHeld;
  m_->eq_active[weld] = held ? 1 : 0;
  if (!held) return;
  const int palm = hand_mocap_[static_cast<std::size_t>(hand::Link::kPalm)];
  const mjtNum* p = d_->mocap_pos + 3 * palm;
  const mjtNum* q = d_->mocap_quat + 4 * palm;
  Eigen::Isometry3d X_GP = Eigen::Isometry3d::Identity();
  X_GP.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  X_GP.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  const Eigen::Isometry3d X_PO = X_GP.inverse() * body.X_GO;
  const Eigen::Quaterniond q_PO(X_PO.linear());
  mjtNum* data = m_->eq_data + mjNEQDATA * weld;
  for (int k = 0; k < 3; ++k) data[k] = 0.0;
  for (int k = 0; k < 3; ++k) data[3 + k] = X_PO.translation()[k];
  data[6] = q_PO.w();
  data[7] = q_PO.x();
  data[8] = q_PO.y();
  data[9] = q_PO.z();
  data[10] = 1.0;
}

void MujocoWorld::step() {
  mj_step(m_, d_);
  const auto raised = [&](int warning) { return d_->warning[warning].number > 0; };
  if (raised(mjWARN_CONTACTFULL) || raised(mjWARN_CNSTRFULL))
    throw std::runtime_error("MujocoWorld: contacts did not fit nconmax/njmax (" +
                             std::to_string(m_->nconmax) + "/" + std::to_string(m_->njmax) + ")");
  if (raised(mjWARN_BADQACC) || raised(mjWARN_BADQVEL) || raised(mjWARN_BADQPOS))
    throw std::runtime_error("MujocoWorld: the state went bad (MuJoCo reset it)");
}

void MujocoWorld::forward() { mj_forward(m_, d_); }

int MujocoWorld::contact_count() const { return d_->ncon; }

Eigen::Isometry3d MujocoWorld::object_pose(int object) const {
  const auto i = static_cast<std::size_t>(object);
  if (object < 0 || i >= object_body_.size())
    throw std::out_of_range("MujocoWorld::object_pose: no such object");
  if (object_body_[i] < 0) return X_GO_spec_[i];
  // qpos, not xpos: xpos is from the start of the last step
  const mjtNum* qpos = d_->qpos + object_qpos_[i];
  if (const auto& c = object_control_[i]) return physics::control_body_pose(*c, qpos[0]);
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();
  X_GO.translation() = Eigen::Vector3d(qpos[0], qpos[1], qpos[2]);
  X_GO.linear() = Eigen::Quaterniond(qpos[3], qpos[4], qpos[5], qpos[6]).normalized().toRotationMatrix();
  return X_GO;
}

double MujocoWorld::timestep_s() const { return m_->opt.timestep; }

int MujocoWorld::object_body(int object) const {
  return object_body_.at(static_cast<std::size_t>(object));
}
int MujocoWorld::object_geom(int object) const {
  return object_geom_.at(static_cast<std::size_t>(object));
}
int MujocoWorld::hand_geom(int link) const { return hand_geom_.at(static_cast<std::size_t>(link)); }

}  // namespace vcockpit::bench
