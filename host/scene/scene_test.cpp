#include "scene/scene.h"

#include <atomic>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "camera/pinhole_camera.h"
#include "camera/thin_lens_camera.h"
#include "json/input_file.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace nlohmann::literals;

const char* kLampCsv =
    "# test lamp, relative units\n"
    "wavelength_nm,value\n"
    "380,0.1\n"
    "480,0.6\n"
    "580,1.0\n"
    "680,0.7\n"
    "780,0.2\n";

// The example from the format description.
json exampleScene() {
  return R"({
    "spectrum": { "min_nm": 360, "max_nm": 830, "bins": 94 },
    "camera": {
      "position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0],
      "sensor": { "width_m": 0.036, "height_m": 0.024, "pixels": [360, 240] },
      "pinhole": { "distance_m": 0.05, "radius_m": 0.0005 }
    },
    "lights": [
      { "type": "point", "position": [0, 0, 2], "power_w": 10, "spd": "D65" },
      { "type": "spot",  "position": [0, 1, 2], "direction": [0, -1, -1], "cone_deg": 20,
        "power_w": 5, "spd": { "blackbody_k": 2700 } },
      { "type": "disk",  "center": [0, 0, 3], "normal": [0, 0, -1], "radius_m": 0.1,
        "power_w": 5, "spd": { "csv": "lamp.csv" } },
      { "type": "rect",  "center": [1, 0, 3], "normal": [0, 0, -1], "size_m": [0.2, 0.1],
        "power_w": 5, "spd": "F11" },
      { "type": "laser", "origin": [0, 0, 1], "direction": [0, 0, -1], "radius_m": 0.001,
        "power_w": 0.005, "spd": { "line_nm": 532 } }
    ],
    "render": { "beams": 100000000, "seed": 1 }
  })"_json;
}

json minimalScene() {
  return R"({
    "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1] },
    "lights": [ { "type": "point", "position": [0, 0, 2], "power_w": 1, "spd": "D65" } ]
  })"_json;
}

class SceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           ("spectrace_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("lamp.csv", kLampCsv);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path write(const fs::path& name, const std::string& text) {
    fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << text;
    return p;
  }

  Scene load(const json& j, const std::string& name = "scene.json") { return loadScene(write(name, j.dump(2))); }

  // Loads `text` and returns the SceneError message ("" if it loaded).
  std::string errorOf(const std::string& text, const std::string& name = "bad.json") {
    fs::path p = write(name, text);
    try {
      loadScene(p);
    } catch (const SceneError& e) {
      lastFile_ = p.string();
      return e.what();
    }
    return "";
  }
  std::string errorOf(const json& j) { return errorOf(j.dump(2)); }

  // The message must be "<file>: <pointer>: ..." and contain every phrase.
  void expectError(const json& j, const std::string& pointer, std::vector<std::string> phrases) {
    expectErrorText(j.dump(2), pointer, std::move(phrases));
  }
  void expectErrorText(const std::string& text, const std::string& pointer, std::vector<std::string> phrases) {
    std::string msg = errorOf(text);
    ASSERT_FALSE(msg.empty()) << "expected an error at " << pointer << " for:\n" << text;
    EXPECT_EQ(msg.rfind(lastFile_ + ": " + pointer + ": ", 0), 0u) << "message: " << msg;
    for (const auto& phrase : phrases) EXPECT_NE(msg.find(phrase), std::string::npos) << "missing '" << phrase << "' in: " << msg;
  }
  // Sets j[pointer] = value and expects an error at `errorPointer`.
  void expectMutationError(const std::string& pointer, const json& value, const std::string& errorPointer,
                           std::vector<std::string> phrases, json base = exampleScene()) {
    SCOPED_TRACE(pointer + " = " + value.dump());
    base[json::json_pointer(pointer)] = value;
    expectError(base, errorPointer, std::move(phrases));
  }
  void expectRemovalError(const std::string& pointer, const std::string& errorPointer,
                          std::vector<std::string> phrases, json base = exampleScene()) {
    SCOPED_TRACE("remove " + pointer);
    json::json_pointer ptr(pointer);
    base[ptr.parent_pointer()].erase(ptr.back());
    expectError(base, errorPointer, std::move(phrases));
  }

  fs::path dir_;
  std::string lastFile_;
};

void expectVec(const glm::dvec3& v, double x, double y, double z) {
  EXPECT_NEAR(v.x, x, 1e-12);
  EXPECT_NEAR(v.y, y, 1e-12);
  EXPECT_NEAR(v.z, z, 1e-12);
}

