// The render library: off-axis stereo camera maths against closed forms (tan of the FOV angles,
// glFrustum), config validation, instance packing, unit meshes, then real OSMesa frames checked
// pixel by pixel where project_to_pixel says objects land, and the PNG export.

#include "image_generator/render/render.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <new>
#include <numbers>
#include <string>
#include <vector>

#include "image_generator/render/instance_packing.hpp"
#include "image_generator/render/meshes.hpp"
#include "model/import/model_file.hpp"
#include "tests/support/process.hpp"

// Counts C++ heap allocations on a thread while asked to, to show render() allocates nothing
// once warmed up. Not under AddressSanitizer, which owns operator new itself.
namespace {
thread_local bool g_count_allocations = false;
std::atomic<long> g_allocations{0};
}  // namespace

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kCountingAllocations = false;
// OSMesa keeps one framebuffer record per pixel format in a global list it never frees (a few
// hundred bytes, bounded); not ours to fix.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}
#else
constexpr bool kCountingAllocations = true;
// GCC pairs the malloc below with the free in delete after inlining and warns; they do match
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  if (g_count_allocations) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop
#endif

namespace vcockpit::render {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kHeadHeightM = 1.2;

// llvmpipe reads this when the first context is made; respect a value set by the caller
const bool kThreadsSet = [] { return setenv("LP_NUM_THREADS", "2", 0) == 0; }();

Eigen::Isometry3d head_pose() {
  return Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, kHeadHeightM));
}

Eigen::Isometry3d at(double x_m, double y_m, double z_m) {
  return Eigen::Isometry3d(Eigen::Translation3d(x_m, y_m, z_m));
}

Instance make(Primitive primitive, const Eigen::Isometry3d& X_GO, const Eigen::Vector3d& size_m,
              std::array<float, 4> rgba, bool highlight = false) {
  Instance instance;
  instance.primitive = primitive;
  instance.X_GO = X_GO;
  instance.size_m = size_m;
  instance.rgba = rgba;
  instance.highlight = highlight;
  return instance;
}

constexpr std::array<float, 4> kRed{1.0f, 0.0f, 0.0f, 1.0f};
constexpr std::array<float, 4> kGreen{0.0f, 1.0f, 0.0f, 1.0f};
constexpr std::array<float, 4> kBlue{0.0f, 0.0f, 1.0f, 1.0f};
constexpr std::array<float, 4> kYellow{1.0f, 1.0f, 0.0f, 1.0f};

// ---------------------------------------------------------------------------------------------
// camera maths

TEST(Camera, EyesAreIpdApartLeftEyeOnPlusY) {
  const HmdConfig config;
  const Eigen::Isometry3d X_GHead =
      at(1.0, 2.0, 3.0) * Eigen::AngleAxisd(30 * kDeg, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d p_L = eye_pose(config, Eye::kLeft, X_GHead).translation();
  const Eigen::Vector3d p_R = eye_pose(config, Eye::kRight, X_GHead).translation();
  EXPECT_NEAR((p_L - p_R).norm(), 0.063, 1e-12);
  EXPECT_TRUE((X_GHead.inverse() * p_L).isApprox(Eigen::Vector3d(0, 0.0315, 0), 1e-12));
  EXPECT_TRUE(eye_pose(config, Eye::kLeft, X_GHead).linear().isApprox(X_GHead.linear(), 1e-12));
}

// A point on an eye's optical axis lands where the tangents put it: for an asymmetric FOV that
// is not the image centre.
TEST(Camera, OnAxisPointLandsWhereTheTangentsPutIt) {
  const HmdConfig config;
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const EyeFov& fov = config.eye_fov(eye);
    const double tl = std::tan(fov.left_rad), tr = std::tan(fov.right_rad);
    const double tu = std::tan(fov.up_rad), td = std::tan(fov.down_rad);
    const Eigen::Isometry3d X_GE = eye_pose(config, eye, head_pose());
    Eigen::Vector2d pixel;
    ASSERT_TRUE(project_to_pixel(config, eye, head_pose(), X_GE * Eigen::Vector3d(2, 0, 0), pixel));
    EXPECT_NEAR(pixel.x(), -tl / (tr - tl) * 1280, 1e-9);
    EXPECT_NEAR(pixel.y(), tu / (tu - td) * 720, 1e-9);
    EXPECT_GT(std::abs(pixel.x() - 640.0), 50.0) << "asymmetric FOV: axis is off centre";
    EXPECT_GT(std::abs(pixel.y() - 360.0), 20.0);
  }
  // left eye sees further left than right, so its axis lands right of centre; right eye mirrors
  Eigen::Vector2d left, right;
  ASSERT_TRUE(project_to_pixel(config, Eye::kLeft, head_pose(),
                               eye_pose(config, Eye::kLeft, head_pose()) * Eigen::Vector3d(2, 0, 0),
                               left));
  ASSERT_TRUE(project_to_pixel(
      config, Eye::kRight, head_pose(),
      eye_pose(config, Eye::kRight, head_pose()) * Eigen::Vector3d(2, 0, 0), right));
  EXPECT_GT(left.x(), 640.0);
  EXPECT_LT(right.x(), 640.0);
  EXPECT_NEAR(left.x() + right.x(), 1280.0, 1e-9);
}

TEST(Camera, AngleOffAxisMapsLinearlyInTangent) {
  const HmdConfig config;
  const EyeFov& fov = config.eye_fov(Eye::kLeft);
  const double tl = std::tan(fov.left_rad), tr = std::tan(fov.right_rad);
  const double tu = std::tan(fov.up_rad), td = std::tan(fov.down_rad);
  // 20 deg right of and 10 deg above the axis, 3 m away
  const Eigen::Vector3d p_E(3.0, -3.0 * std::tan(20 * kDeg), 3.0 * std::tan(10 * kDeg));
  Eigen::Vector2d pixel;
  ASSERT_TRUE(project_to_pixel(config, Eye::kLeft, head_pose(),
                               eye_pose(config, Eye::kLeft, head_pose()) * p_E, pixel));
  EXPECT_NEAR(pixel.x(), (std::tan(20 * kDeg) - tl) / (tr - tl) * 1280, 1e-9);
  EXPECT_NEAR(pixel.y(), (tu - std::tan(10 * kDeg)) / (tu - td) * 720, 1e-9);
}

TEST(Camera, BehindOrOutsideTheImageIsNotProjected) {
  const HmdConfig config;
  Eigen::Vector2d pixel(-1, -1);
  const Eigen::Vector3d p_H_behind(-1.0, 0.0, 0.0), p_H_too_near(0.01, 0.0, 0.0);
  EXPECT_FALSE(project_to_pixel(config, Eye::kLeft, head_pose(), head_pose() * p_H_behind, pixel));
  EXPECT_FALSE(
      project_to_pixel(config, Eye::kLeft, head_pose(), head_pose() * p_H_too_near, pixel));
  // 60 deg to the right is past the left eye's 45 deg
  const Eigen::Vector3d p_H_outside(1.0, -std::tan(60 * kDeg), 0.0);
  EXPECT_FALSE(project_to_pixel(config, Eye::kLeft, head_pose(), head_pose() * p_H_outside, pixel));
  EXPECT_EQ(pixel, Eigen::Vector2d(-1, -1)) << "untouched when false";
}

TEST(Camera, OffAxisProjectionIsGlFrustum) {
  const EyeFov fov{-52 * kDeg, 45 * kDeg, 42 * kDeg, -48 * kDeg};
  const double n = 0.05, f = 20.0;
  const double l = n * std::tan(fov.left_rad), r = n * std::tan(fov.right_rad);
  const double b = n * std::tan(fov.down_rad), t = n * std::tan(fov.up_rad);
  Eigen::Matrix4d expected;  // glFrustum(l, r, b, t, n, f), OpenGL reference pages
  expected << 2 * n / (r - l), 0, (r + l) / (r - l), 0,  //
      0, 2 * n / (t - b), (t + b) / (t - b), 0,          //
      0, 0, -(f + n) / (f - n), -2 * f * n / (f - n),    //
      0, 0, -1, 0;
  const Eigen::Matrix4f P = off_axis_projection(fov, n, f);
  EXPECT_TRUE(P.cast<double>().isApprox(expected, 1e-6)) << P;
  EXPECT_NE(P(0, 2), 0.0f) << "asymmetric: skewed, not a centred (toed-in) frustum";
  // the frustum's corners and depth range land on the NDC cube's faces
  auto ndc = [&](const Eigen::Vector3d& p_gl) {
    const Eigen::Vector4d c = P.cast<double>() * p_gl.homogeneous();
    return Eigen::Vector3d(c.head<3>() / c.w());
  };
  EXPECT_TRUE(ndc({r, t, -n}).isApprox(Eigen::Vector3d(1, 1, -1), 1e-5));
  EXPECT_TRUE(ndc({l * f / n, b * f / n, -f}).isApprox(Eigen::Vector3d(-1, -1, 1), 1e-5));
}

TEST(Camera, ViewMatrixMapsHeadAxesToOpenGlEyeAxes) {
  const HmdConfig config;
  const Eigen::Isometry3d X_GHead = at(0.4, -0.2, 1.1) *
                                    Eigen::AngleAxisd(40 * kDeg, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-15 * kDeg, Eigen::Vector3d::UnitY());
  const Eigen::Isometry3d X_GE = eye_pose(config, Eye::kRight, X_GHead);
  const Eigen::Matrix4d V = view_matrix(X_GE).cast<double>();
  auto eye_space = [&](const Eigen::Vector3d& p_E) {
    return Eigen::Vector3d((V * (X_GE * p_E).homogeneous()).head<3>());
  };
  EXPECT_TRUE(eye_space({0, 0, 0}).isZero(1e-6));
  EXPECT_TRUE(eye_space({1, 0, 0}).isApprox(Eigen::Vector3d(0, 0, -1), 1e-6)) << "forward -> -z";
  EXPECT_TRUE(eye_space({0, 1, 0}).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-6)) << "left -> -x";
  EXPECT_TRUE(eye_space({0, 0, 1}).isApprox(Eigen::Vector3d(0, 1, 0), 1e-6)) << "up -> +y";
}

