// Meshes in the viewer (`ccma view --meshes`, docs/viewer.md "Meshes"): STL
// reading and writing, the mesh files of a model (paths, sharing, bounds),
// the scene's mesh parts, and the command on good and bad files. The page
// itself draws them in a real browser: CTest viewer_browser_meshes.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/rotation.h"
#include "formats/model_loader.h"
#include "tests/tool_run.h"
#include "viewer/html.h"
#include "viewer/mesh_files.h"
#include "viewer/mesh_folders.h"
#include "viewer/scene.h"
#include "viewer/stl.h"
#include "viewer/view_frames.h"

namespace ccma::viewer {
namespace viewer_meshes_test {

namespace fs = std::filesystem;
using ccma::testing::ModelPath;
using ccma::testing::RunTool;
using ccma::testing::ToolRun;

std::string Scratch(const std::string& name) { return ccma::testing::ScratchPath("viewer_meshes", name); }

// A tetrahedron with its four faces wound outwards: vertices (0,0,0), (1,0,0), (0,1,0), (0,0,1) x `size`.
std::vector<StlTriangle> Tetrahedron(float size) {
  const std::array<float, 3> o{0, 0, 0}, x{size, 0, 0}, y{0, size, 0}, z{0, 0, size};
  return {{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
}

// A binary STL written here byte by byte (not by WriteBinaryStl): the header
// says "solid" to show that the size decides, as in three.js's STLLoader.
std::string BinaryStl(const std::vector<StlTriangle>& triangles) {
  std::string out = "solid but binary";
  out.resize(80, ' ');
  auto u32 = [&out](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>(v >> (8 * k)));
  };
  auto f32 = [&u32](float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    u32(bits);
  };
  u32(static_cast<std::uint32_t>(triangles.size()));
  for (const StlTriangle& t : triangles) {
    for (int k = 0; k < 3; ++k) f32(0.0f);  // a zero normal, as some exporters write
    for (const auto& v : t) for (float c : v) f32(c);
    out.append(2, '\0');
  }
  return out;
}

std::string AsciiStl(const std::vector<StlTriangle>& triangles) {
  std::string out = "solid tetra made by hand\n";
  for (const StlTriangle& t : triangles) {
    out += "  facet normal 0 0 0\n    outer loop\n";
    for (const auto& v : t) {
      out += "      vertex " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid tetra\n";
}

std::string ErrorOf(const std::string& bytes) {
  try {
    ReadStl(bytes);
  } catch (const StlError& e) {
    return e.what();
  }
  return "";
}

TEST(Stl, BinaryAndAsciiReadTheSameTriangles) {
  const std::vector<StlTriangle> tetra = Tetrahedron(0.25f);
  EXPECT_EQ(ReadStl(BinaryStl(tetra)), tetra);
  EXPECT_EQ(ReadStl(AsciiStl(tetra)), tetra);
  EXPECT_EQ(ReadStl("  \n" + AsciiStl(tetra) + AsciiStl(tetra)).size(), 8u);  // two solids, leading blanks
  EXPECT_EQ(ReadStl(WriteBinaryStl(tetra)), tetra);
}

TEST(Stl, WrittenFileIsBinaryWithRightHandedUnitNormals) {
  const std::string stl = WriteBinaryStl(Tetrahedron(2.0f));
  ASSERT_EQ(stl.size(), 84u + 4 * 50);
  float n[3];
  std::memcpy(n, stl.data() + 84 + 3 * 50, 12);  // the face (x, y, z): normal (1, 1, 1)/sqrt(3)
  for (float c : n) EXPECT_NEAR(c, 1 / std::sqrt(3.0), 1e-7);
  std::memcpy(n, stl.data() + 84, 12);  // the face (o, y, x) in the plane z = 0, wound to face -z
  EXPECT_EQ(n[2], -1.0f);
}

TEST(Stl, Base64MatchesRfc4648) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(Stl, MalformedFilesSayWhatAndWhere) {
  const std::vector<StlTriangle> tetra = Tetrahedron(1.0f);
  std::string truncated = BinaryStl(tetra);
  truncated.replace(0, 5, "xxxxx");
  truncated.pop_back();
  EXPECT_NE(ErrorOf(truncated).find("neither a binary STL"), std::string::npos) << ErrorOf(truncated);
  EXPECT_NE(ErrorOf("hello").find("neither a binary STL"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("neither a binary STL"), std::string::npos);
  std::string empty(80, ' ');
  empty.append(4, '\0');
  EXPECT_EQ(ErrorOf(empty), "no triangles");
  EXPECT_EQ(ErrorOf("solid x\nendsolid x\n"), "no triangles");
  std::vector<StlTriangle> bad = tetra;
  bad[2][1][0] = NAN;
  EXPECT_EQ(ErrorOf(BinaryStl(bad)), "binary STL: triangle 3 has a vertex that is not a finite number");
  std::string ascii = AsciiStl(tetra);
  ascii.replace(ascii.find("vertex", ascii.find("facet", 30)), 6, "vertec");
  EXPECT_EQ(ErrorOf(ascii), "ASCII STL, line 11: expected 'vertex', got 'vertec'");  // the second facet
  ascii = AsciiStl(tetra);
  ascii.replace(ascii.find("1.000000"), 8, "1e999");
  EXPECT_EQ(ErrorOf(ascii).rfind("ASCII STL, line 5: expected a finite number, got '1e999'", 0), 0u) << ErrorOf(ascii);
  ascii = AsciiStl(tetra);
  EXPECT_EQ(ErrorOf(ascii.substr(0, ascii.size() - 15)), "ASCII STL, line 30: expected 'facet' or 'endsolid', got the end of the file");
}

// The count at byte 80 is believed only as far as the bytes go: a header
// claiming 1e9 triangles (50 GB) allocates nothing. (Already so before the
// trust-boundary work; kept as the STL fuzzer's seeds are: fuzz/corpus_stl/.)
TEST(Stl, ClaimedTriangleCountIsBoundedByTheSize) {
  std::string claim = BinaryStl(Tetrahedron(1.0f));
  const std::uint32_t billion = 1000000000;
  std::memcpy(&claim[80], &billion, 4);
  claim.replace(0, 5, "xxxxx");  // not "solid": only binary could read it
  EXPECT_NE(ErrorOf(claim).find("neither a binary STL"), std::string::npos) << ErrorOf(claim);
  EXPECT_NE(ErrorOf(claim.substr(0, 84)).find("neither a binary STL"), std::string::npos);
  std::vector<StlTriangle> bad = Tetrahedron(1.0f);
  bad[0][0][2] = INFINITY;
  EXPECT_EQ(ErrorOf(BinaryStl(bad)), "binary STL: triangle 1 has a vertex that is not a finite number");
  EXPECT_EQ(ErrorOf("solid x\nfacet normal 0 0 0\nouter loop\nvertex nan 0 0\n").rfind(
                "ASCII STL, line 4: expected a finite number, got 'nan'", 0), 0u);
}

// A grounded post and arm (the arm turned) and an omni base; the arm and the
// base carry meshes given by `arm` and `base`, relative to the model's folder.
std::string WriteMeshModel(const std::string& dir, const std::string& arm, const std::string& base) {
  fs::create_directories(dir);
  const std::string path = dir + "/meshy.yaml";
  std::ofstream(path) << "name: meshy\n"
                         "bodies:\n"
                         "  - {name: post, position: [0, 0, 0.5]}\n"
                         "  - {name: arm, position: [0.3, -0.2, 0.8], rpy: [0.4, -0.3, 1.1],\n"
                         "     meshes: [" << arm << "]}\n"
                         "mobile_bases:\n"
                         "  - {name: base0, actuation: complete, pose: [1, 2, 0.7], meshes: [" << base << "]}\n"
                         "joints:\n"
                         "  - {type: revolute, between: [world, post], point: [0, 0, 0], axis: [0, 0, 1], actuated: true}\n"
                         "  - {type: revolute, between: [post, arm], point: [0.3, -0.2, 0.8], axis: [0, 1, 0]}\n"
                         "  - {type: spherical, between: [base0, arm], point: [1, 2, 0.8]}\n"
                         "end_effector: {body: arm, point: [0.3, -0.2, 0.8], controlled: [x, y]}\n";
  return path;
}

TEST(MeshFiles, PathsResolveAgainstTheModelsFolder) {
  EXPECT_EQ(ResolveMeshPath("robots/r.yaml", "meshes/a.stl"), "robots/meshes/a.stl");
  EXPECT_EQ(ResolveMeshPath("robots/r.yaml", "/abs/a.stl"), "/abs/a.stl");
  EXPECT_EQ(ResolveMeshPath("r.yaml", "a.stl"), "a.stl");
  EXPECT_EQ(ResolveMeshPath("", "a.stl"), "a.stl");
}

// A model's folder and, beside it, a folder it must not reach unless allowed:
//   DIR/model/inside.stl, DIR/outside/secret.stl,
//   DIR/model/link.stl -> DIR/outside/secret.stl (a symlink shipped with the model),
//   DIR/model/linked -> DIR/outside (a symlinked folder),
//   DIR/model/good_link.stl -> inside.stl (a symlink that stays inside).
struct Planted {
  std::string dir, model_dir, outside;
};

Planted PlantOutside(const std::string& name) {
  Planted p;
  p.dir = Scratch(name);
  p.model_dir = p.dir + "/model";
  p.outside = p.dir + "/outside";
  fs::remove_all(p.dir);
  fs::create_directories(p.model_dir);
  fs::create_directories(p.outside);
  std::ofstream(p.model_dir + "/inside.stl", std::ios::binary) << BinaryStl(Tetrahedron(0.1f));
  std::ofstream(p.outside + "/secret.stl", std::ios::binary) << BinaryStl(Tetrahedron(0.3f));
  fs::create_symlink(p.outside + "/secret.stl", p.model_dir + "/link.stl");
  fs::create_directory_symlink(p.outside, p.model_dir + "/linked");
  fs::create_symlink("inside.stl", p.model_dir + "/good_link.stl");
  return p;
}

std::string ReadError(const Model& model, const std::vector<std::string>& roots = {}) {
  try {
    ReadMeshFiles(model, roots);
  } catch (const ViewInputError& e) {
    return e.what();
  }
  return "";
}

// Each way out of the model's folder (an absolute path is added where the
// folder is known): ../, a symlink to a file, a symlinked folder, ../
// through a folder that does not exist. With the name the page gives each
// when allowed: as written when it is relative and stays inside lexically.
const std::vector<std::pair<std::string, std::string>> kOutsideEntries = {
    {"{file: ../outside/secret.stl}", "secret.stl"},
    {"{file: link.stl}", "link.stl"},
    {"{file: linked/secret.stl}", "linked/secret.stl"},
    {"{file: nothing/../../outside/secret.stl}", "secret.stl"}};

TEST(MeshFolders, MeshesOutsideTheModelsFolderAreNotRead) {
  const Planted p = PlantOutside("confined");
  std::vector<std::pair<std::string, std::string>> entries = kOutsideEntries;
  entries.emplace_back("{file: " + p.outside + "/secret.stl}", "secret.stl");
  for (const auto& [entry, page_path] : entries) {
    const Model model = LoadModel(WriteMeshModel(p.model_dir, entry, "{file: inside.stl}"));
    const std::string error = ReadError(model);
    EXPECT_EQ(error.rfind(p.model_dir + "/meshy.yaml:5: body 'arm': mesh '", 0), 0u) << entry << ": " << error;
    EXPECT_NE(error.find(": outside the model file's folder '" + fs::canonical(p.model_dir).string() +
                         "' (symlinks resolved): not read; to allow it, give its folder with --mesh_root=DIR"),
              std::string::npos) << entry << ": " << error;
    // Allowed with the folder as a root: read, and named by its file name.
    const MeshFiles files = ReadMeshFiles(model, {p.outside});
    ASSERT_EQ(files.files.size(), 2u) << entry;
    EXPECT_EQ(ReadStl(files.files[0].stl), Tetrahedron(0.3f)) << entry;
    EXPECT_EQ(files.files[0].page_path, page_path) << entry;
  }
  EXPECT_NE(ReadError(LoadModel(WriteMeshModel(p.model_dir, kOutsideEntries[0].first, "")), {p.dir + "/model"})
                .find("and the mesh roots (symlinks resolved): not read"), std::string::npos);
  EXPECT_EQ(ReadError(LoadModel(WriteMeshModel(p.model_dir, "{file: inside.stl}", "")), {p.dir + "/nope"}),
            "mesh root '" + p.dir + "/nope': not an existing folder");
}

TEST(MeshFolders, MeshesInsideTheModelsFolderAreReadAsBefore) {
  const Planted p = PlantOutside("inside");
  const Model model = LoadModel(WriteMeshModel(
      p.model_dir, "{file: inside.stl}, {file: good_link.stl}", "{file: " + p.model_dir + "/./inside.stl}"));
  const MeshFiles files = ReadMeshFiles(model);
  ASSERT_EQ(files.files.size(), 3u);
  EXPECT_EQ(files.files[1].page_path, "good_link.stl");
  EXPECT_EQ(files.files[2].page_path, "inside.stl");  // absolute: the file name alone
  for (const MeshFiles::File& f : files.files) EXPECT_EQ(ReadStl(f.stl), Tetrahedron(0.1f));
}

TEST(MeshFolders, PagePathsAreNeverAbsolute) {
  EXPECT_EQ(PageMeshPath("meshes/a.stl"), "meshes/a.stl");
  EXPECT_EQ(PageMeshPath("./meshes//a.stl"), "meshes/a.stl");
  EXPECT_EQ(PageMeshPath("/home/someone/robot/a.stl"), "a.stl");
  EXPECT_EQ(PageMeshPath("../robot/a.stl"), "a.stl");
  EXPECT_EQ(PageMeshPath("sub/../../robot/a.stl"), "a.stl");
}

TEST(MeshFiles, EachFileIsReadOnceAndShared) {
  const std::string dir = Scratch("shared");
  fs::create_directories(dir + "/meshes");
  std::ofstream(dir + "/meshes/tetra.stl", std::ios::binary) << BinaryStl(Tetrahedron(0.1f));
  std::ofstream(dir + "/ascii.stl") << AsciiStl(Tetrahedron(0.2f));
  const std::string model_path = WriteMeshModel(
      dir, "{file: meshes/tetra.stl}, {file: " + dir + "/ascii.stl}", "{file: ./meshes/tetra.stl}, {file: meshes/tetra.stl}");
  const MeshFiles files = ReadMeshFiles(LoadModel(model_path));
  ASSERT_EQ(files.files.size(), 3u);  // "./meshes/tetra.stl" is another spelling, read again
  EXPECT_EQ(files.files[0].path, dir + "/meshes/tetra.stl");
  EXPECT_EQ(files.files[1].path, dir + "/ascii.stl");
  // The page's names: relative to the model's folder, an absolute one by its file name.
  EXPECT_EQ(files.files[0].page_path, "meshes/tetra.stl");
  EXPECT_EQ(files.files[1].page_path, "ascii.stl");
  EXPECT_EQ(files.files[2].page_path, "meshes/tetra.stl");
  EXPECT_EQ(files.files[0].triangles, 4u);
  EXPECT_EQ(ReadStl(files.files[1].stl), Tetrahedron(0.2f));
  EXPECT_EQ(files.file_of, (std::vector<std::vector<int>>{{}, {0, 1}, {2, 0}}));
  EXPECT_EQ(files.bytes_read, 2 * fs::file_size(dir + "/meshes/tetra.stl") + fs::file_size(dir + "/ascii.stl"));
}

TEST(Scene, MeshesOnlyWithMeshFiles) {
  const std::string dir = Scratch("scene");
  fs::create_directories(dir);
  std::ofstream(dir + "/tetra.stl", std::ios::binary) << BinaryStl(Tetrahedron(0.1f));
  const Model model = LoadModel(WriteMeshModel(
      dir, "{file: tetra.stl, position: [0.5, 0.1, 0.9], rpy: [-0.2, 0.7, 2.5], scale: [2, 2, 2]}", ""));
  const nlohmann::json plain = nlohmann::json::parse(BuildScene(model, {}, "model", nullptr));
  EXPECT_FALSE(plain.contains("meshes"));
  for (const auto& body : plain["bodies"]) EXPECT_FALSE(body.contains("meshes"));
  const MeshFiles files = ReadMeshFiles(model);
  const nlohmann::json scene = nlohmann::json::parse(BuildScene(model, {}, "model", nullptr, nullptr, &files));
  ASSERT_EQ(scene["meshes"].size(), 1u);
  EXPECT_EQ(scene["meshes"][0]["triangles"], 4);
  EXPECT_EQ(scene["meshes"][0]["stl_base64"], Base64(WriteBinaryStl(Tetrahedron(0.1f))));
  const nlohmann::json& mesh = scene["bodies"][1]["meshes"][0];
  EXPECT_EQ(mesh["file"], 0);
  EXPECT_EQ(mesh["scale"], nlohmann::json({2.0, 2.0, 2.0}));
  // The body's pose at home composed with the mesh's pose is the file's world pose.
  const Eigen::Matrix3d R_WB = RotationFromRpy(Eigen::Vector3d(0.4, -0.3, 1.1));
  const Eigen::Vector3d p_BM(mesh["position"][0], mesh["position"][1], mesh["position"][2]);
  const Eigen::Quaterniond q_BM(mesh["quaternion"][3], mesh["quaternion"][0], mesh["quaternion"][1], mesh["quaternion"][2]);
  EXPECT_LT((Eigen::Vector3d(0.3, -0.2, 0.8) + R_WB * p_BM - Eigen::Vector3d(0.5, 0.1, 0.9)).norm(), 1e-6);
  EXPECT_LT((R_WB * q_BM.toRotationMatrix() - RotationFromRpy(Eigen::Vector3d(-0.2, 0.7, 2.5))).norm(), 1e-6);
  EXPECT_FALSE(scene["bodies"][0].contains("meshes"));
  EXPECT_FALSE(scene["bodies"][2].contains("meshes"));
}

// The scene of a page: the text of <script id="ccma-scene">.
nlohmann::json SceneOf(const std::string& html_path) {
  const std::string html = ccma::testing::Slurp(html_path);
  const std::string open = "<script type=\"application/json\" id=\"ccma-scene\">";
  const size_t from = html.find(open) + open.size();
  return nlohmann::json::parse(html.substr(from, html.find("</script>", from) - from));
}

TEST(ViewCli, MeshesAreEmbeddedAndSummarised) {
  const std::string dir = Scratch("cli");
  fs::create_directories(dir);
  std::ofstream(dir + "/tetra.stl", std::ios::binary) << BinaryStl(Tetrahedron(0.1f));
  const std::string model = WriteMeshModel(dir, "{file: tetra.stl}", "{file: tetra.stl}");
  const std::string out = Scratch("meshes.html");
  const ToolRun r = RunTool({"view", "--model=" + model, "--meshes", "--out=" + out});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mesh_files"], 1);
  EXPECT_EQ(j["mesh_bytes"], 84 + 4 * 50);
  const nlohmann::json scene = SceneOf(out);
  ASSERT_EQ(scene["meshes"].size(), 1u);
  EXPECT_EQ(scene["meshes"][0]["stl_base64"], Base64(WriteBinaryStl(Tetrahedron(0.1f))));
  EXPECT_EQ(scene["bodies"][1]["meshes"].size(), 1u);
  EXPECT_EQ(scene["bodies"][2]["meshes"].size(), 1u);
  EXPECT_EQ(scene["meshes"][0]["path"], "tetra.stl");
  EXPECT_EQ(ccma::testing::Slurp(out).find(dir), std::string::npos) << "the page names the folder " << dir;
  // Without --meshes: no file is opened (it is gone), no mesh in the page.
  fs::remove(dir + "/tetra.stl");
  const ToolRun plain = RunTool({"view", "--model=" + model, "--out=" + out});
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("mesh_files"));
  const nlohmann::json plain_scene = SceneOf(out);
  EXPECT_FALSE(plain_scene.contains("meshes"));
  for (const auto& body : plain_scene["bodies"]) EXPECT_FALSE(body.contains("meshes"));
}

TEST(ViewCli, MeshOutsideTheModelsFolderExitsTwoUnlessItsFolderIsGiven) {
  const Planted p = PlantOutside("cli_confined");
  const std::string out = p.dir + "/page.html";
  for (const auto& [entry, page_path] : kOutsideEntries) {
    const std::string model = WriteMeshModel(p.model_dir, entry, "{file: inside.stl}");
    const ToolRun r = RunTool({"view", "--model=" + model, "--meshes", "--out=" + out});
    EXPECT_EQ(r.status, 2) << entry << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("ccma view: " + model + ":5: body 'arm': mesh '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("outside the model file's folder"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    const ToolRun allowed =
        RunTool({"view", "--model=" + model, "--meshes", "--mesh_root=" + p.dir + "/nope," + p.outside, "--out=" + out});
    EXPECT_EQ(allowed.status, 2) << allowed.err;  // a root that does not exist
    EXPECT_NE(allowed.err.find("mesh root '" + p.dir + "/nope': not an existing folder"), std::string::npos);
    const ToolRun ok = RunTool({"view", "--model=" + model, "--meshes", "--mesh_root=" + p.outside, "--out=" + out});
    ASSERT_EQ(ok.status, 0) << entry << ": " << ok.err;
    EXPECT_EQ(nlohmann::json::parse(ok.out)["mesh_files"], 2);
    const nlohmann::json scene = SceneOf(out);
    EXPECT_EQ(scene["meshes"][0]["path"], page_path);
    EXPECT_EQ(scene["meshes"][1]["path"], "inside.stl");
    EXPECT_EQ(ccma::testing::Slurp(out).find(p.dir), std::string::npos) << "the page names the folder " << p.dir;
    fs::remove(out);
  }
  const ToolRun lone = RunTool({"view", "--model=" + WriteMeshModel(p.model_dir, "", ""),
                                "--mesh_root=" + p.outside, "--out=" + out});
  EXPECT_EQ(lone.status, 2);
  EXPECT_NE(lone.err.find("--mesh_root goes with --meshes"), std::string::npos) << lone.err;
}

TEST(ViewCli, MeshesFlagChangesNothingForModelsWithoutMeshes) {
  const std::string a = Scratch("plain.html"), b = Scratch("flagged.html");
  for (const char* name : {"4dof_reduced", "stewart_gough_6ups"}) {
    ASSERT_EQ(RunTool({"view", "--model=" + ModelPath(name), "--out=" + a}).status, 0);
    ASSERT_EQ(RunTool({"view", "--model=" + ModelPath(name), "--meshes", "--out=" + b}).status, 0);
    EXPECT_EQ(ccma::testing::Slurp(a), ccma::testing::Slurp(b)) << name;
  }
}

TEST(ViewCli, BadMeshFilesExitTwoNamingModelBodyAndFile) {
  const std::string dir = Scratch("bad");
  fs::create_directories(dir + "/folder.stl");
  std::ofstream(dir + "/text.stl") << "hello, not a mesh\n";
  std::ofstream(dir + "/huge.stl").close();
  fs::resize_file(dir + "/huge.stl", kMaxMeshFileBytes + 1);
  const std::string out = Scratch("bad.html");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{file: nope.stl}", "meshy.yaml:5: body 'arm': mesh 'nope.stl': cannot open the mesh file (no such file)"},
      {"{file: folder.stl}", "meshy.yaml:5: body 'arm': mesh 'folder.stl': not a regular file (a directory)"},
      {"{file: text.stl}", "meshy.yaml:5: body 'arm': mesh 'text.stl': not a valid STL: neither a binary STL"},
      {"{file: huge.stl}", "meshy.yaml:5: body 'arm': mesh 'huge.stl': larger than 16 MiB (the limit for a mesh file)"},
  };
  for (const auto& [entry, expected] : cases) {
    const ToolRun r = RunTool({"view", "--model=" + WriteMeshModel(dir, entry, ""), "--meshes", "--out=" + out});
    EXPECT_EQ(r.status, 2) << entry;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("ccma view: " + dir + "/" + expected), std::string::npos) << r.err << "\nwant: " << expected;
  }
  // On a base, and past the total: five valid files of 16 MiB (zero triangles
  // are finite), the fifth refused before it is parsed.
  for (int k = 0; k < 5; ++k) {
    const std::string name = dir + "/big" + std::to_string(k) + ".stl";
    const std::uint32_t count = (kMaxMeshFileBytes - 84) / 50;
    std::string header(80, ' ');
    for (int b = 0; b < 4; ++b) header.push_back(static_cast<char>(count >> (8 * b)));
    std::ofstream(name, std::ios::binary) << header;
    fs::resize_file(name, 84 + 50 * std::uintmax_t{count});
  }
  const ToolRun r = RunTool({"view", "--meshes", "--out=" + out, "--model=" + WriteMeshModel(dir, "",
      "{file: big0.stl}, {file: big1.stl}, {file: big2.stl}, {file: big3.stl}, {file: big4.stl}")});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("meshy.yaml:7: body 'base0': mesh 'big4.stl': the mesh files add up to more than 64 MiB"),
            std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace ccma::viewer