TEST_F(SceneTest, ExampleParsesWithTheRightValues) {
  std::string text = exampleScene().dump(2);
  fs::path file = write("example.json", text);
  Scene s = loadScene(file);

  EXPECT_EQ(s.spectrum.minNm, 360.0);
  EXPECT_EQ(s.spectrum.maxNm, 830.0);
  EXPECT_EQ(s.spectrum.bins, 94);
  expectVec(s.camera.position, 0, 0, 0);
  expectVec(s.camera.lookAt, 0, 0, 1);
  expectVec(s.camera.up, 0, 1, 0);
  EXPECT_EQ(s.camera.sensorWidthM, 0.036);
  EXPECT_EQ(s.camera.sensorHeightM, 0.024);
  EXPECT_EQ(s.camera.pixelsX, 360);
  EXPECT_EQ(s.camera.pixelsY, 240);
  ASSERT_NE(pinholeOf(s.camera), nullptr);
  EXPECT_EQ(pinholeOf(s.camera)->distanceM, 0.05);
  EXPECT_EQ(pinholeOf(s.camera)->radiusM, 0.0005);
  EXPECT_EQ(s.camera.exposureS, 1.0);
  EXPECT_EQ(s.render.beams, 100000000u);
  EXPECT_EQ(s.render.seed, 1u);
  EXPECT_FALSE(s.outputSpectral);
  EXPECT_EQ(s.observer, "CIE1931_2");
  EXPECT_EQ(s.sourcePath, file);
  EXPECT_EQ(s.sourceSha256, sceneSha256Hex(text));

  ASSERT_EQ(s.lights.size(), 5u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_EQ(point.label, "/lights/0");
  expectVec(point.position, 0, 0, 2);
  EXPECT_EQ(point.powerW, 10.0);
  EXPECT_EQ(point.spdLabel, "D65");
  EXPECT_GT(point.spd.lambdaNm.size(), 2u);
  EXPECT_TRUE(point.name.empty());

  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  expectVec(spot.position, 0, 1, 2);
  expectVec(spot.direction, 0, -std::sqrt(0.5), -std::sqrt(0.5));
  EXPECT_EQ(spot.coneHalfAngleDeg, 20.0);
  EXPECT_EQ(spot.spdLabel, "blackbody 2700 K");
  EXPECT_GE(spot.spd.lambdaNm.front(), 360.0 - 1e-9);
  EXPECT_LE(spot.spd.lambdaNm.back(), 830.0 + 1e-9);
  EXPECT_NEAR(glm::dot(spot.uAxis, spot.direction), 0.0, 1e-12);

  const Light& disk = s.lights[2];
  EXPECT_EQ(disk.type, LightType::Disk);
  EXPECT_EQ(disk.label, "/lights/2");
  expectVec(disk.position, 0, 0, 3);
  expectVec(disk.direction, 0, 0, -1);
  EXPECT_EQ(disk.radiusM, 0.1);
  EXPECT_EQ(disk.spdLabel, "csv lamp.csv");
  ASSERT_EQ(disk.spd.lambdaNm.size(), 5u);
  EXPECT_EQ(disk.spd.lambdaNm[2], 580.0);
  EXPECT_EQ(disk.spd.value[2], 1.0);

  const Light& rect = s.lights[3];
  EXPECT_EQ(rect.type, LightType::Rect);
  expectVec(rect.position, 1, 0, 3);
  expectVec(rect.direction, 0, 0, -1);
  EXPECT_EQ(rect.sizeM.x, 0.2);
  EXPECT_EQ(rect.sizeM.y, 0.1);
  expectVec(rect.uAxis, -1, 0, 0);  // cross(world Y, normal)
  EXPECT_EQ(rect.spdLabel, "F11");

  const Light& laser = s.lights[4];
  EXPECT_EQ(laser.type, LightType::Laser);
  expectVec(laser.position, 0, 0, 1);
  expectVec(laser.direction, 0, 0, -1);
  EXPECT_EQ(laser.radiusM, 0.001);
  EXPECT_EQ(laser.powerW, 0.005);
  EXPECT_EQ(laser.spdLabel, "line 532 nm");
  EXPECT_TRUE(laser.spd.isLine());
  EXPECT_EQ(laser.spd.lambdaNm[0], 532.0);
}

TEST_F(SceneTest, DefaultsForOptionalSections) {
  Scene s = load(minimalScene());
  EXPECT_EQ(s.spectrum.minNm, 360.0);
  EXPECT_EQ(s.spectrum.maxNm, 830.0);
  EXPECT_EQ(s.spectrum.bins, 94);
  EXPECT_EQ(s.render.beams, 10'000'000u);
  EXPECT_EQ(s.render.seed, 1u);
  EXPECT_EQ(s.observer, "CIE1931_2");
  expectVec(s.camera.up, 0, 1, 0);
  EXPECT_EQ(s.camera.sensorWidthM, 0.036);
  EXPECT_EQ(s.camera.sensorHeightM, 0.024);
  EXPECT_EQ(s.camera.pixelsX, 360);
  EXPECT_EQ(s.camera.pixelsY, 240);
  EXPECT_EQ(pinholeOf(s.camera), nullptr);
  EXPECT_EQ(s.camera.exposureS, 1.0);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].label, "/lights/0");
}

TEST_F(SceneTest, Extensions) {
  json j = exampleScene();
  j["observer"] = "CIE1964_10";
  j["camera"]["exposure_s"] = 0.25;
  j["camera"]["up"] = {0, 5, 0};
  j["lights"][0]["name"] = "bulb";
  j["lights"][3]["u_axis"] = {1, 0, 1};      // orthogonalised against the normal (0, 0, -1)
  j["lights"][2]["normal"] = {0, -3, 0.1};  // |n.y| > 0.9: default tangent from world X
  j["lights"][4]["spd"] = {{"line_nm", 632.8}, {"fwhm_nm", 2}};
  j["lights"][1]["spd"] = R"({"table": [[400, 0.1], [500, 1.0], [600, 0.5], [700, 0.2], [800, 0]]})"_json;
  j["lights"][0]["spd"] = R"({"lambda_nm": [400, 550, 700], "value": [1, 2, 1]})"_json;
  j["render"] = {{"beams", 18446744073709551615ull}, {"seed", 0}};
  Scene s = load(j);
  EXPECT_EQ(s.observer, "CIE1964_10");
  EXPECT_EQ(s.camera.exposureS, 0.25);
  expectVec(s.camera.up, 0, 1, 0);
  EXPECT_EQ(s.lights[0].name, "bulb");
  EXPECT_EQ(s.lights[0].label, "/lights/0");
  EXPECT_EQ(s.lights[0].spdLabel, "inline table (3 points)");
  EXPECT_EQ(s.lights[1].spdLabel, "inline table (5 points)");
  ASSERT_EQ(s.lights[1].spd.lambdaNm.size(), 5u);
  EXPECT_EQ(s.lights[1].spd.value[1], 1.0);
  expectVec(s.lights[3].uAxis, 1, 0, 0);
  const Light& disk = s.lights[2];
  EXPECT_NEAR(glm::length(disk.direction), 1.0, 1e-15);
  glm::dvec3 expected = glm::normalize(glm::cross(glm::dvec3(1, 0, 0), disk.direction));
  expectVec(disk.uAxis, expected.x, expected.y, expected.z);
  EXPECT_EQ(s.lights[4].spdLabel, "line 632.8 nm (FWHM 2 nm)");
  EXPECT_FALSE(s.lights[4].spd.isLine());
  EXPECT_EQ(s.render.beams, 18446744073709551615ull);
  EXPECT_EQ(s.render.seed, 0u);
}