// The GL pipeline (P * V, viewport, top-down rows) and project_to_pixel agree.
TEST(Camera, MatricesAgreeWithProjectToPixel) {
  const HmdConfig config;
  const Eigen::Isometry3d X_GHead =
      at(0.1, 0.3, 1.25) * Eigen::AngleAxisd(-25 * kDeg, Eigen::Vector3d::UnitZ());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Eigen::Matrix4d PV =
        (off_axis_projection(config.eye_fov(eye), config.near_m, config.far_m) *
         view_matrix(eye_pose(config, eye, X_GHead)))
            .cast<double>();
    for (const Eigen::Vector3d& p_H : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.7, 0.3, -0.2),
                                       Eigen::Vector3d(2.5, -1.1, 0.9)}) {
      const Eigen::Vector3d p_G = X_GHead * p_H;
      const Eigen::Vector4d clip = PV * p_G.homogeneous();
      const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
      const Eigen::Vector2d expected((ndc.x() + 1) / 2 * 1280, (1 - ndc.y()) / 2 * 720);
      Eigen::Vector2d pixel;
      ASSERT_TRUE(project_to_pixel(config, eye, X_GHead, p_G, pixel));
      EXPECT_LT((pixel - expected).norm(), 1e-3)
          << pixel.transpose() << " vs " << expected.transpose();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// config

TEST(HmdConfig, DefaultIsValidAndMirrored) {
  const HmdConfig config;
  EXPECT_NO_THROW(config.validate());
  EXPECT_NEAR(config.fov[0].left_rad, -52 * kDeg, 1e-12);
  EXPECT_NEAR(config.fov[0].right_rad, 45 * kDeg, 1e-12);
  EXPECT_EQ(config.fov[0].left_rad, -config.fov[1].right_rad);
  EXPECT_EQ(config.fov[0].right_rad, -config.fov[1].left_rad);
  EXPECT_EQ(config.fov[0].up_rad, config.fov[1].up_rad);
}

TEST(HmdConfig, RejectsEachBadValue) {
  struct Case {
    const char* field;
    std::function<void(HmdConfig&)> spoil;
  };
  const std::vector<Case> cases{
      {"ipd_m", [](HmdConfig& c) { c.ipd_m = 0.0; }},
      {"ipd_m", [](HmdConfig& c) { c.ipd_m = -0.06; }},
      {"ipd_m", [](HmdConfig& c) { c.ipd_m = 0.11; }},
      {"ipd_m", [](HmdConfig& c) { c.ipd_m = std::nan(""); }},
      {"fov[left].left_rad", [](HmdConfig& c) { c.fov[0].left_rad = 0.1; }},
      {"fov[left].left_rad", [](HmdConfig& c) { c.fov[0].left_rad = -86 * kDeg; }},
      {"fov[left].right_rad", [](HmdConfig& c) { c.fov[0].right_rad = -0.1; }},
      {"fov[right].right_rad", [](HmdConfig& c) { c.fov[1].right_rad = 90 * kDeg; }},
      {"fov[right].up_rad", [](HmdConfig& c) { c.fov[1].up_rad = 0.0; }},
      {"fov[right].up_rad", [](HmdConfig& c) { c.fov[1].up_rad = 86 * kDeg; }},
      {"fov[left].down_rad", [](HmdConfig& c) { c.fov[0].down_rad = 0.2; }},
      {"fov[right].down_rad", [](HmdConfig& c) { c.fov[1].down_rad = -1.6; }},
      {"width_px", [](HmdConfig& c) { c.width_px = 0; }},
      {"width_px", [](HmdConfig& c) { c.width_px = 8193; }},
      {"height_px", [](HmdConfig& c) { c.height_px = -720; }},
      {"height_px", [](HmdConfig& c) { c.height_px = 10000; }},
      {"near_m", [](HmdConfig& c) { c.near_m = 0.0; }},
      {"near_m", [](HmdConfig& c) { c.near_m = -0.1; }},
      {"far_m", [](HmdConfig& c) { c.far_m = c.near_m; }},
      {"far_m", [](HmdConfig& c) { c.far_m = 0.01; }},
      {"far_m", [](HmdConfig& c) { c.far_m = INFINITY; }},
      {"outside.ground_depth_m", [](HmdConfig& c) { c.outside = OutsideView{0.0}; }},
      {"outside.ground_depth_m", [](HmdConfig& c) { c.outside = OutsideView{std::nan("")}; }},
      {"outside.ground_depth_m", [](HmdConfig& c) { c.outside = OutsideView{25000.0}; }},
  };
  for (const Case& bad : cases) {
    HmdConfig config;
    bad.spoil(config);
    try {
      config.validate();
      ADD_FAILURE() << "accepted a bad " << bad.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad.field), std::string::npos)
          << "message names " << bad.field << ": " << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// CPU side of the draw: packing and unit meshes

TEST(InstancePacking, CapsuleIsACylinderAndTwoRoundCapsFacingOut) {
  const Eigen::Isometry3d X_GO =
      at(1.0, 0.5, 0.2) * Eigen::AngleAxisd(90 * kDeg, Eigen::Vector3d::UnitX());
  const std::vector<Instance> instances{
      make(Primitive::kBox, at(0, 0, 0), {0.1, 0.2, 0.3}, kRed),
      make(Primitive::kCapsule, X_GO, {0.02, 0.10, 0.0}, kYellow, true),
      make(Primitive::kSphere, at(0, 0, 0), {0.05, 0.0, 0.0}, kGreen)};
  PackedInstances packed;
  pack_instances(instances, packed);
  ASSERT_EQ(packed.records.size(), 5u);
  EXPECT_EQ(packed.range(UnitMesh::kBox).count, 1);
  EXPECT_EQ(packed.range(UnitMesh::kSphere).count, 1);
  EXPECT_EQ(packed.range(UnitMesh::kCylinder).count, 1);
  EXPECT_EQ(packed.range(UnitMesh::kCap).count, 2);

  const InstanceRecord& cylinder = packed.records[packed.range(UnitMesh::kCylinder).first];
  EXPECT_EQ(cylinder.scale_highlight, (std::array<float, 4>{0.02f, 0.02f, 0.10f, 1.0f}));
  EXPECT_EQ(cylinder.rgba, kYellow);
  std::vector<Eigen::Vector3d> cap_centres;
  for (int i = 0; i < 2; ++i) {
    const InstanceRecord& s = packed.records[packed.range(UnitMesh::kCap).first + i];
    EXPECT_EQ(s.rgba, kYellow);
    EXPECT_EQ(s.scale_highlight, (std::array<float, 4>{0.02f, 0.02f, 0.02f, 1.0f}));
    const Eigen::Matrix4f X = Eigen::Map<const Eigen::Matrix4f>(s.X_GO.data());
    const Eigen::Vector3d centre = X.col(3).head<3>().cast<double>();
    cap_centres.push_back(centre);
    // each hemisphere's dome (its +z) points away from the capsule's middle
    const Eigen::Vector3d dome = X.col(2).head<3>().cast<double>();
    EXPECT_GT(dome.dot(centre - Eigen::Vector3d(1.0, 0.5, 0.2)), 0.0) << "cap " << i;
  }
  // the capsule's z axis is world -y after the 90 deg roll
  for (const Eigen::Vector3d& c : cap_centres) {
    EXPECT_NEAR(std::abs(c.y() - 0.5), 0.05, 1e-6);
    EXPECT_NEAR(c.x(), 1.0, 1e-6);
    EXPECT_NEAR(c.z(), 0.2, 1e-6);
  }
}

// A tapered capsule (a finger's segment) is a frustum from radius r0 at -z to taper * r0 at +z,
// its mean the instance's radius, closed by caps of those two radii.
TEST(InstancePacking, ATaperedCapsuleIsAFrustumBetweenCapsOfItsEndRadii) {
  const std::vector<Instance> instances{
      make(Primitive::kTaperedCapsule, at(1.0, 0.5, 0.2), {0.009, 0.04, 0.0}, kYellow),
      make(Primitive::kRoundedBox, at(0, 0, 0), {0.09, 0.08, 0.025}, kRed)};
  PackedInstances packed;
  pack_instances(instances, packed);
  ASSERT_EQ(packed.records.size(), 4u);
  EXPECT_EQ(packed.range(UnitMesh::kFrustum).count, 1);
  EXPECT_EQ(packed.range(UnitMesh::kCap).count, 2);
  EXPECT_EQ(packed.range(UnitMesh::kRoundedBox).count, 1);
  EXPECT_EQ(packed.range(UnitMesh::kCylinder).count, 0);
  const double r0 = 2 * 0.009 / (1 + kFrustumTaper), r1 = kFrustumTaper * r0;
  EXPECT_NEAR(0.5 * (r0 + r1), 0.009, 1e-9);
  const InstanceRecord& frustum = packed.records[packed.range(UnitMesh::kFrustum).first];
  EXPECT_NEAR(frustum.scale_highlight[0], r0, 1e-7);
  EXPECT_NEAR(frustum.scale_highlight[2], 0.04, 1e-7);
  for (int i = 0; i < 2; ++i) {
    const InstanceRecord& cap = packed.records[packed.range(UnitMesh::kCap).first + i];
    const double z = Eigen::Map<const Eigen::Matrix4f>(cap.X_GO.data())(2, 3) - 0.2;
    EXPECT_NEAR(cap.scale_highlight[0], z > 0 ? r1 : r0, 1e-7) << "cap at z " << z;
    EXPECT_NEAR(std::abs(z), 0.02, 1e-6);
  }
  const InstanceRecord& palm = packed.records[packed.range(UnitMesh::kRoundedBox).first];
  EXPECT_EQ(palm.scale_highlight, (std::array<float, 4>{0.09f, 0.08f, 0.025f, 0.0f}));
}

TEST(InstancePacking, ReusesItsBuffer) {
  std::vector<Instance> instances(50,
                                  make(Primitive::kCapsule, at(0, 0, 0), {0.01, 0.05, 0}, kRed));
  PackedInstances packed;
  pack_instances(instances, packed);
  const InstanceRecord* data = packed.records.data();
  instances.resize(20);
  pack_instances(instances, packed);
  EXPECT_EQ(packed.records.size(), 60u);
  EXPECT_EQ(packed.records.data(), data);
}

// Closed, outward-wound meshes: backface culling relies on it.
void expect_outward(const MeshData& mesh, const char* name) {
  ASSERT_EQ(mesh.indices.size() % 3, 0u) << name;
  for (const Vertex& v : mesh.vertices) {
    EXPECT_NEAR(Eigen::Vector3f(v.normal.data()).norm(), 1.0f, 1e-5f) << name;
  }
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Eigen::Vector3f a(mesh.vertices[mesh.indices[i]].position.data());
    const Eigen::Vector3f b(mesh.vertices[mesh.indices[i + 1]].position.data());
    const Eigen::Vector3f c(mesh.vertices[mesh.indices[i + 2]].position.data());
    const Eigen::Vector3f n(mesh.vertices[mesh.indices[i]].normal.data());
    const Eigen::Vector3f winding = (b - a).cross(c - a);
    ASSERT_GT(winding.norm(), 1e-7f) << name << " degenerate triangle " << i / 3;
    EXPECT_GT(winding.dot(n), 0.0f) << name << " triangle " << i / 3 << " winds inwards";
  }
}

TEST(Meshes, UnitMeshesAreOutwardWoundAndUnitSized) {
  expect_outward(unit_box(), "box");
  expect_outward(unit_sphere(), "sphere");
  expect_outward(unit_cylinder(), "cylinder");
  expect_outward(unit_hemisphere(), "hemisphere");
  expect_outward(unit_frustum(), "frustum");
  expect_outward(unit_rounded_box(), "rounded box");
  EXPECT_EQ(unit_box().indices.size(), 36u);
  for (const Vertex& v : unit_frustum().vertices) {
    const float radius = std::hypot(v.position[0], v.position[1]);
    EXPECT_NEAR(radius, v.position[2] < 0 ? 1.0f : kFrustumTaper, 1e-6f);
    EXPECT_NEAR(Eigen::Vector3f(v.normal.data()).norm(), 1.0f, 1e-6f);
    EXPECT_GT(v.normal[2], 0.0f) << "the side faces up the taper";
  }
  // on |x|^4 + |y|^4 + |z|^4 = 0.5^4: the faces' centres at 0.5, the corners cut to 0.5 / 3^0.25
  float widest = 0.0f;
  for (const Vertex& v : unit_rounded_box().vertices) {
    const Eigen::Vector3f p(v.position.data());
    EXPECT_NEAR(p.array().abs().pow(4.0f).sum(), std::pow(0.5f, 4.0f), 1e-6f);
    widest = std::max(widest, p.cwiseAbs().maxCoeff());
    EXPECT_GT(Eigen::Vector3f(v.normal.data()).dot(p), 0.0f) << "normals point out";
  }
  EXPECT_NEAR(widest, 0.5f, 1e-5f);
  for (const Vertex& v : unit_hemisphere().vertices) {
    EXPECT_NEAR(Eigen::Vector3f(v.position.data()).norm(), 1.0f, 1e-5f);
    EXPECT_GE(v.position[2], -1e-6f) << "the +z half only";
  }
  for (const Vertex& v : unit_sphere().vertices) {
    EXPECT_NEAR(Eigen::Vector3f(v.position.data()).norm(), 1.0f, 1e-5f);
  }
  for (const Vertex& v : unit_cylinder().vertices) {
    EXPECT_LE(std::abs(v.position[2]), 0.5f);
    EXPECT_LE(std::hypot(v.position[0], v.position[1]), 1.0f + 1e-6f);
  }
}

// ---------------------------------------------------------------------------------------------
// rendering

struct Rgb {
  int r, g, b;
};

Rgb pixel_at(const StereoRenderer& renderer, Eye eye, int column, int row) {
  const size_t width = static_cast<size_t>(renderer.width_px());
  const uint8_t* p = renderer.pixels() + (static_cast<size_t>(row) * 2 * width +
                                          eye_index(eye) * width + static_cast<size_t>(column)) *
                                             4;
  return {p[0], p[1], p[2]};
}

Rgb pixel_at(const StereoRenderer& renderer, Eye eye, const Eigen::Vector2d& pixel) {
  return pixel_at(renderer, eye, static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
}

std::ostream& operator<<(std::ostream& os, const Rgb& c) {
  return os << "(" << c.r << ", " << c.g << ", " << c.b << ")";
}

bool is_background(const Rgb& c) {
  auto near = [](int value, float expected) {
    return std::abs(value - static_cast<int>(std::lround(expected * 255))) <= 1;
  };
  return near(c.r, kBackgroundRgb[0]) && near(c.g, kBackgroundRgb[1]) &&
         near(c.b, kBackgroundRgb[2]);
}

// lit, so darker than the base colour, but that channel clearly dominates
bool is_red(const Rgb& c) {
  return c.r > 100 && c.r > 3 * c.g && c.r > 3 * c.b;
}
bool is_green(const Rgb& c) {
  return c.g > 100 && c.g > 3 * c.r && c.g > 3 * c.b;
}
bool is_blue(const Rgb& c) {
  return c.b > 100 && c.b > 3 * c.r && c.b > 3 * c.g;
}
bool is_yellow(const Rgb& c) {
  return c.r > 100 && c.g > 100 && c.r > 3 * c.b && c.g > 3 * c.b;
}

Eigen::Vector2d projected(const HmdConfig& config, Eye eye, const Eigen::Vector3d& p_G) {
  Eigen::Vector2d pixel(-1, -1);
  EXPECT_TRUE(project_to_pixel(config, eye, head_pose(), p_G, pixel)) << p_G.transpose();
  return pixel;
}

// Columns [first, last] of the run of red pixels through `pixel` on its row.
std::pair<int, int> red_run(const StereoRenderer& renderer, Eye eye, const Eigen::Vector2d& pixel) {
  const int row = static_cast<int>(pixel.y());
  int first = static_cast<int>(pixel.x()), last = first;
  while (first > 0 && is_red(pixel_at(renderer, eye, first - 1, row)))
    --first;
  while (last + 1 < renderer.width_px() && is_red(pixel_at(renderer, eye, last + 1, row)))
    ++last;
  return {first, last};
}

class RenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { renderer_ = std::make_unique<StereoRenderer>(HmdConfig{}); }
  static void TearDownTestSuite() { renderer_.reset(); }

  static StereoRenderer& renderer() { return *renderer_; }
  static const HmdConfig& config() { return renderer_->config(); }

  static std::unique_ptr<StereoRenderer> renderer_;
};
std::unique_ptr<StereoRenderer> RenderTest::renderer_;

TEST_F(RenderTest, ContextIsOsMesaCoreProfile) {
  EXPECT_EQ(renderer().gl_version().rfind("4.5 (Core Profile) Mesa", 0), 0u)
      << renderer().gl_version();
  EXPECT_FALSE(renderer().gl_renderer().empty());
  EXPECT_EQ(renderer().width_px(), 1280);
  EXPECT_EQ(renderer().height_px(), 720);
  std::printf("[ renderer ] %s, %s, LP_NUM_THREADS=%s\n", renderer().gl_renderer().c_str(),
              renderer().gl_version().c_str(), std::getenv("LP_NUM_THREADS"));
}

TEST_F(RenderTest, EmptySceneIsBackgroundEverywhere) {
  renderer().render({}, head_pose());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    constexpr std::array<std::pair<int, int>, 5> kCorners{
        {{0, 0}, {1279, 0}, {0, 719}, {1279, 719}, {640, 360}}};
    for (const auto& [c, r] : kCorners) {
      EXPECT_TRUE(is_background(pixel_at(renderer(), eye, c, r)))
          << pixel_at(renderer(), eye, c, r);
    }
  }
  EXPECT_EQ(renderer().last_draw_calls(), 0);
}

