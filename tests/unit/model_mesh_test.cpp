// Meshes from model files (model/): the same solids written by scripts/make_test_models.py as
// glTF, OBJ and AC3D load to the same geometry in the project's axes and metres; bad files are
// refused with the file and node named; the mass properties and the convex hull against closed
// forms.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/convex_hull.hpp"
#include "model/import/model_file.hpp"
#include "model/triangle_mesh.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::model {
namespace {

std::string models_dir() {
  return std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models";
}

const double kRampHeight_m = 0.8 * std::tan(20.0 * M_PI / 180.0);

class EachFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(EachFormat, TheRampLoadsInMetresWithZUpAndOutwardTriangles) {
  const TriangleMesh ramp = load_model_mesh({models_dir() + "/ramp." + GetParam(), "ramp"});
  const Bounds b = bounds(ramp);
  EXPECT_TRUE(b.min_m.isApprox(Eigen::Vector3d(-0.4, -0.15, 0.0), 1e-6)) << b.min_m.transpose();
  EXPECT_NEAR(b.max_m.x(), 0.4, 1e-6);
  EXPECT_NEAR(b.max_m.y(), 0.15, 1e-6);
  EXPECT_NEAR(b.max_m.z(), kRampHeight_m, 1e-6) << "the slope's top is up (+z), not along y";
  EXPECT_EQ(ramp.triangles.size(), 8u);
  // a positive volume: every triangle faces out
  const MassProperties m = mass_properties(ramp);
  EXPECT_NEAR(m.volume_m3, 0.5 * 0.8 * kRampHeight_m * 0.3, 1e-7);  // (6 decimals in the files)
  // the wedge's centroid: a third of the way up from the bottom, a third from the high end
  EXPECT_NEAR(m.centroid_m.x(), -0.4 + 0.8 / 3.0, 1e-6);
  EXPECT_NEAR(m.centroid_m.z(), kRampHeight_m / 3.0, 1e-6);
  ASSERT_EQ(ramp.colors_rgba.size(), ramp.vertices_m.size());
  EXPECT_NEAR(ramp.colors_rgba[0][0], 0.55f, 1e-3f) << "the material's base colour";
  EXPECT_NEAR(ramp.colors_rgba[0][2], 0.6f, 1e-3f);
}

TEST_P(EachFormat, ScaleAndUpAxisAreApplied) {
  ModelRequest request{models_dir() + "/ramp." + GetParam(), "ramp", 2.0, UpAxis::kZ};
  const Bounds b = bounds(load_model_mesh(request));
  // read as +z up, the file's y (the height) stays y; doubled
  EXPECT_NEAR(b.max_m.y(), 2.0 * kRampHeight_m, 1e-6);
  EXPECT_NEAR(b.max_m.z(), 2.0 * 0.15, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Model, EachFormat, ::testing::Values("gltf", "obj", "ac"));

TEST(ModelFile, TheWholeFileWithoutANode) {
  const TriangleMesh all = load_model_mesh({models_dir() + "/button.gltf", ""});
  EXPECT_EQ(all.triangles.size(), 20u);  // top and bottom, eight side quads: ten quads
}

// A cockpit that is one file of many parts (a flight simulator's .ac, a Blender export): its parts
// read in one go, the file parsed once, each part as it reads alone; a part the file lacks gets
// its error in its place. A ModelPrefetch hands the parts out to load_model_mesh without another
// read while it lives.
TEST(ModelFile, SeveralPartsOfOneFileAreReadInOneGo) {
  const std::string dir = vcockpit::test::make_temp_dir("vcockpit_model_parts");
  const std::string obj = dir + "/parts.obj";
  std::ofstream(obj) << "o lever\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                        "o knob\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 4 5 6\nf 4 6 7\n"
                        "o panel\nv 0 0 2\nv 2 0 2\nv 0 2 2\nf 8 9 10\n";
  const std::vector<ModelRequest> requests{{obj, "lever"}, {obj, "knob"}, {obj, "switch"},
                                           {obj, "panel", 2.0}};
  const uint64_t reads = model_file_reads();
  const std::vector<ModelPart> parts = load_model_parts(requests);
  EXPECT_EQ(model_file_reads(), reads + 1) << "one read of the file";
  ASSERT_EQ(parts.size(), 4u);
  for (const std::size_t i : {0u, 1u, 3u}) {
    ASSERT_TRUE(parts[i].mesh) << requests[i].node << ": " << parts[i].error;
    const TriangleMesh alone = load_model_mesh(requests[i]);
    EXPECT_EQ(parts[i].mesh->vertices_m, alone.vertices_m) << requests[i].node;
    EXPECT_EQ(parts[i].mesh->triangles, alone.triangles) << requests[i].node;
    EXPECT_EQ(parts[i].mesh->source, alone.source);
  }
  EXPECT_EQ(parts[1].mesh->triangles.size(), 2u);
  EXPECT_FALSE(parts[2].mesh);
  EXPECT_NE(parts[2].error.find(obj + ": no node 'switch'"), std::string::npos) << parts[2].error;
  EXPECT_THROW(load_model_parts({{obj, "lever"}, {dir + "/other.obj", "knob"}}), std::invalid_argument);

  {
    const ModelPrefetch prefetch(requests);
    const uint64_t before = model_file_reads();
    EXPECT_EQ(load_model_mesh(requests[1]).triangles, parts[1].mesh->triangles);
    EXPECT_EQ(load_model_mesh(requests[0]).vertices_m, parts[0].mesh->vertices_m);
    EXPECT_EQ(load_model_mesh(requests[0]).vertices_m, parts[0].mesh->vertices_m) << "twice";
    try {
      load_model_mesh(requests[2]);
      ADD_FAILURE() << "a part the file lacks";
    } catch (const MeshError& e) {
      EXPECT_NE(std::string(e.what()).find("no node 'switch'"), std::string::npos) << e.what();
    }
    EXPECT_EQ(model_file_reads(), before) << "handed out, not read again";
    // what was not asked for beforehand is read as ever (the same part at another scale)
    load_model_mesh({obj, "lever", 3.0});
    EXPECT_EQ(model_file_reads(), before + 1);
  }
  const uint64_t after = model_file_reads();
  load_model_mesh(requests[0]);
  EXPECT_EQ(model_file_reads(), after + 1) << "once the prefetch is gone, read again";
  // a file that cannot be read: each part gets the error reading it alone gives, without
  // another try
  const ModelPrefetch missing({{dir + "/none.obj", "a"}, {dir + "/none.obj", "b"}});
  const uint64_t tried = model_file_reads();
  for (const char* node : {"a", "b"}) {
    try {
      load_model_mesh({dir + "/none.obj", node});
      ADD_FAILURE() << "a missing file";
    } catch (const MeshError& e) {
      EXPECT_EQ(std::string(e.what()), dir + "/none.obj: no such file");
    }
  }
  EXPECT_EQ(model_file_reads(), tried);
}

class BadModel : public ::testing::Test {
 protected:
  // one directory per test: ctest runs this fixture's tests in parallel processes
  std::filesystem::path dir_;
  void SetUp() override { dir_ = vcockpit::test::make_temp_dir("vcockpit_model"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  // the message of the MeshError loading `request` throws ("" if none)
  static std::string error_of(const ModelRequest& request) {
    try {
      load_model_mesh(request);
    } catch (const MeshError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(BadModel, EachIsRefusedNamingTheFileAndWhat) {
  const std::string missing = (dir_ / "nothing.glb").string();
  EXPECT_EQ(error_of({missing, ""}), missing + ": no such file");
  const std::string stl = write("part.stl", "solid x\nendsolid x\n");
  EXPECT_NE(error_of({stl, ""}).find("unsupported model format"), std::string::npos);
  const std::string garbage = write("broken.gltf", "{ this is not json");
  EXPECT_NE(error_of({garbage, ""}).find(garbage + ": not a readable model"), std::string::npos);
  const std::string no_node = error_of({models_dir() + "/ramp.gltf", "lever"});
  EXPECT_NE(no_node.find("no node 'lever' (its nodes: "), std::string::npos) << no_node;
  EXPECT_NE(no_node.find("'ramp'"), std::string::npos) << no_node;
  const std::string nan = write("nan.obj", "o part\nv 0 0 0\nv 1 0 0\nv 1e999 1 0\nf 1 2 3\n");
  const std::string nan_error = error_of({nan, ""});
  EXPECT_NE(nan_error.find("is not a finite number"), std::string::npos) << nan_error;
  const std::string flat = write("flat.obj", "o part\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const std::string flat_error = error_of({flat, "part"});
  EXPECT_NE(flat_error.find(flat + " node 'part': every one of its 1 triangles is degenerate"),
            std::string::npos)
      << flat_error;
  const std::string empty = write("empty.obj", "o part\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_NE(error_of({empty, ""}).find(empty), std::string::npos);
  EXPECT_NE(
      error_of({models_dir() + "/ramp.obj", "", -1.0}).find("scale must be a positive number"),
      std::string::npos);
}

// A triangle with no area among good ones (CAD exports and simulator models have them) is left
// out and counted, not a reason to refuse the part.
TEST_F(BadModel, ADegenerateTriangleAmongGoodOnesIsDroppedAndCounted) {
  const std::string part = write("part.obj",
                                 "o part\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                 "f 1 2 3\nf 1 2 4\nf 1 3 2\n");
  const TriangleMesh mesh = load_model_mesh({part, "part"});
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.degenerate_dropped, 1u);
  EXPECT_EQ(mesh.first_degenerate, 1u);
}

TEST(MassProperties, AUnitCubeAgainstItsClosedForm) {
  TriangleMesh cube;
  for (int i = 0; i < 8; ++i)
    cube.vertices_m.emplace_back(i & 1 ? 1.0 : 0.0, i & 2 ? 1.0 : 0.0, i & 4 ? 1.0 : 0.0);
  const TriangleMesh hull = convex_hull(cube);
  EXPECT_EQ(hull.triangles.size(), 12u);
  const MassProperties m = mass_properties(hull);
  EXPECT_NEAR(m.volume_m3, 1.0, 1e-12);
  EXPECT_TRUE(m.centroid_m.isApprox(Eigen::Vector3d::Constant(0.5), 1e-12));
  EXPECT_TRUE(m.unit_density_inertia.isApprox(Eigen::Matrix3d::Identity() / 6.0, 1e-12))
      << m.unit_density_inertia;
}

TEST(ConvexHull, TheButtonCapsHullIsTheCapItselfAndAFlatPartHasNone) {
  const TriangleMesh cap = load_model_mesh({models_dir() + "/button.obj", "button"});
  const TriangleMesh hull = convex_hull(cap);
  // the chamfered block is convex: its hull has its volume, 24 x 24 x 10 mm plus the chamfer's
  // frustum (2 mm high, 24 mm square below and 20 mm above)
  const double frustum_m3 = 0.002 / 3.0 * (0.024 * 0.024 + 0.020 * 0.020 + 0.024 * 0.020);
  EXPECT_NEAR(mass_properties(hull).volume_m3, 0.024 * 0.024 * 0.010 + frustum_m3, 1e-12);
  EXPECT_NEAR(mass_properties(hull).volume_m3, mass_properties(cap).volume_m3, 1e-12);
  TriangleMesh flat;
  flat.source = "panel.glb node 'placard'";
  flat.vertices_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
  try {
    convex_hull(flat);
    FAIL() << "a flat part has no hull";
  } catch (const MeshError& e) {
    EXPECT_NE(
        std::string(e.what()).find("panel.glb node 'placard' (hull): the vertices span no volume"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vcockpit::model