TEST_F(SceneTest, RectDefaultTangentRule) {
  json j = minimalScene();
  j["lights"][0] = R"({"type": "rect", "center": [0, 0, 2], "normal": [0, 0, 1], "size_m": [1, 2],
                       "power_w": 1, "spd": "A"})"_json;
  expectVec(load(j).lights[0].uAxis, 1, 0, 0);
  j["lights"][0]["normal"] = {0, -1, 0};  // world Y is unusable: pick world X
  expectVec(load(j).lights[0].uAxis, 0, 0, -1);
}

TEST_F(SceneTest, IntegralFloatsAndCommentsAreAccepted) {
  Scene s = loadScene(write("c.json", R"({
    // comments are tolerated
    "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1], "sensor": { "pixels": [64.0, 48] } },
    /* block comment */
    "lights": [ { "type": "point", "position": [0, 0, 2], "power_w": 1, "spd": "D65" } ],
    "render": { "beams": 1e8 }
  })"));
  EXPECT_EQ(s.render.beams, 100000000u);
  EXPECT_EQ(s.camera.pixelsX, 64);
}

TEST_F(SceneTest, ZeroPowerLightIsKept) {
  json j = exampleScene();
  j["lights"][1]["power_w"] = 0;
  Scene s = load(j);
  ASSERT_EQ(s.lights.size(), 5u);
  EXPECT_EQ(s.lights[1].powerW, 0.0);
}

TEST_F(SceneTest, CsvWithNamedColumn) {
  write("multi.csv", "# two lamps\nwavelength_nm,cool,warm\n400,1.0,0.2\n550,0.8,0.7\n700,0.3,1.0\n");
  json j = exampleScene();
  j["lights"][2]["spd"] = {{"csv", "multi.csv"}, {"column", "warm"}};
  Scene s = load(j);
  EXPECT_EQ(s.lights[2].spdLabel, "csv multi.csv column warm");
  ASSERT_EQ(s.lights[2].spd.value.size(), 3u);
  EXPECT_EQ(s.lights[2].spd.value[2], 1.0);
}

TEST_F(SceneTest, CsvPathResolvesAgainstTheSceneFolderNotTheCwd) {
  write("sub/spd/only_here.csv", kLampCsv);
  json j = exampleScene();
  j["lights"][2]["spd"] = {{"csv", "spd/only_here.csv"}};
  fs::path scene = write("sub/scene.json", j.dump(2));
  fs::path old = fs::current_path();
  fs::create_directories(dir_ / "elsewhere");
  fs::current_path(dir_ / "elsewhere");
  Scene s;
  std::string error;
  try {
    s = loadScene(scene);                      // absolute scene path
    s = loadScene(fs::path("../sub/scene.json"));  // relative scene path
  } catch (const std::exception& e) {
    error = e.what();
  }
  fs::current_path(old);
  ASSERT_EQ(error, "");
  EXPECT_EQ(s.lights[2].spd.lambdaNm.size(), 5u);

  // An absolute CSV path is used as is.
  j["lights"][2]["spd"] = {{"csv", (dir_ / "lamp.csv").string()}};
  EXPECT_EQ(load(j, "sub/abs.json").lights[2].spd.lambdaNm.size(), 5u);
}

// A scene parsed under BundledInputFiles (as a render state develops it)
// reads the files it names from the bundle and never the disk, with the
// digests of a load from disk; a file the bundle lacks is refused by name.
TEST_F(SceneTest, BundledInputFilesServeTheCsvInPlaceOfTheDisk) {
  const std::string text = exampleScene().dump(2);
  const fs::path scenePath = write("scene.json", text);
  const Scene fromDisk = loadScene(scenePath);
  InputFileBundle files;
  for (const fs::path& file : referencedFiles(fromDisk)) files[file.string()] = readInputFile(file, "file");
  ASSERT_EQ(files.count((dir_ / "lamp.csv").string()), 1u);
  fs::remove(dir_ / "lamp.csv");
  Scene bundled;
  {
    const BundledInputFiles served(files, "the test's bundle");
    bundled = parseScene(text, scenePath);
  }
  EXPECT_EQ(bundled.sourceText, text);
  EXPECT_EQ(bundled.sourceSha256, fromDisk.sourceSha256);
  EXPECT_EQ(bundled.referencedFilesSha256, fromDisk.referencedFilesSha256);
  EXPECT_EQ(bundled.lights[2].spd.lambdaNm, fromDisk.lights[2].spd.lambdaNm);
  {
    files[(dir_ / "lamp.csv").string()] = "wavelength_nm,value\n400,1\n700,2\n";
    const BundledInputFiles served(files, "the test's bundle");
    EXPECT_EQ(parseScene(text, scenePath).lights[2].spd.lambdaNm.size(), 2u) << "the bundle's bytes, not the disk's";
  }
  write("lamp.csv", kLampCsv);  // on disk again, but not in the bundle
  const InputFileBundle none;
  const BundledInputFiles served(none, "the test's bundle");
  try {
    parseScene(text, scenePath);
    ADD_FAILURE() << "a CSV missing from the bundle was read";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "lamp.csv").string() + ": SPD file not in the test's bundle"),
              std::string::npos)
        << e.what();
  }
}