// A model's mesh (the ramp of tests/data/models, read through assimp as the image generator
// reads an object's model) shows where its back face projects, tinted by its material and the
// instance's colour; fixed, it is drawn into the cached background once.
TEST_F(RenderTest, AModelMeshShowsInTheCachedLayerWithItsMaterial) {
  const std::string file = std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models/ramp.obj";
  const model::TriangleMesh ramp = model::load_model_mesh({file, "ramp"});
  auto data = std::make_shared<const MeshData>(model_mesh_data(ramp));
  ASSERT_EQ(data->vertices.size(), 3 * ramp.triangles.size()) << "no normals in the file: flat faces";
  EXPECT_NEAR(data->vertices[0].rgb[2], 0.6f, 1e-3f) << "the material's colour per vertex";
  Instance instance = make(Primitive::kMesh, at(1.5, 0.0, 1.0), Eigen::Vector3d::Ones(),
                           {1.0f, 1.0f, 1.0f, 1.0f});
  instance.mesh = data;
  instance.fixed = true;
  // its back face (x = -0.4, facing the viewer) from 0 to 0.29 m up
  const Eigen::Vector3d on_back_face(1.1, 0.0, 1.1);
  const uint64_t redraws = renderer().background_redraws();
  renderer().render({instance}, head_pose());
  EXPECT_EQ(renderer().background_redraws(), redraws + 1);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb c = pixel_at(renderer(), eye, projected(config(), eye, on_back_face));
    EXPECT_FALSE(is_background(c)) << c;
    EXPECT_GT(c.b, c.r) << "the material's blue-grey: " << c;
    EXPECT_TRUE(is_background(pixel_at(renderer(), eye, projected(config(), eye, {1.5, 0.0, 1.45}))))
        << "above the ramp's top";
  }
  renderer().render({instance}, head_pose());
  EXPECT_EQ(renderer().background_redraws(), redraws + 1) << "the same model, the cached layer";
  instance.rgba = kRed;
  renderer().render({instance}, head_pose());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb c = pixel_at(renderer(), eye, projected(config(), eye, on_back_face));
    EXPECT_TRUE(c.r > 60 && c.g < 20 && c.b < 20) << "the instance's colour times the material's: " << c;
  }
}

