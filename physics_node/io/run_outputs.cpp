#include "physics_node/io/run_outputs.hpp"

#include <cstdio>

#include "common/json.hpp"
#include "physics_node/io/grasp_event_text.hpp"

namespace vcockpit::physics_io {

std::string hand_name(int hand_id) { return hand_id == 1 ? "left" : "right"; }


TrajectoryWriter::TrajectoryWriter(const std::string& path) : file_(path) {
  std::fprintf(file_.get(), "t_s,object,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held_by\n");
}

void TrajectoryWriter::write(const physics::World& world) {
  const auto& objects = world.scene().objects;
  const double t_s = static_cast<double>(world.time_ns()) / 1e9;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!objects[i].dynamic) continue;
    const auto& b = world.bodies()[i];
    const Eigen::Vector3d p = b.X_GO.translation();
    const Eigen::Quaterniond q(b.X_GO.linear());
    std::fprintf(file_.get(),
                 "%.6f,%s,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%s\n",
                 t_s, objects[i].name.c_str(), p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(),
                 b.v_G.x(), b.v_G.y(), b.v_G.z(), b.w_G.x(), b.w_G.y(), b.w_G.z(),
                 b.held_by == physics::kNotHeld ? "" : hand_name(b.held_by).c_str());
  }
}

EventWriter::EventWriter(const std::string& path) : file_(path) {}

void EventWriter::write(const physics::World& world) {
  for (const auto& e : world.step_events()) {
    (e.grasp ? grasps_ : releases_)++;
    std::fprintf(file_.get(),
                 "{\"t_s\": %.6f, \"event\": \"%s\", \"hand\": \"%s\", \"object\": %s, "
                 "\"reason\": %s, \"contacts\": %d, \"residual_force_N\": %.6f, "
                 "\"residual_torque_Nm\": %.6f}\n",
                 static_cast<double>(e.t_ns) / 1e9, e.grasp ? "grasp" : "release",
                 hand_name(e.hand_id).c_str(),
                 json_string(world.scene().objects[e.object].name).c_str(),
                 json_string(grasp_event_text(e)).c_str(), e.contacts, e.residual_force_N,
                 e.residual_torque_Nm);
  }
}

void write_summary(const std::string& path, const RunSummary& s, const physics::World& world) {
  AtomicFile file(path);
  std::FILE* f = file.get();
  const double mean_m =
      s.penetration_points > 0 ? s.penetration_sum_m / static_cast<double>(s.penetration_points) : 0.0;
  std::fprintf(f, "{\n  \"scene\": %s,\n  \"log\": %s,\n", json_string(s.scene_path).c_str(),
               s.log_path.empty() ? "null" : json_string(s.log_path).c_str());
  std::fprintf(f, "  \"steps\": %llu,\n  \"substeps_per_step\": %d,\n  \"substeps_mean\": %.3f,\n",
               static_cast<unsigned long long>(s.steps), s.substeps,
               s.steps > 0 ? static_cast<double>(s.substeps_total) / static_cast<double>(s.steps) : 0.0);
  std::fprintf(f, "  \"simulated_s\": %.6f,\n  \"wall_s\": %.6f,\n  \"realtime_factor\": %.3f,\n",
               s.simulated_s, s.wall_s, s.wall_s > 0 ? s.simulated_s / s.wall_s : 0.0);
  std::fprintf(f, "  \"grasps\": %d,\n  \"releases\": %d,\n", s.grasps, s.releases);
  std::fprintf(f, "  \"hand_penetration_max_m\": %.9f,\n  \"hand_penetration_mean_m\": %.9f,\n",
               s.penetration_max_m, mean_m);
  std::fprintf(f, "  \"stage_wall_s\": {");
  for (int i = 0; i < physics::kStageCount; ++i) {
    std::fprintf(f, "%s\"%s\": %.6f", i ? ", " : "", physics::stage_name(static_cast<physics::Stage>(i)),
                 i < static_cast<int>(s.stage_total_s.size()) ? s.stage_total_s[i] : 0.0);
  }
  std::fprintf(f, "},\n  \"final\": {\n");
  const auto& objects = world.scene().objects;
  bool first = true;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!objects[i].dynamic) continue;
    const auto& b = world.bodies()[i];
    const Eigen::Vector3d p = b.X_GO.translation();
    const Eigen::Quaterniond q(b.X_GO.linear());
    std::fprintf(f,
                 "%s    %s: {\"position\": [%.9f, %.9f, %.9f], \"quaternion_wxyz\": [%.9f, %.9f, "
                 "%.9f, %.9f], \"held_by\": %s}",
                 first ? "" : ",\n", json_string(objects[i].name).c_str(), p.x(), p.y(), p.z(),
                 q.w(), q.x(), q.y(), q.z(),
                 b.held_by == physics::kNotHeld ? "null" : json_string(hand_name(b.held_by)).c_str());
    first = false;
  }
  std::fprintf(f, "\n  }\n}\n");
  file.commit();
}

}  // namespace vcockpit::physics_io