// A mesh's digest in the scene's fingerprint is of the bytes its loader
// read (taken on another thread while the mesh was checked), so the
// fingerprint is the same as reading every file again while they are
// unchanged, and stays that of what was read once the file changes.
TEST_F(SceneTest, MeshDigestIsOfTheBytesRead) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  write("tetra.obj", obj);
  json j = exampleScene();
  j["objects"] = json::array(
      {{{"type", "mesh"}, {"file", "tetra.obj"}, {"material", {{"type", "diffuse"}, {"reflectance", 0.5}}}}});
  const Scene s = load(j);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].shape.meshSha256, sceneSha256Hex(obj));
  EXPECT_EQ(s.referencedFilesSha256, referencedFilesSha256(s));
  write("tetra.obj", obj + "# changed\n");
  EXPECT_NE(s.referencedFilesSha256, referencedFilesSha256(s)) << "the files are read again";
  EXPECT_EQ(s.objects[0].shape.meshSha256, sceneSha256Hex(obj));
}

TEST_F(SceneTest, Sha256OfKnownStrings) {
  EXPECT_EQ(sceneSha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sceneSha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  std::string text = minimalScene().dump();
  EXPECT_EQ(parseScene(text, dir_ / "mem.json").sourceSha256, sceneSha256Hex(text));
  // A file's digest is of its exact bytes: whitespace changes it.
  EXPECT_NE(load(minimalScene(), "a.json").sourceSha256, loadScene(write("b.json", minimalScene().dump(4))).sourceSha256);
}

// The thin lens replaces the pinhole: its values, the lens distance from
// 1/f = 1/d + 1/s, and its errors, each naming the field.
TEST_F(SceneTest, ThinLensParsesAndItsErrorsNameTheField) {
  json j = exampleScene();
  j["camera"].erase("pinhole");
  j["camera"]["thin_lens"] = {{"focal_length_m", 0.05}, {"aperture_radius_m", 0.01}, {"focus_distance_m", 2.0}};
  const Scene s = load(j);
  EXPECT_EQ(pinholeOf(s.camera), nullptr);
  const ThinLens* lens = thinLensOf(s.camera);
  ASSERT_NE(lens, nullptr);
  EXPECT_EQ(lens->focalLengthM, 0.05);
  EXPECT_EQ(lens->apertureRadiusM, 0.01);
  EXPECT_EQ(lens->focusDistanceM, 2.0);
  EXPECT_NEAR(1.0 / lens->focusDistanceM + 1.0 / lens->lensDistanceM(), 1.0 / lens->focalLengthM, 1e-12);
  EXPECT_EQ(s.camera.model->frontZ(), lens->lensDistanceM());
  EXPECT_TRUE(s.camera.model->imageFlipped());

  expectMutationError("/camera/thin_lens/focus_distance_m", 0.05, "/camera/thin_lens/focus_distance_m",
                      {"must exceed focal_length_m", "no real image", "(got 0.05)"}, j);
  expectMutationError("/camera/thin_lens/focus_distance_m", 0.02, "/camera/thin_lens/focus_distance_m",
                      {"must exceed focal_length_m"}, j);
  expectMutationError("/camera/thin_lens/aperture_radius_m", -1, "/camera/thin_lens/aperture_radius_m", {"> 0"}, j);
  expectMutationError("/camera/thin_lens/focal_length_m", "long", "/camera/thin_lens/focal_length_m", {"> 0"}, j);
  expectMutationError("/camera/thin_lens/f_number", 2, "/camera/thin_lens/f_number", {"unknown key"}, j);
  expectRemovalError("/camera/thin_lens/aperture_radius_m", "/camera/thin_lens/aperture_radius_m",
                     {"missing required field"}, j);
  // One model before the sensor.
  j["camera"]["pinhole"] = {{"distance_m", 0.05}, {"radius_m", 0.001}};
  expectError(j, "/camera/thin_lens", {"not both", "pinhole", "thin_lens"});
}

TEST_F(SceneTest, ExactMessageFormat) {
  json j = exampleScene();
  j["lights"][2]["power_w"] = -1;
  std::string msg = errorOf(j);
  EXPECT_EQ(msg, lastFile_ + ": /lights/2/power_w: must be a finite number >= 0 (got -1)");
}

TEST_F(SceneTest, FileLevelErrors) {
  fs::path missing = dir_ / "nope.json";
  try {
    loadScene(missing);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              missing.string() + ": scene file not found (looked for " + fs::absolute(missing).string() + ")");
  }
  // A relative path: as given, then where it was looked for (the working folder).
  try {
    loadScene("no_such_scene.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "no_such_scene.json: scene file not found (looked for " +
                                         (fs::current_path() / "no_such_scene.json").string() + ")");
  }
  try {
    loadScene(dir_);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
  expectErrorText("{\n  \"camera\": {\n    \"position\": [0, 0, 0],\n  }\n}", "/",
                  {"invalid JSON", "line 4", "column", "byte"});
  expectErrorText("", "/", {"invalid JSON"});
  expectErrorText("[1, 2, 3]", "/", {"must be a JSON object", "[1, 2, 3]"});
  expectErrorText("{\"render\": {\"beams\": 1e400}}", "/", {"invalid JSON", "overflow"});
  expectErrorText(R"({"camera": {"position": [0,0,0], "position": [1,1,1], "look_at": [0,0,1]}})",
                  "/camera/position", {"duplicate key", "\"position\""});
  expectErrorText(R"({"lights": [{"type": "point"}, {"type": "point", "type": "spot"}]})", "/lights/1/type",
                  {"duplicate key"});
}

TEST_F(SceneTest, OutputSpectral) {
  json j = exampleScene();
  j["output"] = {{"spectral", true}};
  EXPECT_TRUE(load(j).outputSpectral);
  j["output"] = {{"spectral", false}};
  EXPECT_FALSE(load(j).outputSpectral);
  j["output"] = json::object();
  EXPECT_FALSE(load(j).outputSpectral);
  expectMutationError("/output", 1, "/output", {"output"});
  expectMutationError("/output", {{"spectral", 1}}, "/output/spectral", {"true or false", "got"});
  expectMutationError("/output", {{"spectral", "yes"}}, "/output/spectral", {"true or false"});
  expectMutationError("/output", {{"spectra", true}}, "/output/spectra", {"unknown key", "spectral"});
}

TEST_F(SceneTest, UnknownKeysAnywhere) {
  expectMutationError("/lightz", 1, "/lightz", {"unknown key \"lightz\"", "allowed keys", "lights", "camera"});
  expectMutationError("/camera/positon", json::array({0, 0, 0}), "/camera/positon",
                      {"unknown key", "did you mean \"position\"", "look_at"});
  expectMutationError("/camera/sensor/pixel", 1, "/camera/sensor/pixel", {"unknown key", "width_m", "pixels"});
  expectMutationError("/camera/pinhole/radius", 1, "/camera/pinhole/radius", {"unknown key", "radius_m"});
  expectMutationError("/spectrum/bin", 1, "/spectrum/bin", {"unknown key", "bins"});
  expectMutationError("/render/beam", 1, "/render/beam", {"unknown key", "beams", "seed"});
  expectMutationError("/lights/0/power", 1, "/lights/0/power", {"unknown key", "power_w"});
  // A key that belongs to another light type.
  expectMutationError("/lights/0/radius_m", 1, "/lights/0/radius_m", {"unknown key", "point light", "position"});
  expectMutationError("/lights/1/spd/kelvin", 1, "/lights/1/spd/kelvin", {"unknown key", "blackbody_k"});
  expectMutationError("/lights/2/spd/colum", "x", "/lights/2/spd/colum", {"unknown key", "did you mean \"column\""});
  expectMutationError("/lights/1/spd", {{"blackbdy_k", 2700}}, "/lights/1/spd/blackbdy_k",
                      {"unknown key", "blackbody_k"});
  expectRemovalError("/lights/0/type", "/lights/0/type", {"missing required field", "point, spot"});
  expectMutationError("/lights/0/typ", "point", "/lights/0/typ", {"unknown key", "did you mean \"type\""},
                      [] { auto j = exampleScene(); j["lights"][0].erase("type"); return j; }());
}

TEST_F(SceneTest, MissingFieldsAndWrongTypes) {
  expectRemovalError("/camera", "/camera", {"missing required field"});
  expectRemovalError("/lights", "/lights", {"missing required field"});
  expectRemovalError("/camera/look_at", "/camera/look_at", {"missing required field"});
  expectRemovalError("/camera/pinhole/radius_m", "/camera/pinhole/radius_m", {"missing required field"});
  expectRemovalError("/lights/0/power_w", "/lights/0/power_w", {"missing required field"});
  expectRemovalError("/lights/0/spd", "/lights/0/spd", {"missing required field"});
  expectRemovalError("/lights/1/cone_deg", "/lights/1/cone_deg", {"missing required field"});
  expectRemovalError("/lights/3/size_m", "/lights/3/size_m", {"missing required field"});
  expectRemovalError("/lights/4/origin", "/lights/4/origin", {"missing required field"});
  expectMutationError("/camera", json::array(), "/camera", {"must be an object"});
  expectMutationError("/camera/position", "abc", "/camera/position", {"array of 3 finite numbers", "\"abc\""});
  expectMutationError("/camera/position", {1, 2}, "/camera/position", {"array of 3 finite numbers"});
  expectMutationError("/camera/position", {1, 2, 3, 4}, "/camera/position", {"array of 3 finite numbers"});
  expectMutationError("/camera/position", json::parse(R"([1, "x", 3])"), "/camera/position/1",
                      {"finite number", "\"x\""});
  expectMutationError("/camera/position", json::parse("[1, null, 3]"), "/camera/position/1", {"finite number", "null"});
  expectMutationError("/camera/position", json::parse("[true, 0, 3]"), "/camera/position/0", {"finite number", "true"});
  json far = exampleScene();
  far["lights"][0]["position"] = json::parse("[1, 2, 1e11]");  // far but within the limit
  EXPECT_EQ(load(far).lights[0].position.z, 1e11);
}

TEST_F(SceneTest, SpectrumRangeErrors) {
  expectMutationError("/spectrum/bins", 0, "/spectrum/bins", {"integer in 1..100000", "got 0"});
  expectMutationError("/spectrum/bins", 100001, "/spectrum/bins", {"integer in 1..100000"});
  expectMutationError("/spectrum/bins", 2.5, "/spectrum/bins", {"integer", "2.5"});
  expectMutationError("/spectrum/bins", "94", "/spectrum/bins", {"integer", "\"94\""});
  expectMutationError("/spectrum/min_nm", -1, "/spectrum/min_nm", {"> 0", "got -1"});
  expectMutationError("/spectrum/min_nm", 0, "/spectrum/min_nm", {"> 0"});
  // A range reaching down to 1e-300 nm is refused for what it is, not by
  // a blackbody whose radiance underflows there.
  expectMutationError("/spectrum/min_nm", 1e-300, "/spectrum/min_nm", {"at least 1 nm"});
  expectMutationError("/spectrum/max_nm", 360, "/spectrum/max_nm", {"min_nm", "less than max_nm"});
  expectMutationError("/spectrum/max_nm", 300, "/spectrum/max_nm", {"less than max_nm"});
  expectMutationError("/spectrum", 5, "/spectrum", {"must be an object"});
  expectMutationError("/observer", "CIE1931", "/observer", {"unknown observer", "CIE1964_10"});
}

TEST_F(SceneTest, CameraErrors) {
  expectMutationError("/camera/look_at", {0, 0, 0}, "/camera/look_at", {"zero-length view direction"});
  expectMutationError("/camera/up", {0, 0, 2}, "/camera/up", {"parallel to the view direction"});
  expectMutationError("/camera/up", {0, 1e-12, -1}, "/camera/up", {"parallel"});
  expectMutationError("/camera/up", {0, 0, 0}, "/camera/up", {"zero-length"});
  expectMutationError("/camera/sensor/width_m", 0, "/camera/sensor/width_m", {"> 0", "got 0"});
  expectMutationError("/camera/sensor/height_m", -0.024, "/camera/sensor/height_m", {"> 0"});
  expectMutationError("/camera/sensor/pixels", {0, 240}, "/camera/sensor/pixels/0", {"integer in 1..65535"});
  expectMutationError("/camera/sensor/pixels", {360, 65536}, "/camera/sensor/pixels/1", {"integer in 1..65535"});
  expectMutationError("/camera/sensor/pixels", {360.5, 240}, "/camera/sensor/pixels/0", {"integer", "360.5"});
  expectMutationError("/camera/sensor/pixels", {-360, 240}, "/camera/sensor/pixels/0", {"integer"});
  expectMutationError("/camera/sensor/pixels", {360}, "/camera/sensor/pixels", {"2 positive integers"});
  expectMutationError("/camera/sensor/pixels", {65535, 65535}, "/camera/sensor/pixels", {"too many pixels"});
  expectMutationError("/camera/pinhole/distance_m", 0, "/camera/pinhole/distance_m", {"> 0"});
  expectMutationError("/camera/pinhole/radius_m", 0, "/camera/pinhole/radius_m", {"> 0"});
  expectMutationError("/camera/pinhole/radius_m", "small", "/camera/pinhole/radius_m", {"> 0", "\"small\""});
  expectMutationError("/camera/exposure_s", 0, "/camera/exposure_s", {"> 0"});
}

TEST_F(SceneTest, LightErrors) {
  expectMutationError("/lights", json::array(), "/lights", {"non-empty array"});
  expectMutationError("/lights", json::object(), "/lights", {"non-empty array"});
  expectMutationError("/lights/0", 5, "/lights/0", {"must be an object"});
  expectMutationError("/lights/0/type", "area", "/lights/0/type",
                      {"unknown light type \"area\"", "point, spot, disk, rect, laser"});
  expectMutationError("/lights/0/type", 3, "/lights/0/type", {"must be a string"});
  expectMutationError("/lights/1/direction", {0, 0, 0}, "/lights/1/direction", {"zero-length"});
  expectMutationError("/lights/2/normal", {0, 0, 0}, "/lights/2/normal", {"zero-length"});
  expectMutationError("/lights/3/normal", {0, 0, 0}, "/lights/3/normal", {"zero-length"});
  expectMutationError("/lights/4/direction", {0, 0, 0}, "/lights/4/direction", {"zero-length"});
  expectMutationError("/lights/1/cone_deg", 0, "/lights/1/cone_deg", {"> 0 and <= 180"});
  expectMutationError("/lights/1/cone_deg", 180.5, "/lights/1/cone_deg", {"<= 180", "180.5"});
  expectMutationError("/lights/1/cone_deg", -5, "/lights/1/cone_deg", {"> 0"});
  expectMutationError("/lights/2/radius_m", 0, "/lights/2/radius_m", {"> 0"});
  expectMutationError("/lights/4/radius_m", -0.001, "/lights/4/radius_m", {"> 0"});
  expectMutationError("/lights/3/size_m", {0, 0.1}, "/lights/3/size_m/0", {"> 0", "non-zero area"});
  expectMutationError("/lights/3/size_m", {0.2, 0}, "/lights/3/size_m/1", {"non-zero area"});
  expectMutationError("/lights/3/size_m", {0.2}, "/lights/3/size_m", {"2 numbers"});
  expectMutationError("/lights/3/size_m", {1e-200, 1e-200}, "/lights/3/size_m", {"area"});
  expectMutationError("/lights/3/u_axis", {0, 0, 5}, "/lights/3/u_axis", {"parallel to the normal"});
  expectMutationError("/lights/3/u_axis", {0, 0, 0}, "/lights/3/u_axis", {"zero-length"});
  expectMutationError("/lights/2/power_w", -1, "/lights/2/power_w", {"finite number >= 0", "got -1"});
  expectMutationError("/lights/2/power_w", "5", "/lights/2/power_w", {"finite number >= 0", "\"5\""});
  expectMutationError("/lights/0/name", 7, "/lights/0/name", {"must be a string"});
  // Messages inside a named light also name it.
  json named = exampleScene();
  named["lights"][1]["name"] = "desk lamp";
  expectMutationError("/lights/1/cone_deg", 0, "/lights/1/cone_deg", {"(light \"desk lamp\")"}, named);
  // All powers zero.
  json dark = exampleScene();
  for (auto& l : dark["lights"]) l["power_w"] = 0;
  expectError(dark, "/lights", {"no light emits power"});
}

TEST_F(SceneTest, SpdErrors) {
  expectMutationError("/lights/0/spd", "D66", "/lights/0/spd", {"unknown CIE illuminant \"D66\"", "D65", "F11"});
  expectMutationError("/lights/0/spd", "d65", "/lights/0/spd", {"did you mean \"D65\""});
  expectMutationError("/lights/0/spd", 42, "/lights/0/spd", {"CIE illuminant name", "blackbody_k", "got 42"});
  expectMutationError("/lights/0/spd", json::object(), "/lights/0/spd", {"blackbody_k", "csv", "line_nm"});
  expectMutationError("/lights/0/spd", {{"blackbody_k", 2700}, {"line_nm", 532}}, "/lights/0/spd",
                      {"ambiguous", "blackbody_k", "line_nm"});
  expectMutationError("/lights/1/spd/blackbody_k", 0, "/lights/1/spd/blackbody_k", {"> 0"});
  expectMutationError("/lights/1/spd/blackbody_k", "warm", "/lights/1/spd/blackbody_k", {"> 0", "\"warm\""});
  expectMutationError("/lights/2/spd/csv", "missing.csv", "/lights/2/spd/csv", {"not found", "missing.csv"});
  expectMutationError("/lights/2/spd/csv", "", "/lights/2/spd/csv", {"non-empty string"});
  write("bad.csv", "wavelength_nm,value\n400,1\n390,2\n");
  expectMutationError("/lights/2/spd/csv", "bad.csv", "/lights/2/spd/csv", {"increasing"});
  write("two.csv", "wavelength_nm,a,b\n400,1,2\n500,2,3\n");
  expectMutationError("/lights/2/spd/csv", "two.csv", "/lights/2/spd/csv", {"column"});
  // SpdError from spd.h: prefixed with the pointer of the spd field.
  expectMutationError("/lights/0/spd", json::parse(R"({"table": [[500, 1], [400, 1]]})"), "/lights/0/spd/table",
                      {"increasing"});
  expectMutationError("/lights/0/spd", json::parse(R"({"table": [[400, 1], [500, -1]]})"), "/lights/0/spd/table",
                      {"negative"});
  expectMutationError("/lights/0/spd", json::parse(R"({"table": [[400, 1], [500]]})"), "/lights/0/spd/table/1",
                      {"[wavelength_nm, value] pair"});
  expectMutationError("/lights/0/spd", json::parse(R"({"table": [[400, 1], [500, "x"]]})"),
                      "/lights/0/spd/table/1/1", {"finite number"});
  expectMutationError("/lights/0/spd", json::parse(R"({"table": []})"), "/lights/0/spd/table", {"non-empty"});
  expectMutationError("/lights/0/spd", json::parse(R"({"lambda_nm": [400, 500], "value": [1]})"),
                      "/lights/0/spd/value", {"same length"});
  expectMutationError("/lights/0/spd", json::parse(R"({"value": [1, 2]})"), "/lights/0/spd/lambda_nm",
                      {"missing required field"});
  expectMutationError("/lights/0/spd", json::parse(R"({"lambda_nm": [400, 500], "value": [0, 0]})"),
                      "/lights/0/spd", {"no power"});
  expectMutationError("/lights/4/spd/line_nm", -532, "/lights/4/spd/line_nm", {"> 0"});
  expectMutationError("/lights/4/spd/fwhm_nm", 0, "/lights/4/spd/fwhm_nm", {"> 0"});
  expectMutationError("/lights/4/spd/line_nm", 1064, "/lights/4/spd", {"emits nothing inside", "360-830 nm"});
  expectMutationError("/lights/0/spd", json::parse(R"({"table": [[900, 1], [1000, 1]]})"), "/lights/0/spd",
                      {"emits nothing inside"});
}

TEST_F(SceneTest, RenderErrors) {
  expectMutationError("/render/beams", -1, "/render/beams", {"integer in 1..18446744073709551615", "got -1"});
  expectMutationError("/render/beams", 0, "/render/beams", {"integer in 1.."});
  expectMutationError("/render/beams", 1.5, "/render/beams", {"integer", "1.5"});
  expectMutationError("/render/beams", "many", "/render/beams", {"integer", "\"many\""});
  expectMutationError("/render/seed", -3, "/render/seed", {"integer in 0..18446744073709551615"});
  expectErrorText(R"({"camera": {"position": [0,0,0], "look_at": [0,0,1]},
                      "lights": [{"type": "point", "position": [0,0,2], "power_w": 1, "spd": "D65"}],
                      "render": {"seed": 18446744073709551616}})",
                  "/render/seed", {"integer in 0..18446744073709551615"});
}