// The placard's quadrants (tests/data/models, scripts/make_test_models.py) as the eye sees the
// plate at x = 0.8 (looking along +x, +y is to the left): where each centre is on the plate and
// the colour it must show, lit.
struct PlacardQuadrant {
  double y_m, z_m;
  const char* name;
  bool (*is)(const Rgb&);
};
const PlacardQuadrant kPlacardQuadrants[] = {
    {0.05, 0.025, "top left red", [](const Rgb& c) { return c.r > 120 && c.g < 40 && c.b < 40; }},
    {-0.05, 0.025, "top right green", [](const Rgb& c) { return c.g > 100 && c.r < 40 && c.b < 40; }},
    {0.05, -0.025, "bottom left blue", [](const Rgb& c) { return c.b > 120 && c.r < 40 && c.g < 40; }},
    {-0.05, -0.025, "bottom right yellow", [](const Rgb& c) { return c.r > 120 && c.g > 120 && c.b < 40; }},
};

// A model's texture (the placard of tests/data/models: red, green, blue and yellow quadrants)
// shows on its face the right way up and unmirrored, in each format's file: each quadrant's
// centre, projected, is its colour, lit; the placard drawn as a moving instance too.
TEST_F(RenderTest, AModelTextureShowsTheRightWayUpInEachFormat) {
  const std::string dir = std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models/";
  for (const char* file : {"placard.gltf", "placard_embedded.gltf", "placard.obj", "placard.ac"}) {
    SCOPED_TRACE(file);
    const model::TriangleMesh placard =
        model::load_model_mesh({dir + file, "placard", 1.0, model::UpAxis::kY, true});
    auto data = std::make_shared<const MeshData>(model_mesh_data(placard));
    ASSERT_EQ(data->groups.size(), 1u);
    ASSERT_EQ(data->textures.size(), 1u);
    for (const bool fixed : {true, false}) {
      Instance instance = make(Primitive::kMesh, at(0.8, 0.0, kHeadHeightM), Eigen::Vector3d::Ones(),
                               {1.0f, 1.0f, 1.0f, 1.0f});
      instance.mesh = data;
      instance.fixed = fixed;
      renderer().render({instance}, head_pose());
      EXPECT_EQ(renderer().gl_error_count(), 0u);
      for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
        for (const PlacardQuadrant& q : kPlacardQuadrants) {
          const Rgb c = pixel_at(renderer(), eye, projected(config(), eye, {0.8, q.y_m, kHeadHeightM + q.z_m}));
          EXPECT_TRUE(q.is(c)) << q.name << (fixed ? " (cached layer) " : " (instance) ") << c;
        }
      }
    }
  }
}

// The placard's coordinates spread to [-1, 2] (u' = 3u - 1), drawn with each wrap along u: two
// points of its top half tell the three apart. At u = 0.75 (u' = 1.25) repeat reads the image's
// left (red), clamp and mirror its right (green); at u = 0.9 (u' = 1.7) repeat and clamp read
// its right (green), mirror its left (red).
TEST_F(RenderTest, AModelTextureWrapsAsItsSamplerSays) {
  const std::string dir = std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models/";
  model::TriangleMesh placard =
      model::load_model_mesh({dir + "placard.gltf", "placard", 1.0, model::UpAxis::kY, true});
  ASSERT_EQ(placard.textures.size(), 1u);
  for (Eigen::Vector2f& uv : placard.uv) uv.x() = 3.0f * uv.x() - 1.0f;
  const auto red = [](const Rgb& c) { return c.r > 120 && c.g < 40 && c.b < 40; };
  const auto green = [](const Rgb& c) { return c.g > 100 && c.r < 40 && c.b < 40; };
  struct Case {
    model::TextureWrap wrap;
    const char* name;
    bool at_075_red, at_090_red;
  };
  for (const Case& k : {Case{model::TextureWrap::kRepeat, "repeat", true, false},
                        Case{model::TextureWrap::kClampToEdge, "clamp", false, false},
                        Case{model::TextureWrap::kMirroredRepeat, "mirror", false, true}}) {
    SCOPED_TRACE(k.name);
    placard.textures[0].sampler.wrap_u = k.wrap;
    auto data = std::make_shared<const MeshData>(model_mesh_data(placard));
    Instance instance = make(Primitive::kMesh, at(0.8, 0.0, kHeadHeightM), Eigen::Vector3d::Ones(),
                             {1.0f, 1.0f, 1.0f, 1.0f});
    instance.mesh = data;
    instance.fixed = false;
    renderer().render({instance}, head_pose());
    EXPECT_EQ(renderer().gl_error_count(), 0u);
    // u runs from the plate's left edge (y = +0.1) to its right (y = -0.1); z = +0.01 is v = 0.6
    for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
      const Rgb at_075 = pixel_at(renderer(), eye, projected(config(), eye, {0.8, -0.05, kHeadHeightM + 0.01}));
      const Rgb at_090 = pixel_at(renderer(), eye, projected(config(), eye, {0.8, -0.08, kHeadHeightM + 0.01}));
      EXPECT_TRUE(k.at_075_red ? red(at_075) : green(at_075)) << "u = 0.75: " << at_075;
      EXPECT_TRUE(k.at_090_red ? red(at_090) : green(at_090)) << "u = 0.9: " << at_090;
    }
  }
}

// A model with an untextured part before a textured one: two draw groups, the textured one
// starting past the first's indices. Each shows what it should: the plain plate its white
// material, the placard its quadrants.
TEST_F(RenderTest, AModelsUntexturedAndTexturedPartsDrawAsTwoGroups) {
  const std::string dir = std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models/";
  const model::TriangleMesh placard =
      model::load_model_mesh({dir + "placard.gltf", "placard", 1.0, model::UpAxis::kY, true});
  model::TriangleMesh both = placard;  // the plain plate first, 0.25 m to the pilot's right
  both.vertices_m.clear();
  both.triangles.clear();
  both.triangle_texture.clear();
  both.uv.clear();
  both.colors_rgba.clear();
  both.normals.clear();
  for (const int32_t texture : {-1, 0}) {
    const auto base = static_cast<uint32_t>(both.vertices_m.size());
    const Eigen::Vector3d shift(0.0, texture < 0 ? -0.25 : 0.0, 0.0);
    for (std::size_t v = 0; v < placard.vertices_m.size(); ++v) {
      both.vertices_m.push_back(placard.vertices_m[v] + shift);
      both.uv.push_back(placard.uv[v]);
      both.colors_rgba.push_back(placard.colors_rgba[v]);
    }
    for (const auto& t : placard.triangles) {
      both.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      both.triangle_texture.push_back(texture);
    }
  }
  model::check_mesh(both);
  auto data = std::make_shared<const MeshData>(model_mesh_data(both));
  ASSERT_EQ(data->groups.size(), 2u);
  EXPECT_EQ(data->groups[1].first_index, 6u) << "the textured group after the plain one's 6 indices";
  Instance instance = make(Primitive::kMesh, at(0.8, 0.0, kHeadHeightM), Eigen::Vector3d::Ones(),
                           {1.0f, 1.0f, 1.0f, 1.0f});
  instance.mesh = data;
  renderer().render({instance}, head_pose());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb plain = pixel_at(renderer(), eye, projected(config(), eye, {0.8, -0.25, kHeadHeightM}));
    EXPECT_TRUE(plain.r > 80 && std::abs(plain.r - plain.g) < 10 && std::abs(plain.r - plain.b) < 10)
        << "the plain plate, white lit: " << plain;
    for (const PlacardQuadrant& q : kPlacardQuadrants) {
      const Rgb c = pixel_at(renderer(), eye, projected(config(), eye, {0.8, q.y_m, kHeadHeightM + q.z_m}));
      EXPECT_TRUE(q.is(c)) << "the placard's " << q.name << ": " << c;
    }
  }
}

// A red 0.1 m cube 1 m ahead at head height shows, lit, where project_to_pixel says, in both
// eyes, against the background elsewhere.
TEST_F(RenderTest, RedBoxAppearsAtItsProjectionInBothEyes) {
  const Eigen::Vector3d p_G(1.0, 0.0, kHeadHeightM);
  renderer().render({make(Primitive::kBox, at(1.0, 0.0, kHeadHeightM), {0.1, 0.1, 0.1}, kRed)},
                    head_pose());
  EXPECT_EQ(renderer().last_draw_calls(), 2) << "one box draw per eye";
  EXPECT_EQ(renderer().gl_error_count(), 0u);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb centre = pixel_at(renderer(), eye, projected(config(), eye, p_G));
    EXPECT_TRUE(is_red(centre)) << centre;
    EXPECT_LT(centre.r, 250) << "lit, not flat";
    EXPECT_TRUE(is_background(pixel_at(renderer(), eye, 100, 100)));
    EXPECT_TRUE(is_background(pixel_at(renderer(), eye, 1200, 650)));
  }
}

// The red run through the box's centre row spans exactly the columns of its outermost corners
// (vertical edges stay vertical: the head does not pitch or roll).
void expect_run_matches_corners(const StereoRenderer& renderer, Eye eye, double x_m,
                                std::pair<int, int> run) {
  double min_column = 1e9, max_column = -1e9;
  for (const double dx : {-0.05, 0.05}) {
    for (const double dy : {-0.05, 0.05}) {
      const Eigen::Vector2d c =
          projected(renderer.config(), eye, Eigen::Vector3d(x_m + dx, dy, kHeadHeightM + 0.04));
      min_column = std::min(min_column, c.x());
      max_column = std::max(max_column, c.x());
    }
  }
  EXPECT_NEAR(run.first, min_column, 1.5) << "x " << x_m;
  EXPECT_NEAR(run.second + 1, max_column, 1.5) << "x " << x_m;
}

// Stereo geometry: a point ahead appears further right to the left eye; nearer, more so.
TEST_F(RenderTest, DisparityGrowsAsTheBoxComesCloser) {
  std::array<double, 2> projected_disparity{}, rendered_disparity{};
  const std::array<double, 2> distances_m{1.0, 0.5};
  for (int i = 0; i < 2; ++i) {
    const double x_m = distances_m[i];
    const Eigen::Vector3d p_G(x_m, 0.0, kHeadHeightM);
    renderer().render({make(Primitive::kBox, at(x_m, 0.0, kHeadHeightM), {0.1, 0.1, 0.1}, kRed)},
                      head_pose());
    const Eigen::Vector2d left = projected(config(), Eye::kLeft, p_G);
    const Eigen::Vector2d right = projected(config(), Eye::kRight, p_G);
    EXPECT_GT(left.x(), right.x()) << "x " << x_m;
    EXPECT_NEAR(left.y(), right.y(), 1e-9) << "no vertical disparity";
    const auto run_left = red_run(renderer(), Eye::kLeft, left);
    const auto run_right = red_run(renderer(), Eye::kRight, right);
    expect_run_matches_corners(renderer(), Eye::kLeft, x_m, run_left);
    expect_run_matches_corners(renderer(), Eye::kRight, x_m, run_right);
    const double mid_left = 0.5 * (run_left.first + run_left.second + 1);
    const double mid_right = 0.5 * (run_right.first + run_right.second + 1);
    EXPECT_GT(mid_left, mid_right) << "x " << x_m;
    projected_disparity[i] = left.x() - right.x();
    rendered_disparity[i] = mid_left - mid_right;
    std::printf("[ disparity ] box at %.1f m: projected %.1f px, rendered %.1f px\n", x_m,
                projected_disparity[i], rendered_disparity[i]);
  }
  EXPECT_GT(projected_disparity[1], projected_disparity[0]);
  EXPECT_GT(rendered_disparity[1], rendered_disparity[0]);
  // closed form: the ipd over the distance, in pixels per unit tangent, on top of the FOVs'
  // constant offset (their axes land at different columns)
  const EyeFov& fov = config().eye_fov(Eye::kLeft);
  const double px_per_tan = 1280 / (std::tan(fov.right_rad) - std::tan(fov.left_rad));
  EXPECT_NEAR(projected_disparity[1] - projected_disparity[0], 0.063 * (2.0 - 1.0) * px_per_tan,
              1e-6);
}

// Sphere, cylinder and capsule each show at their projected centres; the capsule's round caps
// reach past its length, where an equally long cylinder ends.
TEST_F(RenderTest, EachPrimitiveRenders) {
  const Eigen::Vector3d sphere_G(1.0, 0.25, kHeadHeightM), cylinder_G(1.0, 0.0, kHeadHeightM);
  const Eigen::Vector3d capsule_G(1.0, -0.25, kHeadHeightM);
  const double r_m = 0.04, length_m = 0.15;
  const std::vector<Instance> scene{
      make(Primitive::kSphere, at(1.0, 0.25, kHeadHeightM), {0.05, 0, 0}, kGreen),
      make(Primitive::kCylinder, at(1.0, 0.0, kHeadHeightM), {r_m, length_m, 0}, kBlue),
      make(Primitive::kCapsule, at(1.0, -0.25, kHeadHeightM), {r_m, length_m, 0}, kYellow)};
  renderer().render(scene, head_pose());
  EXPECT_EQ(renderer().last_draw_calls(), 6) << "sphere, cylinder and cap meshes, two eyes";
  const Eigen::Vector3d past_end_G(0.0, 0.0, 0.5 * length_m + 0.5 * r_m);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb sphere = pixel_at(renderer(), eye, projected(config(), eye, sphere_G));
    const Rgb cylinder = pixel_at(renderer(), eye, projected(config(), eye, cylinder_G));
    const Rgb capsule = pixel_at(renderer(), eye, projected(config(), eye, capsule_G));
    EXPECT_TRUE(is_green(sphere)) << sphere;
    EXPECT_TRUE(is_blue(cylinder)) << cylinder;
    EXPECT_TRUE(is_yellow(capsule)) << capsule;
    const Rgb cap = pixel_at(renderer(), eye, projected(config(), eye, capsule_G + past_end_G));
    const Rgb cylinder_end =
        pixel_at(renderer(), eye, projected(config(), eye, cylinder_G + past_end_G));
    EXPECT_TRUE(is_yellow(cap)) << cap;
    EXPECT_TRUE(is_background(cylinder_end)) << cylinder_end;
  }
}

// A finger's segment and a palm: the tapered capsule is wider at its -z end than at its +z end
// (measured across the screen at equal distances from its middle), the rounded box fills its
// centre but not the corners of its extents.
TEST_F(RenderTest, ATaperedCapsuleNarrowsAndARoundedBoxHasRoundCorners) {
  const Eigen::Isometry3d X_G_segment = at(1.0, 0.15, kHeadHeightM) *
                                        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX());  // z -> -y
  const Eigen::Vector3d p_G_box(1.0, -0.15, kHeadHeightM);
  renderer().render({make(Primitive::kTaperedCapsule, X_G_segment, {0.03, 0.16, 0}, kYellow),
                     make(Primitive::kRoundedBox, at(p_G_box.x(), p_G_box.y(), p_G_box.z()),
                          {0.02, 0.12, 0.12}, kBlue)},
                   head_pose());
  EXPECT_EQ(renderer().gl_error_count(), 0u);
  const Eye eye = Eye::kLeft;
  // the segment runs along -y: its wide (-z) end at y 0.15 + 0.06, its narrow end at 0.15 - 0.06
  auto height_px = [&](double y_m) {
    const Eigen::Vector2d c = projected(config(), eye, {1.0, y_m, kHeadHeightM});
    int top = static_cast<int>(c.y()), bottom = top;
    const int column = static_cast<int>(c.x());
    while (top > 0 && !is_background(pixel_at(renderer(), eye, column, top - 1))) --top;
    while (bottom + 1 < renderer().height_px() &&
           !is_background(pixel_at(renderer(), eye, column, bottom + 1)))
      ++bottom;
    return bottom - top + 1;
  };
  const int wide = height_px(0.15 + 0.06), narrow = height_px(0.15 - 0.06);
  // diameters there 6.5 and 5.5 cm, 1 m off: about 23 and 20 px
  EXPECT_GE(wide, narrow + 3) << wide << " px vs " << narrow << " px";
  EXPECT_TRUE(is_blue(pixel_at(renderer(), eye, projected(config(), eye, p_G_box))));
  // a box's corner (at 0.058 of its 0.06 half extents) is empty: rounded off
  EXPECT_TRUE(is_background(pixel_at(renderer(), eye, projected(config(), eye, p_G_box + Eigen::Vector3d(-0.01, 0.058, 0.058)))));
  EXPECT_TRUE(is_blue(pixel_at(renderer(), eye, projected(config(), eye, p_G_box + Eigen::Vector3d(-0.01, 0.058, 0.0)))));
}

// The frame's cost in triangles, per eye and layer: each instance's unit mesh (a capsule is a
// cylinder and two caps), a model's own triangles.
TEST_F(RenderTest, TheFrameCountsTheTrianglesOfEachLayer) {
  auto triangles = [](const MeshData& mesh) { return static_cast<uint64_t>(mesh.indices.size() / 3); };
  Instance panel = make(Primitive::kBox, at(1.2, 0.0, kHeadHeightM - 0.3), {0.1, 1.0, 0.4}, kBlue);
  panel.fixed = true;
  Instance pane = make(Primitive::kBox, at(1.1, 0.0, kHeadHeightM + 0.2), {0.01, 1.0, 0.4}, {1, 1, 1, 0.3f});
  pane.fixed = true;
  renderer().render({panel, pane, make(Primitive::kSphere, at(1.0, 0.1, kHeadHeightM), {0.05, 0, 0}, kRed),
                     make(Primitive::kCapsule, at(1.0, -0.1, kHeadHeightM), {0.02, 0.1, 0}, kGreen)},
                    head_pose());
  const auto& cost = renderer().last_cost();
  EXPECT_EQ(cost.fixed_triangles, 2 * triangles(unit_box()));
  EXPECT_EQ(cost.moving_triangles,
            triangles(unit_sphere()) + triangles(unit_cylinder()) + 2 * triangles(unit_hemisphere()));
}

// A capsule lying along y: its caps follow its axis and stay round (no stretched spheres).
TEST_F(RenderTest, CapsuleCapsFollowItsAxis) {
  const double r_m = 0.03, length_m = 0.3;
  const Eigen::Isometry3d X_GO =
      at(1.0, 0.0, kHeadHeightM) * Eigen::AngleAxisd(90 * kDeg, Eigen::Vector3d::UnitX());
  renderer().render({make(Primitive::kCapsule, X_GO, {r_m, length_m, 0}, kYellow)}, head_pose());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    for (const double side : {-1.0, 1.0}) {
      const Eigen::Vector3d inside_cap(1.0 - 0.5 * r_m, side * (0.5 * length_m + 0.7 * r_m),
                                       kHeadHeightM);
      const Eigen::Vector3d past_cap(1.0, side * (0.5 * length_m + 1.3 * r_m), kHeadHeightM);
      const Eigen::Vector3d above_cap(1.0, side * 0.5 * length_m, kHeadHeightM + 1.3 * r_m);
      EXPECT_TRUE(is_yellow(pixel_at(renderer(), eye, projected(config(), eye, inside_cap))));
      EXPECT_TRUE(is_background(pixel_at(renderer(), eye, projected(config(), eye, past_cap))));
      EXPECT_TRUE(is_background(pixel_at(renderer(), eye, projected(config(), eye, above_cap))));
    }
  }
}