TEST_F(SceneTest, LimitsKeepNumbersInRange) {
  expectMutationError("/lights/0/position", {0, 0, 1e13}, "/lights/0/position/2", {"magnitude <= 1e+12 m", "got 10000000000000.0"});
  expectMutationError("/camera/look_at", {-1e300, 0, 1}, "/camera/look_at/0", {"magnitude"});
  expectMutationError("/lights/2/radius_m", 1e20, "/lights/2/radius_m", {"<= 1e+12"});
  expectMutationError("/spectrum/max_nm", 1e12, "/spectrum/max_nm", {"at most 100000 nm"});
  expectMutationError("/lights/1/spd/blackbody_k", 1e308, "/lights/1/spd/blackbody_k", {"<= 1e+06"});
  // Huge but finite direction components are fine: only the direction counts.
  json j = exampleScene();
  j["lights"][1]["direction"] = {0, -1e300, -1e300};
  Scene s = load(j);
  expectVec(s.lights[1].direction, 0, -std::sqrt(0.5), -std::sqrt(0.5));
}

// Every leaf of the example replaced by values of every JSON type: the loader
// either accepts the scene (with finite numbers) or throws SceneError naming
// the file; nothing else escapes.
TEST_F(SceneTest, ArbitraryValuesNeverEscapeAsOtherErrors) {
  const json base = exampleScene();
  const json flat = base.flatten();
  const std::vector<json> weird = {nullptr, true, -1, 0, 1e308, -1e-308, 0.5, 65536, "x", "", json::array(),
                                   json::object(), json::array({1, 2, 3}), json::array({0, 0, 0}),
                                   json::parse("18446744073709551615"), json::parse("-9223372036854775808")};
  fs::path file = dir_ / "fuzz.json";
  int accepted = 0, rejected = 0;
  for (const auto& [pointer, value] : flat.items()) {
    for (const auto& w : weird) {
      json j = base;
      j[json::json_pointer(pointer)] = w;
      try {
        Scene s = parseScene(j.dump(), file);
        ++accepted;
        for (const Light& l : s.lights) {
          EXPECT_TRUE(std::isfinite(glm::length(l.position)) && std::isfinite(l.powerW)) << pointer << " = " << w;
          EXPECT_NEAR(glm::length(l.direction), 1.0, 1e-12) << pointer << " = " << w;
        }
      } catch (const SceneError& e) {
        ++rejected;
        EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": /", 0), 0u) << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << pointer << " = " << w.dump() << " escaped as " << e.what();
      }
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(rejected, 0);
}

// validateScene holds the loader's limits, so a scene built in code cannot
// pass values a file could not.
TEST_F(SceneTest, ScenesBuiltInCodeGetTheLoadersLimits) {
  const Scene base = load(exampleScene());
  EXPECT_NO_THROW(validateScene(base));
  auto errorOfScene = [](const Scene& s) {
    try {
      validateScene(s);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  struct Case {
    const char* what;
    void (*mutate)(Scene&);
    const char* phrase;
  };
  const Case cases[] = {
      {"far light", [](Scene& s) { s.lights[0].position.z = 1e13; }, "/lights/0/position/2: must be a coordinate"},
      {"far camera", [](Scene& s) { s.camera.lookAt.x = -1e300; }, "/camera/look_at/0: must be a coordinate"},
      {"huge disk", [](Scene& s) { s.lights[2].radiusM = 1e20; }, "/lights/2/radius_m: must be a length"},
      {"huge rect", [](Scene& s) { s.lights[3].sizeM.y = 1e13; }, "/lights/3/size_m/1: must be a length"},
      {"tiny rect", [](Scene& s) { s.lights[3].sizeM = {1e-200, 1e-200}; }, "/lights/3/size_m: the rect's area"},
      {"rect u_axis", [](Scene& s) { s.lights[3].uAxis = {0.0, 0.0, 2.0}; }, "/lights/3/u_axis: [0, 0, 2] is parallel"},
      {"wide cone", [](Scene& s) { s.lights[1].coneHalfAngleDeg = 180.5; }, "/lights/1/cone_deg: must be a half angle"},
      {"long waves", [](Scene& s) { s.spectrum.maxNm = 1e12; }, "/spectrum/max_nm: must be at most 100000 nm"},
      {"many bins", [](Scene& s) { s.spectrum.bins = 100001; }, "/spectrum/bins: must be an integer in 1..100000"},
      {"wide sensor", [](Scene& s) { s.camera.pixelsX = 65536; }, "/camera/sensor/pixels/0: must be an integer"},
      {"many pixels", [](Scene& s) { s.camera.pixelsX = s.camera.pixelsY = 65535; }, "too many pixels"},
      {"up along view", [](Scene& s) { s.camera.up = {0.0, 0.0, 3.0}; }, "/camera/up: [0, 0, 3] is parallel"},
      {"no exposure", [](Scene& s) { s.camera.exposureS = 0.0; }, "/camera/exposure_s: must be a finite number > 0"},
  };
  for (const Case& c : cases) {
    Scene s = base;
    s.sourcePath.clear();
    c.mutate(s);
    const std::string message = errorOfScene(s);
    EXPECT_EQ(message.rfind("<scene>: ", 0), 0u) << c.what << ": " << message;
    EXPECT_NE(message.find(c.phrase), std::string::npos) << c.what << ": " << message;
  }
  // Dark lights are the trace plan's business in code, a file's error.
  Scene dark = base;
  for (Light& l : dark.lights) l.powerW = 0.0;
  EXPECT_NO_THROW(validateScene(dark));
}

TEST_F(SceneTest, AllSceneFilesInTheRepositoryParse) {
  fs::path root = fs::path(SPECTRACE_SOURCE_DIR) / "scenes";
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    Scene s;
    EXPECT_NO_THROW(s = loadScene(entry.path()));
    EXPECT_FALSE(s.lights.empty());
    EXPECT_EQ(s.sourceSha256.size(), 64u);
  }
  EXPECT_GE(count, 2);
}

}  // namespace
}  // namespace spectrace