TEST_F(RenderTest, HighlightedInstancesAreBrighter) {
  const Eigen::Vector3d p_G(1.0, 0.0, kHeadHeightM);
  const Instance box =
      make(Primitive::kBox, at(1.0, 0.0, kHeadHeightM), {0.1, 0.1, 0.1}, {0.6f, 0.3f, 0.1f, 1.0f});
  Instance highlighted = box;
  highlighted.highlight = true;
  renderer().render({box}, head_pose());
  const Rgb plain = pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, p_G));
  renderer().render({highlighted}, head_pose());
  const Rgb bright = pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, p_G));
  EXPECT_GT(bright.r + bright.g + bright.b, (plain.r + plain.g + plain.b) * 5 / 4)
      << plain << " -> " << bright;
}

// Nearer objects hide farther ones.
TEST_F(RenderTest, DepthTestHidesTheFartherBox) {
  const Eigen::Vector3d p_G(1.0, 0.0, kHeadHeightM);
  // the far (blue) one is drawn after the near (red) one: same mesh, later instance
  renderer().render({make(Primitive::kBox, at(0.8, 0.0, kHeadHeightM), {0.1, 0.1, 0.1}, kRed),
                     make(Primitive::kBox, at(1.2, 0.0, kHeadHeightM), {0.3, 0.3, 0.3}, kBlue)},
                    head_pose());
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    EXPECT_TRUE(is_red(pixel_at(renderer(), eye, projected(config(), eye, p_G))));
  }
}

// 200 instances of all four kinds in one render(), each at its projection in both eyes, with at
// most one draw call per unit mesh per eye.
TEST_F(RenderTest, TwoHundredInstancesInOneCall) {
  struct Kind {
    Primitive primitive;
    Eigen::Vector3d size_m;
    std::array<float, 4> rgba;
    bool (*looks_right)(const Rgb&);
  };
  const std::array<Kind, 4> kinds{Kind{Primitive::kBox, {0.05, 0.05, 0.05}, kRed, is_red},
                                  Kind{Primitive::kSphere, {0.03, 0, 0}, kGreen, is_green},
                                  Kind{Primitive::kCylinder, {0.025, 0.05, 0}, kBlue, is_blue},
                                  Kind{Primitive::kCapsule, {0.02, 0.03, 0}, kYellow, is_yellow}};
  std::vector<Instance> scene;
  std::vector<int> kind_of;
  for (int row = 0; row < 10; ++row) {
    for (int column = 0; column < 20; ++column) {
      const int k = (row + column) % 4;
      const Eigen::Vector3d p_G(1.5, 0.95 - 0.1 * column, kHeadHeightM + 0.45 - 0.1 * row);
      scene.push_back(
          make(kinds[k].primitive, at(p_G.x(), p_G.y(), p_G.z()), kinds[k].size_m, kinds[k].rgba));
      kind_of.push_back(k);
    }
  }
  ASSERT_EQ(scene.size(), 200u);
  renderer().render(scene, head_pose());
  EXPECT_EQ(renderer().last_draw_calls(), 8) << "box, sphere, cylinder and cap meshes, two eyes";
  EXPECT_EQ(renderer().gl_error_count(), 0u);
  int wrong = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
      const Rgb c =
          pixel_at(renderer(), eye, projected(config(), eye, scene[i].X_GO.translation()));
      if (!kinds[kind_of[i]].looks_right(c)) {
        ++wrong;
        ADD_FAILURE() << "instance " << i << " eye " << eye_index(eye) << ": " << c;
      }
      if (wrong > 5) return;
    }
  }
}

// ~40 instances: a panel, switches, levers and two hands' worth of capsules.
std::vector<Instance> cockpit_scene() {
  std::vector<Instance> scene;
  scene.push_back(
      make(Primitive::kBox, at(0.9, 0.0, 0.85), {0.1, 1.2, 0.5}, {0.25f, 0.27f, 0.3f, 1}));
  for (int i = 0; i < 9; ++i) {
    scene.push_back(make(Primitive::kBox, at(0.83, -0.4 + 0.1 * i, 1.0), {0.03, 0.04, 0.02},
                         {0.8f, 0.8f, 0.2f, 1}));
  }
  for (int i = 0; i < 4; ++i) {
    scene.push_back(make(Primitive::kCylinder, at(0.8, -0.3 + 0.2 * i, 0.9), {0.02, 0.08, 0},
                         {0.1f, 0.4f, 0.9f, 1}, i == 1));
  }
  for (int i = 0; i < 6; ++i) {
    scene.push_back(make(Primitive::kSphere, at(0.75, -0.25 + 0.1 * i, 0.8), {0.025, 0, 0},
                         {0.9f, 0.2f, 0.2f, 1}));
  }
  for (int hand = 0; hand < 2; ++hand) {
    scene.push_back(make(Primitive::kRoundedBox, at(0.5, hand ? -0.2 : 0.2, 1.0), {0.09, 0.08, 0.025},
                         {0.9f, 0.75f, 0.6f, 1}));
    for (int link = 0; link < 10; ++link) {
      const Eigen::Isometry3d X_GO =
          at(0.55 + 0.02 * (link % 5), (hand ? -0.2 : 0.2) + 0.02 * (link / 5), 1.0) *
          Eigen::AngleAxisd(80 * kDeg, Eigen::Vector3d::UnitY());
      scene.push_back(make(link % 2 ? Primitive::kTaperedCapsule : Primitive::kCapsule, X_GO,
                           {0.009, 0.03, 0}, {0.9f, 0.75f, 0.6f, 1}));
    }
  }
  // glazing: drawn translucent, in a pass of its own
  scene.push_back(make(Primitive::kBox, at(0.95, 0.0, 1.3), {0.02, 1.2, 0.5}, {0.45f, 0.55f, 0.62f, 0.3f}));
  return scene;
}

TEST_F(RenderTest, NoHeapAllocationOnceWarmedUp) {
  if (!kCountingAllocations) GTEST_SKIP() << "operator new belongs to the sanitizer";
  const std::vector<Instance> scene = cockpit_scene();
  for (int i = 0; i < 3; ++i)
    renderer().render(scene, head_pose());
  const uint8_t* pixels = renderer().pixels();
  g_allocations = 0;
  g_count_allocations = true;
  static void* volatile sink = nullptr;  // control: the counter sees an allocation kept alive
  sink = ::operator new(16);
  ::operator delete(sink);
  ASSERT_EQ(g_allocations.load(), 1);
  g_allocations = 0;
  for (int i = 0; i < 10; ++i)
    renderer().render(scene, head_pose());
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_EQ(renderer().pixels(), pixels) << "same buffer every frame";
}

// The cockpit frame over a slowly turning head raises no GL error. (What a frame costs is
// measured by scripts/bench through image_generator --stats-out, not here.)
TEST_F(RenderTest, CockpitFramesRaiseNoGlError) {
  const std::vector<Instance> scene = cockpit_scene();
  for (int i = 0; i < 10; ++i)
    renderer().render(scene, head_pose() * Eigen::AngleAxisd(0.002 * i, Eigen::Vector3d::UnitZ()));
  EXPECT_GT(renderer().last_draw_calls(), 0);
  EXPECT_EQ(renderer().gl_error_count(), 0u);
}

// Two renderers in one process each keep their own context and buffer.
TEST_F(RenderTest, SecondRendererHasItsOwnContext) {
  HmdConfig small;
  small.width_px = 320;
  small.height_px = 240;
  StereoRenderer other(small);
  other.render({make(Primitive::kSphere, at(1.0, 0.0, kHeadHeightM), {0.1, 0, 0}, kGreen)},
               head_pose());
  renderer().render({}, head_pose());
  other.render({make(Primitive::kSphere, at(1.0, 0.0, kHeadHeightM), {0.1, 0, 0}, kGreen)},
               head_pose());
  const Eigen::Vector2d c = projected(small, Eye::kRight, Eigen::Vector3d(1.0, 0.0, kHeadHeightM));
  EXPECT_TRUE(is_green(pixel_at(other, Eye::kRight, c)));
  EXPECT_TRUE(is_background(pixel_at(renderer(), Eye::kRight, 640, 360)));
}

// The background layer (stereo_renderer.hpp): a frame made from the cached background plus the
// moving instances is the frame a full redraw makes, pixel for pixel (within one grey level),
// also where moving and fixed instances cut into each other; the cache is redrawn when a fixed
// instance or the head changes, and only then.
TEST_F(RenderTest, CachedBackgroundFrameEqualsAFullRedraw) {
  std::vector<Instance> scene;
  auto fixed = [&](Primitive p, const Eigen::Isometry3d& X, const Eigen::Vector3d& size,
                   const std::array<float, 4>& rgba) {
    Instance in = make(p, X, size, rgba);
    in.fixed = true;
    scene.push_back(in);
  };
  fixed(Primitive::kBox, at(1.2, 0.0, kHeadHeightM - 0.3), {0.1, 1.5, 0.6}, {0.35f, 0.36f, 0.4f, 1});
  fixed(Primitive::kBox, at(0.8, -0.3, kHeadHeightM - 0.25), {0.4, 0.3, 0.05}, {0.5f, 0.5f, 0.45f, 1});
  fixed(Primitive::kCylinder, at(1.0, 0.25, kHeadHeightM - 0.1), {0.05, 0.4, 0}, kGreen);
  const std::size_t fixed_count = scene.size();
  auto with_moving = [&](double x) {
    std::vector<Instance> all(scene.begin(), scene.begin() + static_cast<std::ptrdiff_t>(fixed_count));
    // a sphere and a capsule pushed into the panel and the slab: depth against the cached depth
    all.push_back(make(Primitive::kSphere, at(x, -0.1, kHeadHeightM - 0.2), {0.08, 0, 0}, kRed));
    all.push_back(make(Primitive::kCapsule, at(x - 0.3, -0.3, kHeadHeightM - 0.22), {0.03, 0.2, 0},
                       {0.85f, 0.66f, 0.55f, 1}));
    return all;
  };
  StereoRenderer full(config());
  full.set_background_cache(false);
  const uint64_t redraws_before = renderer().background_redraws();
  for (const double x : {1.1, 1.15, 1.2}) {
    const std::vector<Instance> frame = with_moving(x);
    renderer().render(frame, head_pose());
    full.render(frame, head_pose());
    const std::size_t bytes = static_cast<std::size_t>(2 * 1280 * 720 * 4);
    int worst = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
      const int d = std::abs(int{renderer().pixels()[i]} - int{full.pixels()[i]});
      worst = std::max(worst, d);
      if (d > 0) ++differing;
    }
    EXPECT_LE(worst, 1) << "at x " << x << ": " << differing << " bytes differ";
    EXPECT_EQ(renderer().gl_error_count(), 0u);
    EXPECT_EQ(full.gl_error_count(), 0u);
  }
  EXPECT_EQ(renderer().background_redraws(), redraws_before + 1) << "drawn once for three frames";
  // a fixed instance changes colour (an annunciator lit): redrawn; the head moves: redrawn
  std::vector<Instance> lit = with_moving(1.2);
  lit[2].highlight = true;
  renderer().render(lit, head_pose());
  EXPECT_EQ(renderer().background_redraws(), redraws_before + 2);
  EXPECT_TRUE(renderer().last_cost().background_redrawn);
  renderer().render(lit, head_pose() * Eigen::Translation3d(0, 0.01, 0));
  EXPECT_EQ(renderer().background_redraws(), redraws_before + 3);
  renderer().render(lit, head_pose() * Eigen::Translation3d(0, 0.01, 0));
  EXPECT_EQ(renderer().background_redraws(), redraws_before + 3);
  EXPECT_FALSE(renderer().last_cost().background_redrawn);
  // a fixed box drawn rounded instead, same pose, size and colour (the same record): redrawn
  lit[0].primitive = Primitive::kRoundedBox;
  renderer().render(lit, head_pose() * Eigen::Translation3d(0, 0.01, 0));
  EXPECT_EQ(renderer().background_redraws(), redraws_before + 4);
}

// A frame a consumer keeps (shared_pixels) stays as it was while the renderer goes on: later
// frames are read into other buffers; once let go, its buffer is used again.
TEST_F(RenderTest, AHeldFrameIsNotOverwritten) {
  renderer().render({make(Primitive::kBox, at(1.0, 0.0, kHeadHeightM), {0.1, 0.1, 0.1}, kRed)},
                    head_pose());
  auto held = renderer().shared_pixels();
  const std::vector<uint8_t> copy = *held;
  renderer().render({}, head_pose());
  EXPECT_NE(renderer().pixels(), held->data()) << "the next frame went elsewhere";
  EXPECT_TRUE(*held == copy) << "the held frame is unchanged";
  EXPECT_TRUE(is_background(pixel_at(renderer(), Eye::kLeft, 640, 360)));
  const uint8_t* buffer = held->data();
  held.reset();
  renderer().render({}, head_pose());
  renderer().render({}, head_pose());
  EXPECT_EQ(renderer().pixels(), buffer) << "let go, it is used again (the pool does not grow)";
}

// ---------------------------------------------------------------------------------------------
// the outside view and the glazing

Eigen::Vector3d elevated(double elevation_deg) {
  return {std::cos(elevation_deg * kDeg), 0.0, std::sin(elevation_deg * kDeg)};
}

// The pixel that looks along d_G from the eye (a point 10 m along it projected).
Eigen::Vector2d pixel_looking(const HmdConfig& config, Eye eye, const Eigen::Vector3d& d_G) {
  const Eigen::Vector3d p_GE = eye_pose(config, eye, head_pose()).translation();
  return projected(config, eye, p_GE + 10.0 * d_G.normalized());
}

HmdConfig with_outside_view() {
  HmdConfig config;
  config.outside = OutsideView{300.0};
  return config;
}

TEST(OutsideView, SkyAboveTheHorizonGroundBelowAndTheCockpitInFront) {
  const HmdConfig config = with_outside_view();
  StereoRenderer renderer(config);
  const Eigen::Vector3d p_G_box(1.0, 0.3, kHeadHeightM - 0.3);
  renderer.render({make(Primitive::kBox, at(p_G_box.x(), p_G_box.y(), p_G_box.z()), {0.1, 0.1, 0.1}, kRed)},
                  head_pose());
  EXPECT_EQ(renderer.gl_error_count(), 0u);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb overhead = pixel_at(renderer, eye, pixel_looking(config, eye, elevated(35)));
    const Rgb low_sky = pixel_at(renderer, eye, pixel_looking(config, eye, elevated(3)));
    const Rgb ground = pixel_at(renderer, eye, pixel_looking(config, eye, elevated(-20)));
    const Rgb far_ground = pixel_at(renderer, eye, pixel_looking(config, eye, elevated(-1)));
    // a blue sky, paler towards the horizon
    EXPECT_GT(overhead.b, overhead.g) << overhead;
    EXPECT_GT(overhead.g, overhead.r) << overhead;
    EXPECT_GT(overhead.b - overhead.r, low_sky.b - low_sky.r + 20) << overhead << " " << low_sky;
    // fields below (greens and browns: blue the weakest), hazier far off
    EXPECT_GT(ground.g, ground.b + 20) << ground;
    EXPECT_GT(ground.r, ground.b) << ground;
    EXPECT_FALSE(is_background(ground)) << ground;
    EXPECT_GT(far_ground.b, ground.b + 30) << far_ground << " " << ground;
    // the cockpit covers it
    EXPECT_TRUE(is_red(pixel_at(renderer, eye, projected(config, eye, p_G_box))));
    // the horizon is one soft line: no step between neighbouring rows across it (a hard line
    // between haze and fields would step by 90 levels or more; the sky's own gradient is
    // steepest just above it)
    const Eigen::Vector2d above = pixel_looking(config, eye, elevated(2));
    const Eigen::Vector2d below = pixel_looking(config, eye, elevated(-2));
    const int column = static_cast<int>(above.x());
    int worst_step = 0;
    for (int row = static_cast<int>(above.y()); row < static_cast<int>(below.y()); ++row) {
      const Rgb a = pixel_at(renderer, eye, column, row), b = pixel_at(renderer, eye, column, row + 1);
      worst_step = std::max({worst_step, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
    }
    EXPECT_LE(worst_step, 12) << "rows " << above.y() << ".." << below.y();
  }
}

// A translucent pane (rgba alpha < 1: a windscreen) tints the cockpit behind it and hides
// nothing: it writes no depth, so what moves behind it still shows.
TEST_F(RenderTest, GlazingTintsWhatIsBehindItAndHidesNothing) {
  Instance pane = make(Primitive::kBox, at(0.8, 0.0, kHeadHeightM), {0.01, 1.0, 1.0}, {0.9f, 0.9f, 0.95f, 0.4f});
  pane.fixed = true;
  const Eigen::Vector3d p_G_red(1.2, 0.15, kHeadHeightM), p_G_green(1.2, -0.15, kHeadHeightM);
  Instance red = make(Primitive::kBox, at(p_G_red.x(), p_G_red.y(), p_G_red.z()), {0.1, 0.1, 0.1}, kRed);
  red.fixed = true;
  const Instance green =
      make(Primitive::kBox, at(p_G_green.x(), p_G_green.y(), p_G_green.z()), {0.1, 0.1, 0.1}, kGreen);
  renderer().render({red, green}, head_pose());
  const Rgb red_bare = pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, p_G_red));
  renderer().render({pane, red, green}, head_pose());
  EXPECT_EQ(renderer().gl_error_count(), 0u);
  for (const Eye eye : {Eye::kLeft, Eye::kRight}) {
    const Rgb red_tinted = pixel_at(renderer(), eye, projected(config(), eye, p_G_red));
    EXPECT_GT(red_tinted.r, red_tinted.g + 40) << red_tinted;
    EXPECT_GT(red_tinted.g, red_bare.g + 40) << red_tinted << " over " << red_bare;
    EXPECT_TRUE(is_green(pixel_at(renderer(), eye, projected(config(), eye, p_G_green))))
        << "the moving box behind the pane shows";
    const Rgb glass = pixel_at(renderer(), eye, projected(config(), eye, {0.8, 0.0, kHeadHeightM + 0.3}));
    EXPECT_GT(glass.r, static_cast<int>(kBackgroundRgb[0] * 255) + 30) << glass;
  }
}

// The cached background holds the outside view and the glazing as a full redraw draws them.
TEST(OutsideView, CachedBackgroundFrameEqualsAFullRedraw) {
  const HmdConfig config = with_outside_view();
  StereoRenderer cached(config), full(config);
  full.set_background_cache(false);
  Instance pane = make(Primitive::kBox, at(0.9, 0.0, kHeadHeightM + 0.2), {0.01, 1.2, 0.6}, {0.45f, 0.55f, 0.62f, 0.3f});
  pane.fixed = true;
  Instance panel = make(Primitive::kBox, at(0.9, 0.0, kHeadHeightM - 0.3), {0.05, 1.2, 0.4}, {0.3f, 0.3f, 0.32f, 1});
  panel.fixed = true;
  for (const double x : {0.6, 0.65}) {
    const std::vector<Instance> frame{pane, panel, make(Primitive::kSphere, at(x, 0.0, kHeadHeightM - 0.1), {0.05, 0, 0}, kRed)};
    cached.render(frame, head_pose());
    full.render(frame, head_pose());
    const std::size_t bytes = static_cast<std::size_t>(2 * 1280 * 720 * 4);
    int worst = 0;
    for (std::size_t i = 0; i < bytes; ++i)
      worst = std::max(worst, std::abs(int{cached.pixels()[i]} - int{full.pixels()[i]}));
    EXPECT_LE(worst, 1) << "at x " << x;
  }
  EXPECT_EQ(cached.background_redraws(), 1u) << "drawn once for two frames";
  EXPECT_EQ(cached.gl_error_count(), 0u);
  EXPECT_EQ(full.gl_error_count(), 0u);
}

TEST(StereoRenderer, RejectsABadConfig) {
  HmdConfig config;
  config.ipd_m = 0.5;
  EXPECT_THROW(StereoRenderer{config}, std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// frame export

// one directory per test: ctest runs this file's tests in parallel processes
std::filesystem::path test_dir() { return vcockpit::test::make_temp_dir("render"); }

std::vector<uint8_t> read_png(const std::string& path, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return {};
  image.format = PNG_FORMAT_RGBA;
  std::vector<uint8_t> rgba(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr)) return {};
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return rgba;
}

TEST_F(RenderTest, PngRoundTripOfARenderedFrame) {
  renderer().render(cockpit_scene(), head_pose());
  const int width = 2 * renderer().width_px(), height = renderer().height_px();
  const std::string path = (test_dir() / "stereo.png").string();
  std::filesystem::remove(path);
  write_png(path, renderer().pixels(), width, height);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  int read_width = 0, read_height = 0;
  const std::vector<uint8_t> back = read_png(path, read_width, read_height);
  ASSERT_EQ(read_width, width);
  ASSERT_EQ(read_height, height);
  ASSERT_EQ(back.size(), static_cast<size_t>(width) * height * 4);
  EXPECT_TRUE(std::equal(back.begin(), back.end(), renderer().pixels()));

  // one eye, cut out and written on its own
  std::vector<uint8_t> right;
  copy_eye(renderer().pixels(), renderer().width_px(), height, Eye::kRight, right);
  const std::string eye_path = (test_dir() / "right.png").string();
  write_png(eye_path, right.data(), renderer().width_px(), height);
  const std::vector<uint8_t> eye_back = read_png(eye_path, read_width, read_height);
  ASSERT_EQ(read_width, renderer().width_px());
  EXPECT_EQ(eye_back, right);
}

TEST(CopyEye, TakesTheRightHalfOfEachRow) {
  // 2 eyes of 3 x 2 px; each pixel's red channel is its side-by-side column, green its row
  std::vector<uint8_t> frame;
  for (int row = 0; row < 2; ++row) {
    for (int column = 0; column < 6; ++column) {
      frame.insert(frame.end(), {static_cast<uint8_t>(column), static_cast<uint8_t>(row), 0, 255});
    }
  }
  std::vector<uint8_t> left, right;
  copy_eye(frame.data(), 3, 2, Eye::kLeft, left);
  copy_eye(frame.data(), 3, 2, Eye::kRight, right);
  ASSERT_EQ(left.size(), 24u);
  ASSERT_EQ(right.size(), 24u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(left[i * 4], i % 3);
    EXPECT_EQ(right[i * 4], 3 + i % 3);
    EXPECT_EQ(right[i * 4 + 1], i / 3);
  }
}

TEST(WritePng, FailureNamesThePathAndLeavesNoPartial) {
  const std::vector<uint8_t> rgba(4 * 4 * 4, 128);
  const std::string path = (test_dir() / "no_such_dir" / "frame.png").string();
  try {
    write_png(path, rgba.data(), 4, 4);
    FAIL() << "wrote into a missing directory";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_png((test_dir() / "x.png").string(), rgba.data(), 4, 4, 10),
               std::invalid_argument);
  EXPECT_THROW(write_png((test_dir() / "x.png").string(), rgba.data(), 0, 4),
               std::invalid_argument);
}


// ---- the panel's instruments (render/instrument_panel.hpp) ---------------------------------------

TEST(InstrumentPanel, NeedleAngleIsLinearInItsRangeAndClamped) {
  GaugeSpec g;
  g.min = 0;
  g.max = 100;
  g.start_deg = -135;
  g.end_deg = 135;
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, 0), -135);
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, 50), 0);
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, 75), 67.5);
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, 250), 135);
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, -5), -135);
  EXPECT_DOUBLE_EQ(needle_angle_deg(g, std::nan("")), -135);  // not known: at rest
}

// A label is the panel font's glyphs as boxes, one per run of lit pixels in a row, centred.
TEST(InstrumentPanel, LabelsAreTheFontsGlyphsAsRunsOfBoxes) {
  PanelFace face;  // identity: x right, y up, z out
  std::vector<Instance> boxes;
  append_label(face, {"I", {0.0, 0.0}, 0.007, {1, 1, 1}}, boxes);
  // 'I': a bar of 3 at the top and bottom, a single pixel in the 5 rows between
  ASSERT_EQ(boxes.size(), 7u);
  EXPECT_NEAR(boxes[0].size_m.x(), 0.003, 1e-12);
  EXPECT_NEAR(boxes[0].X_GO.translation().x(), 0.0, 1e-12);  // centred
  EXPECT_NEAR(boxes[0].X_GO.translation().y(), 0.003, 1e-12);  // the top row
  EXPECT_NEAR(boxes[6].X_GO.translation().y(), -0.003, 1e-12);
  EXPECT_NEAR(boxes[3].size_m.x(), 0.001, 1e-12);
  boxes.clear();
  append_label(face, {"RPM", {0.1, 0.2}, 0.007, {1, 1, 1}}, boxes);
  double left = 1, right = -1;
  for (const Instance& b : boxes) {
    left = std::min(left, b.X_GO.translation().x() - b.size_m.x() / 2);
    right = std::max(right, b.X_GO.translation().x() + b.size_m.x() / 2);
  }
  EXPECT_NEAR(left + right, 0.2, 1e-12);      // centred on x = 0.1
  EXPECT_NEAR(right - left, 0.017, 1e-12);    // 3 glyphs of 5 and 2 gaps, 1 mm pixels
}

// A gauge and a lamp on a face 0.6 m ahead: the needle is where its value puts it and nowhere
// else, the lamp is bright only when lit, and neither redraws the cached static layer.
TEST_F(RenderTest, InstrumentNeedleAndLampFollowTheirValuesInTheMovingLayer) {
  InstrumentsSpec spec;
  spec.face.X_GF.linear().col(0) = Eigen::Vector3d(0, -1, 0);  // the pilot's right
  spec.face.X_GF.linear().col(1) = Eigen::Vector3d(0, 0, 1);   // up
  spec.face.X_GF.linear().col(2) = Eigen::Vector3d(-1, 0, 0);  // toward the pilot
  spec.face.X_GF.translation() = Eigen::Vector3d(0.6, 0.0, kHeadHeightM);
  GaugeSpec gauge;
  gauge.system = "rpm";
  gauge.radius_m = 0.05;
  spec.gauges.push_back(gauge);
  LampSpec lamp;
  lamp.system = "fire";
  lamp.at_m = {0.09, 0.0};
  lamp.size_m = {0.03, 0.02};
  lamp.rgb = {0.95f, 0.1f, 0.1f};
  spec.lamps.push_back(lamp);
  EXPECT_EQ(spec.systems(), (std::vector<std::string>{"rpm", "fire"}));

  // a point on the needle's line for a value: 60 % out along it, on top of it
  const auto needle_point = [&](double value) {
    const double a = needle_angle_deg(gauge, value) * M_PI / 180.0;
    return Eigen::Vector3d(spec.face.at({0.6 * 0.05 * std::sin(a), 0.6 * 0.05 * std::cos(a)}) *
                           Eigen::Vector3d(0, 0, 0.0095));
  };
  const auto is_needle = [](const Rgb& c) { return c.r > 150 && c.g > 60 && c.b < 80 && c.r > c.g; };
  const auto frame = [&](double rpm, double fire) {
    std::vector<Instance> all;
    append_instrument_faces(spec, all);
    for (Instance& i : all) i.fixed = true;
    append_instrument_indications(spec, {rpm, fire}, all);
    renderer().render(all, head_pose());
    EXPECT_EQ(renderer().gl_error_count(), 0u);
  };
  const Eigen::Vector3d lamp_centre = spec.face.at(lamp.at_m) * Eigen::Vector3d(0, 0, 0.004);
  frame(0.0, 0.0);
  const uint64_t redraws = renderer().background_redraws();
  const Rgb lamp_off = pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, lamp_centre));
  EXPECT_TRUE(is_needle(pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, needle_point(0)))));
  EXPECT_FALSE(is_needle(pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, needle_point(100)))));
  frame(100.0, 1.0);
  EXPECT_FALSE(is_needle(pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, needle_point(0)))));
  for (const Eye eye : {Eye::kLeft, Eye::kRight})
    EXPECT_TRUE(is_needle(pixel_at(renderer(), eye, projected(config(), eye, needle_point(100)))));
  const Rgb lamp_on = pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, lamp_centre));
  EXPECT_GT(lamp_on.r, 2 * lamp_off.r + 40) << lamp_off << " -> " << lamp_on;
  frame(50.0, 0.0);
  EXPECT_TRUE(is_needle(pixel_at(renderer(), Eye::kLeft, projected(config(), Eye::kLeft, needle_point(50)))));
  EXPECT_EQ(renderer().background_redraws(), redraws) << "the faces stay cached as values change";
}

}  // namespace
}  // namespace vcockpit::render
