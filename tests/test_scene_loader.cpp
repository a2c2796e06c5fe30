// Tests for the scene loader (common/content/scene.cpp, format in docs/scene-format.md).
//
// Every rejected input must produce one line "FILE: JSON.PATH: reason"; the
// bad-input tests check the file label, the exact path and a word of the reason.
#include "mesh.h"
#include "scene.h"
#include "temp_dir.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;
using lab::SceneError;

namespace {


// The smallest valid scene: one object, one material.
const std::string kMinimal = R"({"materials": {"m": {}}, "objects": [{"mesh": "cube", "material": "m"}]})";

// The minimal scene plus `extra` top-level keys, e.g. R"("camera": {"near": 0})".
std::string with(const std::string& extra) {
    return R"({ "materials": {"m": {}}, "objects": [{"mesh": "cube", "material": "m"}], )" + extra + "}";
}

// The minimal scene with `extra` keys inside objects[0].
std::string object_with(const std::string& extra) {
    return R"({ "materials": {"m": {}}, "objects": [{"mesh": "cube", "material": "m", )" + extra + "}]}";
}

// The minimal scene with a single light.
std::string light(const std::string& body) { return with(R"("lights": [)" + body + "]"); }

lab::Scene parse(const std::string& text, const std::string& base_dir = ".") {
    return lab::parse_scene(text, "scene.json", base_dir);
}

// The SceneError message for `text` ("" and a test failure if it parses).
std::string error_of(const std::string& text, const std::string& base_dir = ".") {
    try {
        parse(text, base_dir);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a SceneError for: " << text;
    return "";
}

// Checks the message shape "scene.json: <path>...: ...<reason>..." on one line.
void expect_error(const std::string& text, const std::string& path, const std::string& reason,
                  const std::string& base_dir = ".") {
    const std::string message = error_of(text, base_dir);
    SCOPED_TRACE(message);
    EXPECT_EQ(message.rfind("scene.json: " + path, 0), 0u) << "file label and JSON path";
    EXPECT_NE(message.find(reason), std::string::npos) << "reason";
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
}

void expect_vec3(const glm::vec3& v, float x, float y, float z) {
    EXPECT_FLOAT_EQ(v.x, x);
    EXPECT_FLOAT_EQ(v.y, y);
    EXPECT_FLOAT_EQ(v.z, z);
}

}  // namespace

// --- valid scenes -------------------------------------------------------------

TEST(SceneLoader, FullSceneParsesEveryField) {
    TempDir dir;
    dir.write("models/teapot.obj", "v 0 0 0\n");
    const std::string text = R"({
      "camera": { "mode": "transform", "position": [1, 2, 3], "target": [4, 5, 6], "up": [0, 0, 1],
                  "yaw_deg": 10, "pitch_deg": -20, "roll_deg": 30, "fov_y_deg": 45,
                  "near": 0.5, "far": 50 },
      "background": [0.1, 0.2, 0.3],
      "ambient": { "color": [0.4, 0.5, 0.6], "intensity": 0.25 },
      "lights": [
        { "type": "directional", "direction": [1, -1, 0], "color": [1, 0.9, 0.8], "intensity": 2 },
        { "type": "point", "position": [0, 3, 0], "color": [0.5, 0.5, 1], "intensity": 3,
          "attenuation": [1, 0.1, 0.01] },
        { "type": "spot", "position": [1, 4, 1], "direction": [0, -1, 0], "color": [1, 1, 1],
          "intensity": 4, "attenuation": [0, 0, 1], "inner_deg": 10, "outer_deg": 20 } ],
      "materials": {
        "red": { "albedo": [0.9, 0.1, 0.1], "specular": [0.5, 0.5, 0.5], "shininess": 64,
                 "emissive": [0, 0, 0.2] },
        "plain": {} },
      "objects": [
        { "mesh": "sphere", "material": "red", "position": [1, 0, -1], "rotation_deg": [10, 20, 30],
          "scale": [2, 2, 2], "segments": 32, "rings": 16 },
        { "mesh": "models/teapot.obj", "material": "plain", "crease_deg": 45, "normalize": true } ]
    })";
    const lab::Scene s = parse(text, dir.path().string());

    EXPECT_EQ(s.file, "");  // parsed from a string
    EXPECT_EQ(s.camera.mode, lab::CameraDesc::Mode::Transform);
    expect_vec3(s.camera.position, 1, 2, 3);
    expect_vec3(s.camera.target, 4, 5, 6);
    expect_vec3(s.camera.up, 0, 0, 1);
    EXPECT_FLOAT_EQ(s.camera.yaw_deg, 10);
    EXPECT_FLOAT_EQ(s.camera.pitch_deg, -20);
    EXPECT_FLOAT_EQ(s.camera.roll_deg, 30);
    EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 45);
    EXPECT_FLOAT_EQ(s.camera.near_plane, 0.5f);
    EXPECT_FLOAT_EQ(s.camera.far_plane, 50);

    expect_vec3(s.background, 0.1f, 0.2f, 0.3f);
    expect_vec3(s.ambient.color, 0.4f, 0.5f, 0.6f);
    EXPECT_FLOAT_EQ(s.ambient.intensity, 0.25f);

    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, lab::LightDesc::Type::Directional);
    expect_vec3(s.lights[0].direction, 1, -1, 0);
    expect_vec3(s.lights[0].color, 1, 0.9f, 0.8f);
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 2);
    EXPECT_EQ(s.lights[1].type, lab::LightDesc::Type::Point);
    expect_vec3(s.lights[1].position, 0, 3, 0);
    expect_vec3(s.lights[1].color, 0.5f, 0.5f, 1);
    EXPECT_FLOAT_EQ(s.lights[1].intensity, 3);
    expect_vec3(s.lights[1].attenuation, 1, 0.1f, 0.01f);
    EXPECT_EQ(s.lights[2].type, lab::LightDesc::Type::Spot);
    expect_vec3(s.lights[2].position, 1, 4, 1);
    expect_vec3(s.lights[2].direction, 0, -1, 0);
    EXPECT_FLOAT_EQ(s.lights[2].intensity, 4);
    expect_vec3(s.lights[2].attenuation, 0, 0, 1);
    EXPECT_FLOAT_EQ(s.lights[2].inner_deg, 10);
    EXPECT_FLOAT_EQ(s.lights[2].outer_deg, 20);

    ASSERT_EQ(s.materials.size(), 2u);
    const lab::MaterialDesc& red = s.materials.at("red");
    expect_vec3(red.albedo, 0.9f, 0.1f, 0.1f);
    expect_vec3(red.specular, 0.5f, 0.5f, 0.5f);
    EXPECT_FLOAT_EQ(red.shininess, 64);
    expect_vec3(red.emissive, 0, 0, 0.2f);
    const lab::MaterialDesc& plain = s.materials.at("plain");  // all defaults
    expect_vec3(plain.albedo, 0.8f, 0.8f, 0.8f);
    expect_vec3(plain.specular, 0, 0, 0);
    EXPECT_FLOAT_EQ(plain.shininess, 32);
    expect_vec3(plain.emissive, 0, 0, 0);

    ASSERT_EQ(s.objects.size(), 2u);
    const lab::ObjectDesc& a = s.objects[0];
    EXPECT_EQ(a.mesh, "sphere");
    EXPECT_EQ(a.mesh_path, "");
    EXPECT_EQ(a.material, "red");
    expect_vec3(a.position, 1, 0, -1);
    expect_vec3(a.rotation_deg, 10, 20, 30);
    expect_vec3(a.scale, 2, 2, 2);
    EXPECT_EQ(a.segments, 32);
    EXPECT_EQ(a.rings, 16);
    const lab::ObjectDesc& b = s.objects[1];
    EXPECT_EQ(b.mesh, "models/teapot.obj");
    EXPECT_EQ(fs::path(b.mesh_path), fs::absolute(dir.path() / "models" / "teapot.obj").lexically_normal());
    EXPECT_EQ(b.material, "plain");
    EXPECT_FLOAT_EQ(b.crease_deg, 45);
    EXPECT_TRUE(b.normalize);
}

TEST(SceneLoader, OmittedKeysTakeTheDefaultsOfSceneH) {
    const lab::Scene s = parse(kMinimal);
    const lab::CameraDesc camera;
    EXPECT_EQ(s.camera.mode, lab::CameraDesc::Mode::LookAt);
    expect_vec3(s.camera.position, 0, 2, 6);
    expect_vec3(s.camera.target, 0, 0, 0);
    expect_vec3(s.camera.up, 0, 1, 0);
    EXPECT_FLOAT_EQ(s.camera.yaw_deg, camera.yaw_deg);
    EXPECT_FLOAT_EQ(s.camera.pitch_deg, camera.pitch_deg);
    EXPECT_FLOAT_EQ(s.camera.roll_deg, camera.roll_deg);
    EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 60);
    EXPECT_FLOAT_EQ(s.camera.near_plane, 0.01f);
    EXPECT_FLOAT_EQ(s.camera.far_plane, 100);
    expect_vec3(s.background, 0.05f, 0.05f, 0.08f);
    expect_vec3(s.ambient.color, 1, 1, 1);
    EXPECT_FLOAT_EQ(s.ambient.intensity, 0.1f);
    EXPECT_TRUE(s.lights.empty());
    ASSERT_EQ(s.objects.size(), 1u);
    const lab::ObjectDesc& o = s.objects[0];
    expect_vec3(o.position, 0, 0, 0);
    expect_vec3(o.rotation_deg, 0, 0, 0);
    expect_vec3(o.scale, 1, 1, 1);
    EXPECT_EQ(o.segments, 0);
    EXPECT_EQ(o.rings, 0);
    EXPECT_FLOAT_EQ(o.crease_deg, 60);
    EXPECT_FALSE(o.normalize);
}

TEST(SceneLoader, LightDefaultsPerType) {
    const lab::Scene s = parse(with(R"("lights": [{"type": "directional"}, {"type": "point"}, {"type": "spot"}])"));
    ASSERT_EQ(s.lights.size(), 3u);
    expect_vec3(s.lights[0].direction, 0, -1, 0);
    expect_vec3(s.lights[0].color, 1, 1, 1);
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 1);
    expect_vec3(s.lights[1].position, 0, 0, 0);
    expect_vec3(s.lights[1].attenuation, 1, 0, 0);
    EXPECT_FLOAT_EQ(s.lights[2].inner_deg, 12.5f);
    EXPECT_FLOAT_EQ(s.lights[2].outer_deg, 17.5f);
}

TEST(SceneLoader, EmptyObjectListNeedsNoMaterials) {
    const lab::Scene s = parse(R"({"objects": []})");
    EXPECT_TRUE(s.objects.empty());
    EXPECT_TRUE(s.materials.empty());
}

TEST(SceneLoader, LookAtSpecialCasesAreAllowed) {
    // eye == target (documented: looks down -Z) and up parallel to the view direction.
    EXPECT_NO_THROW(parse(with(R"("camera": {"position": [1, 2, 3], "target": [1, 2, 3]})")));
    EXPECT_NO_THROW(parse(with(R"("camera": {"position": [0, 5, 0], "target": [0, 0, 0], "up": [0, 1, 0]})")));
}

TEST(SceneLoader, BoundaryValuesThatAreValid) {
    const lab::Scene s = parse(R"({
      "camera": { "fov_y_deg": 179.5, "near": 0.001, "far": 1000000 },
      "ambient": { "intensity": 0 },
      "lights": [ { "type": "spot", "attenuation": [0, 0, 0], "inner_deg": 0, "outer_deg": 90 },
                  { "type": "spot", "inner_deg": 30, "outer_deg": 30 } ],
      "materials": { "m": { "shininess": 0, "albedo": [0, 0, 0], "emissive": [5, 5, 5] } },
      "objects": [ { "mesh": "plane", "material": "m", "scale": [-1, 0.5, 1000000],
                     "position": [-1000000, 0, 1000000], "segments": 3, "rings": 1024,
                     "crease_deg": 180 },
                   { "mesh": "torus", "material": "m", "segments": 3.0, "crease_deg": 0 } ] })");
    expect_vec3(s.lights[0].attenuation, 0, 0, 0);
    expect_vec3(s.objects[0].scale, -1, 0.5f, 1e6f);  // negative = mirror, allowed
    EXPECT_EQ(s.objects[0].segments, 3);
    EXPECT_EQ(s.objects[0].rings, 1024);
    EXPECT_EQ(s.objects[1].segments, 3);  // 3.0 is an integer in JSON's eyes
    expect_vec3(s.materials.at("m").emissive, 5, 5, 5);  // HDR colours may exceed 1
}

TEST(SceneLoader, EveryPrimitiveNameIsAccepted) {
    for (const std::string& name : lab::primitive_mesh_names()) {
        const lab::Scene s = parse(R"({"materials": {"m": {}}, "objects": [{"mesh": ")" + name +
                                   R"(", "material": "m"}]})");
        EXPECT_EQ(s.objects[0].mesh, name);
        EXPECT_EQ(s.objects[0].mesh_path, "");
    }
    EXPECT_EQ(lab::primitive_mesh_names().size(), 8u);
}

// --- files and .obj paths -----------------------------------------------------

TEST(SceneLoader, LoadSceneResolvesObjPathsAgainstTheSceneFolder) {
    TempDir dir;
    dir.write("scenes/meshes/bunny.obj", "v 0 0 0\n");
    dir.write("shared/cow.OBJ", "v 0 0 0\n");
    const fs::path absolute_obj = dir.write("abs/thing.obj", "v 0 0 0\n");
    const fs::path scene = dir.write(
        "scenes/test.json", R"({"materials": {"m": {}}, "objects": [
            {"mesh": "meshes/bunny.obj", "material": "m"},
            {"mesh": "../shared/cow.OBJ", "material": "m"},
            {"mesh": ")" + absolute_obj.string() + R"(", "material": "m"}]})");
    const lab::Scene s = lab::load_scene(scene.string());
    EXPECT_EQ(s.file, scene.string());
    ASSERT_EQ(s.objects.size(), 3u);
    EXPECT_EQ(s.objects[0].mesh, "meshes/bunny.obj");
    EXPECT_EQ(fs::path(s.objects[0].mesh_path), (dir.path() / "scenes/meshes/bunny.obj").lexically_normal());
    EXPECT_EQ(fs::path(s.objects[1].mesh_path), (dir.path() / "shared/cow.OBJ").lexically_normal());
    EXPECT_EQ(fs::path(s.objects[2].mesh_path), absolute_obj);
    EXPECT_TRUE(fs::path(s.objects[0].mesh_path).is_absolute());
}

TEST(SceneLoader, RelativeSceneFileFromAnotherWorkingDirectory) {
    TempDir dir;
    dir.write("sub/m.obj", "v 0 0 0\n");
    dir.write("sub/s.json", R"({"materials": {"m": {}}, "objects": [{"mesh": "m.obj", "material": "m"}]})");
    const fs::path old = fs::current_path();
    fs::current_path(dir.path());
    lab::Scene s;
    EXPECT_NO_THROW(s = lab::load_scene("sub/s.json"));
    fs::current_path(old);
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(fs::path(s.objects[0].mesh_path), (dir.path() / "sub/m.obj").lexically_normal());
}

TEST(SceneLoader, MissingObjFileIsAnError) {
    TempDir dir;
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "nothere.obj", "material": "m"}]})",
                 "objects[0].mesh: ", "mesh file not found", dir.path().string());
    // The message shows the resolved path, so the student sees where the loader looked.
    const std::string message =
        error_of(R"({"materials": {"m": {}}, "objects": [{"mesh": "nothere.obj", "material": "m"}]})",
                 dir.path().string());
    EXPECT_NE(message.find((dir.path() / "nothere.obj").string()), std::string::npos) << message;
}

TEST(SceneLoader, ObjPathThatIsAFolderIsAnError) {
    TempDir dir;
    fs::create_directories(dir.path() / "folder.obj");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "folder.obj", "material": "m"}]})",
                 "objects[0].mesh", "not a file", dir.path().string());
}

TEST(SceneLoader, MissingSceneFile) {
    TempDir dir;
    const std::string file = (dir.path() / "missing.json").string();
    try {
        lab::load_scene(file);
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("No such file"), std::string::npos) << message;
    }
}

TEST(SceneLoader, SceneFileThatIsAFolder) {
    TempDir dir;
    try {
        lab::load_scene(dir.path().string());
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
    }
}

// Found while fuzzing (tests/fuzz/regressions.txt): --scene /dev/zero read forever.
TEST(SceneLoader, SceneFileThatIsADeviceOrAFifo) {
    for (const std::string file : {"/dev/zero", "/dev/urandom"}) {
        if (!fs::exists(file)) continue;
        try {
            lab::load_scene(file);
            FAIL() << "expected SceneError for " << file;
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()), file + ": cannot read scene: not a regular file");
        }
    }
    TempDir dir;
    const std::string fifo = (dir.path() / "pipe.json").string();
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_THROW(lab::load_scene(fifo), SceneError);  // would block in open() without the check
}

TEST(SceneLoader, HugeSceneFileIsRejectedUnread) {
    TempDir dir;
    const fs::path file = dir.path() / "huge.json";
    std::ofstream(file) << kMinimal;
    fs::resize_file(file, (16u << 20) + 1);  // sparse: costs no disk
    try {
        lab::load_scene(file.string());
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("file too large (16777217 bytes; at most 16 MiB)"), std::string::npos)
            << e.what();
    }
}

TEST(SceneLoader, UnreadableSceneFile) {
    TempDir dir;
    const fs::path file = dir.write("locked.json", kMinimal);
    fs::permissions(file, fs::perms::none);
    if (std::ifstream(file).good()) GTEST_SKIP() << "running as root: permissions are not enforced";
    try {
        lab::load_scene(file.string());
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("Permission denied"), std::string::npos) << message;
    }
}

TEST(SceneLoader, LoadSceneErrorsNameTheFile) {
    TempDir dir;
    const fs::path file = dir.write("bad.json", with(R"("camera": {"near": -1})"));
    try {
        lab::load_scene(file.string());
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": camera.near: ", 0), 0u) << e.what();
    }
}

// --- malformed JSON -----------------------------------------------------------

TEST(SceneLoader, MalformedJsonReportsLineAndColumn) {
    // Line 2 is `  "objects": [,]`: the ',' is the 15th character.
    expect_error("{\n  \"objects\": [,]\n}", "line 2, column 15: malformed JSON", "syntax error");
    // Missing closing brace: the error is at the end of the text (line 1, column 15).
    expect_error(R"({"objects": [])", "line 1, column 15: malformed JSON", "unexpected end of input");
    expect_error("", "line 1, column 1: malformed JSON", "end of input");
    expect_error(kMinimal + " x", "line 1, column ", "malformed JSON");
    expect_error("{\"objects\": [], }", "line 1, column 17: malformed JSON", "object key");
}

TEST(SceneLoader, NumberOverflowInTheTextIsRejected) {
    // 1e400 does not fit a double; JSON cannot spell NaN or Infinity at all.
    // The column is that of the number's first character (the 17th on line 2).
    expect_error("{\"objects\": [],\n \"background\": [1e400, 0, 0]}", "line 2, column 17: malformed JSON",
                 "overflow");
    expect_error(with(R"("background": [NaN, 0, 0])"), "line 1, column ", "malformed JSON");
}

TEST(SceneLoader, TopLevelMustBeAnObject) {
    expect_error("[]", "(top level)", "JSON object");
    expect_error("42", "(top level)", "got number");
    expect_error("\"scene\"", "(top level)", "got string");
}

TEST(SceneLoader, DuplicateKeysAreRejected) {
    expect_error(object_with(R"("position": [1, 0, 0], "position": [2, 0, 0])"), "objects[0].position: ",
                 "duplicate key");
    expect_error(R"({"objects": [], "objects": []})", "objects: ", "duplicate key");
    expect_error(with(R"("lights": [{"type": "point"}, {"type": "point", "type": "spot"}])"), "lights[1].type: ",
                 "duplicate key");
}

// --- wrong types --------------------------------------------------------------

TEST(SceneLoader, WrongTypesAreRejected) {
    expect_error(with(R"("camera": {"fov_y_deg": "60"})"), "camera.fov_y_deg: ", "expected a number, got string");
    expect_error(with(R"("camera": {"near": true})"), "camera.near: ", "expected a number, got boolean");
    expect_error(with(R"("camera": {"mode": 1})"), "camera.mode: ", "expected a string, got number");
    expect_error(with(R"("camera": [])"), "camera: ", "expected an object");
    expect_error(object_with(R"("scale": [1, 2])"), "objects[0].scale: ", "array of 3 numbers");
    expect_error(object_with(R"("scale": [1, 2, 3, 4])"), "objects[0].scale: ", "array of 4 elements");
    expect_error(object_with(R"("scale": 2)"), "objects[0].scale: ", "array of 3 numbers");
    expect_error(object_with(R"("position": [1, "2", 3])"), "objects[0].position[1]: ", "expected a number");
    expect_error(object_with(R"("normalize": 1)"), "objects[0].normalize: ", "expected true or false");
    expect_error(object_with(R"("segments": 1.5)"), "objects[0].segments: ", "expected an integer");
    expect_error(object_with(R"("segments": "8")"), "objects[0].segments: ", "expected a number");
    expect_error(with(R"("background": null)"), "background: ", "got null");
    expect_error(with(R"("lights": {})"), "lights: ", "expected an array");
    expect_error(with(R"("lights": [5])"), "lights[0]: ", "expected an object");
    expect_error(R"({"objects": {}})", "objects: ", "expected an array");
    expect_error(R"({"objects": [], "materials": []})", "materials: ", "expected an object");
    expect_error(R"({"objects": [], "materials": {"m": 3}})", "materials.m: ", "expected an object");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": 7, "material": "m"}]})", "objects[0].mesh: ",
                 "expected a string");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "cube", "material": ["m"]}]})",
                 "objects[0].material: ", "expected a string");
}

// --- unknown and missing keys -------------------------------------------------

TEST(SceneLoader, UnknownKeysAreRejectedWithASuggestion) {
    expect_error(object_with(R"("postion": [1, 0, 0])"), "objects[0].postion: ", "did you mean 'position'?");
    expect_error(with(R"("camera": {"fov": 60})"), "camera.fov: ", "did you mean 'fov_y_deg'?");
    expect_error(with(R"("backgroud": [0, 0, 0])"), "backgroud: ", "did you mean 'background'?");
    expect_error(with(R"("ambient": {"colour": [1, 1, 1]})"), "ambient.colour: ", "did you mean 'color'?");
    expect_error(R"({"objects": [], "materials": {"m": {"glossiness": 0.5}}})", "materials.m.glossiness: ",
                 "unknown key");
    // No close match: the message lists the valid keys instead.
    expect_error(with(R"("zzzzzz": 1)"), "zzzzzz: ", "expected one of: camera, background");
}

TEST(SceneLoader, KeysOfAnotherLightTypeAreUnknown) {
    expect_error(light(R"({"type": "point", "inner_deg": 10})"), "lights[0].inner_deg: ",
                 "unknown key for a point light");
    expect_error(light(R"({"type": "directional", "position": [0, 1, 0]})"), "lights[0].position: ",
                 "unknown key for a directional light");
    expect_error(light(R"({"type": "directional", "attenuation": [1, 0, 0]})"), "lights[0].attenuation: ",
                 "unknown key");
    expect_error(light(R"({"type": "point", "direction": [0, -1, 0]})"), "lights[0].direction: ",
                 "unknown key for a point light");
}

TEST(SceneLoader, MissingRequiredKeys) {
    expect_error("{}", "objects: ", "missing required key");
    expect_error(R"({"objects": [{"mesh": "cube", "material": "m"}]})", "materials: ", "missing required key");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"material": "m"}]})", "objects[0].mesh: ",
                 "missing required key");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "cube"}]})", "objects[0].material: ",
                 "missing required key");
    expect_error(light(R"({"direction": [0, -1, 0]})"), "lights[0].type: ", "missing required key");
    // A misspelled required key is pointed out.
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mseh": "cube", "material": "m"}]})",
                 "objects[0].mesh: ", "found 'mseh'");
}

TEST(SceneLoader, UnknownNamesAreRejected) {
    expect_error(with(R"("camera": {"mode": "look_at"})"), "camera.mode: ", "unknown camera mode 'look_at'; did you mean 'lookat'?");
    expect_error(with(R"("camera": {"mode": "orbit"})"), "camera.mode: ", "expected one of: lookat, transform");
    expect_error(light(R"({"type": "area"})"), "lights[0].type: ", "unknown light type 'area'");
    expect_error(light(R"({"type": "spotlight"})"), "lights[0].type: ", "did you mean 'spot'?");
    expect_error(R"({"materials": {"red": {}}, "objects": [{"mesh": "cube", "material": "rde"}]})",
                 "objects[0].material: ", "unknown material 'rde'; did you mean 'red'?");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "cubee", "material": "m"}]})",
                 "objects[0].mesh: ", "unknown mesh 'cubee'; did you mean 'cube'?");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "Sphere", "material": "m"}]})",
                 "objects[0].mesh: ", "did you mean 'sphere'?");
    expect_error(R"({"materials": {"m": {}}, "objects": [{"mesh": "teapot.stl", "material": "m"}]})",
                 "objects[0].mesh: ", ".obj");
    expect_error(R"({"objects": [], "materials": {"": {}}})", "materials[\"\"]: ", "must not be empty");
}

// --- numbers out of range -----------------------------------------------------

TEST(SceneLoader, AbsurdMagnitudesAreRejected) {
    // |v| <= 1e6 everywhere; this also keeps every value finite as a float (1e39 is not).
    expect_error(object_with(R"("position": [1e7, 0, 0])"), "objects[0].position[0]: ", "magnitude");
    expect_error(object_with(R"("scale": [1, 1e39, 1])"), "objects[0].scale[1]: ", "magnitude");
    expect_error(with(R"("camera": {"far": 1e300})"), "camera.far: ", "magnitude");
    expect_error(with(R"("camera": {"yaw_deg": -2e6})"), "camera.yaw_deg: ", "magnitude");
}

TEST(SceneLoader, CameraClipPlanesAndFieldOfView) {
    expect_error(with(R"("camera": {"near": 0})"), "camera.near: ", "must be > 0");
    expect_error(with(R"("camera": {"near": -0.1})"), "camera.near: ", "must be > 0");
    expect_error(with(R"("camera": {"near": 10, "far": 5})"), "camera.far: ", "greater than near");
    expect_error(with(R"("camera": {"near": 5, "far": 5})"), "camera.far: ", "greater than near");
    expect_error(with(R"("camera": {"near": 200})"), "camera.far: ", "greater than near");  // default far = 100
    expect_error(with(R"("camera": {"fov_y_deg": 0})"), "camera.fov_y_deg: ", "must be in (0, 180)");
    expect_error(with(R"("camera": {"fov_y_deg": 180})"), "camera.fov_y_deg: ", "must be in (0, 180)");
    expect_error(with(R"("camera": {"fov_y_deg": -30})"), "camera.fov_y_deg: ", "must be in (0, 180)");
}

TEST(SceneLoader, ZeroLengthDirections) {
    expect_error(with(R"("camera": {"up": [0, 0, 0]})"), "camera.up: ", "zero-length");
    expect_error(with(R"("camera": {"up": [0, 1e-7, 0]})"), "camera.up: ", "zero-length");
    expect_error(light(R"({"type": "directional", "direction": [0, 0, 0]})"), "lights[0].direction: ",
                 "zero-length");
    expect_error(light(R"({"type": "spot", "direction": [0, 0, 0]})"), "lights[0].direction: ", "zero-length");
    EXPECT_NO_THROW(parse(with(R"("camera": {"up": [0, 1e-5, 0]})")));
}

TEST(SceneLoader, ScaleMustBeNonZero) {
    expect_error(object_with(R"("scale": [1, 0, 1])"), "objects[0].scale[1]: ", "non-zero");
    expect_error(object_with(R"("scale": [0, 0, 0])"), "objects[0].scale[0]: ", "non-zero");
    expect_error(object_with(R"("scale": [1, 1, -1e-9])"), "objects[0].scale[2]: ", "non-zero");
}

TEST(SceneLoader, NegativeColoursAndIntensities) {
    expect_error(with(R"("background": [0, -0.1, 0])"), "background[1]: ", "must be >= 0");
    expect_error(with(R"("ambient": {"intensity": -1})"), "ambient.intensity: ", "must be >= 0");
    expect_error(with(R"("ambient": {"color": [-1, 0, 0]})"), "ambient.color[0]: ", "must be >= 0");
    expect_error(light(R"({"type": "point", "intensity": -0.5})"), "lights[0].intensity: ", "must be >= 0");
    expect_error(light(R"({"type": "spot", "color": [1, 1, -1]})"), "lights[0].color[2]: ", "must be >= 0");
    expect_error(R"({"objects": [], "materials": {"m": {"albedo": [-0.2, 0, 0]}}})", "materials.m.albedo[0]: ",
                 "must be >= 0");
    expect_error(R"({"objects": [], "materials": {"m": {"specular": [0, -1, 0]}}})", "materials.m.specular[1]: ",
                 "must be >= 0");
    expect_error(R"({"objects": [], "materials": {"m": {"emissive": [0, 0, -3]}}})", "materials.m.emissive[2]: ",
                 "must be >= 0");
    expect_error(R"({"objects": [], "materials": {"m": {"shininess": -1}}})", "materials.m.shininess: ",
                 "must be >= 0");
}

TEST(SceneLoader, AttenuationAndSpotAngles) {
    expect_error(light(R"({"type": "point", "attenuation": [1, -0.1, 0]})"), "lights[0].attenuation[1]: ",
                 "must be >= 0");
    expect_error(light(R"({"type": "spot", "inner_deg": -1})"), "lights[0].inner_deg: ", "must be in [0, 90]");
    expect_error(light(R"({"type": "spot", "outer_deg": 90.5})"), "lights[0].outer_deg: ", "must be in [0, 90]");
    expect_error(light(R"({"type": "spot", "inner_deg": 20, "outer_deg": 10})"), "lights[0].inner_deg: ",
                 "must be <= outer_deg");
    // The error names the right element of the array.
    expect_error(with(R"("lights": [{"type": "point"}, {"type": "point", "intensity": -1}])"),
                 "lights[1].intensity: ", "must be >= 0");
}

TEST(SceneLoader, MeshOptionRanges) {
    expect_error(object_with(R"("segments": 2)"), "objects[0].segments: ", "must be 0 (default) or in [3, 1024]");
    expect_error(object_with(R"("segments": 1)"), "objects[0].segments: ", "[3, 1024]");
    expect_error(object_with(R"("rings": 1025)"), "objects[0].rings: ", "must be in [0, 1024]");
    expect_error(object_with(R"("rings": -3)"), "objects[0].rings: ", "must be in [0, 1024]");
    expect_error(object_with(R"("crease_deg": 181)"), "objects[0].crease_deg: ", "must be in [0, 180]");
    expect_error(object_with(R"("crease_deg": -1)"), "objects[0].crease_deg: ", "must be in [0, 180]");
}

TEST(SceneLoader, IcosphereSegmentsIsTheSubdivisionLevel) {
    const auto ico = [](const std::string& extra) {
        return R"({ "materials": {"m": {}}, "objects": [{"mesh": "icosphere", "material": "m", )" + extra + "}]}";
    };
    EXPECT_EQ(parse(ico(R"("segments": 1)")).objects[0].segments, 1);
    EXPECT_EQ(parse(ico(R"("segments": 7)")).objects[0].segments, 7);
    expect_error(ico(R"("segments": 8)"), "objects[0].segments: ", "must be in [0, 7]");
}

// --- message format -----------------------------------------------------------

TEST(SceneLoader, MessagesStayOnOneLine) {
    // "a\nb" is a legal JSON key; the message must still be one line.
    const std::string message = error_of(with(R"("a\nb": 1)"));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("unknown key"), std::string::npos) << message;
}

TEST(SceneLoader, OddMaterialNamesAreQuotedInPaths) {
    expect_error(R"({"objects": [], "materials": {"my red": {"albedo": [2, -1, 0]}}})",
                 "materials[\"my red\"].albedo[1]: ", "must be >= 0");
}

TEST(SceneLoader, EmptyFileLabelStillGivesALabel) {
    try {
        lab::parse_scene("{}", "", ".");
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), "<scene>: objects: missing required key");
    }
}

// --- lab 2: "lighting" section and the lighting-model material keys ---------------

TEST(SceneLoader, LightingDefaultsAreBlinnPhongPerPixel) {
    const lab::Scene s = parse(kMinimal);
    EXPECT_EQ(s.lighting.model, lab::LightingDesc::Model::BlinnPhong);
    EXPECT_EQ(s.lighting.shading, lab::LightingDesc::Shading::Phong);
    EXPECT_EQ(s.lighting.spot_falloff, lab::LightingDesc::SpotFalloff::Smooth);
    EXPECT_EQ(s.lighting.distribution, lab::LightingDesc::Distribution::GGX);
    EXPECT_EQ(s.lighting.toon_bands, 4);
    EXPECT_FALSE(s.lighting.markers);
    EXPECT_EQ(s.lighting.nan_check, lab::LightingDesc::NanCheck::Off);
    const lab::MaterialDesc& m = s.materials.at("m");
    EXPECT_FLOAT_EQ(m.roughness, 0.5f);
    expect_vec3(m.f0, 0.04f, 0.04f, 0.04f);
    EXPECT_FLOAT_EQ(m.roughness_x, 0.15f);
    EXPECT_FLOAT_EQ(m.roughness_y, 0.45f);
    EXPECT_FLOAT_EQ(m.minnaert_k, 0.8f);
}

TEST(SceneLoader, LightingSectionParsesEveryKey) {
    const lab::Scene s = parse(with(R"("lighting": {"model": "cook_torrance", "shading": "gouraud",
        "spot_falloff": "edge", "distribution": "beckmann", "toon_bands": 6, "markers": true, "nan_check": "on"})"));
    EXPECT_EQ(s.lighting.model, lab::LightingDesc::Model::CookTorrance);
    EXPECT_EQ(s.lighting.shading, lab::LightingDesc::Shading::Gouraud);
    EXPECT_EQ(s.lighting.spot_falloff, lab::LightingDesc::SpotFalloff::Edge);
    EXPECT_EQ(s.lighting.distribution, lab::LightingDesc::Distribution::Beckmann);
    EXPECT_EQ(s.lighting.toon_bands, 6);
    EXPECT_TRUE(s.lighting.markers);
    EXPECT_EQ(s.lighting.nan_check, lab::LightingDesc::NanCheck::On);
    const char* models[] = {"lambert", "phong", "blinn_phong", "toon", "oren_nayar", "minnaert", "cook_torrance", "ward"};
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(int(parse(with(std::string(R"("lighting": {"model": ")") + models[i] + "\"}")).lighting.model), i);
    const char* shadings[] = {"flat", "gouraud", "phong"};
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(int(parse(with(std::string(R"("lighting": {"shading": ")") + shadings[i] + "\"}")).lighting.shading), i);
}

TEST(SceneLoader, LightingMaterialKeysParse) {
    const lab::Scene s = parse(R"({"objects": [], "materials": {"m": {"roughness": 0.25, "f0": [1, 0.71, 0.29],
        "roughness_x": 0.1, "roughness_y": 0.6, "minnaert_k": 1.5}}})");
    const lab::MaterialDesc& m = s.materials.at("m");
    EXPECT_FLOAT_EQ(m.roughness, 0.25f);
    expect_vec3(m.f0, 1.0f, 0.71f, 0.29f);
    EXPECT_FLOAT_EQ(m.roughness_x, 0.1f);
    EXPECT_FLOAT_EQ(m.roughness_y, 0.6f);
    EXPECT_FLOAT_EQ(m.minnaert_k, 1.5f);
}

TEST(SceneLoader, BadLightingValuesAreRejected) {
    expect_error(with(R"("lighting": {"model": "blinn"})"), "lighting.model: ",
                 "unknown lighting model 'blinn'; did you mean 'blinn_phong'?");
    expect_error(with(R"("lighting": {"shading": "smooth"})"), "lighting.shading: ", "unknown shading model 'smooth'");
    expect_error(with(R"("lighting": {"spot_falloff": "linear"})"), "lighting.spot_falloff: ", "unknown spot falloff");
    expect_error(with(R"("lighting": {"distribution": "ggx2"})"), "lighting.distribution: ", "did you mean 'ggx'?");
    expect_error(with(R"("lighting": {"toon_bands": 0})"), "lighting.toon_bands: ", "must be in [1, 16], got 0");
    expect_error(with(R"("lighting": {"toon_bands": 2.5})"), "lighting.toon_bands: ", "expected an integer");
    expect_error(with(R"("lighting": {"markers": 1})"), "lighting.markers: ", "expected true or false");
    expect_error(with(R"("lighting": {"nan_check": true})"), "lighting.nan_check: ", "expected a string");
    expect_error(with(R"("lighting": {"modle": "phong"})"), "lighting.modle: ", "did you mean 'model'?");
    expect_error(with(R"("lighting": "phong")"), "lighting: ", "expected an object");
}

TEST(SceneLoader, BadLightingMaterialValuesAreRejected) {
    auto material = [](const std::string& body) {
        return R"({"objects": [], "materials": {"m": {)" + body + "}}}";
    };
    expect_error(material(R"("roughness": 1.5)"), "materials.m.roughness: ", "must be in [0, 1], got 1.5");
    expect_error(material(R"("roughness": -0.1)"), "materials.m.roughness: ", "must be in [0, 1]");
    expect_error(material(R"("f0": [0.5, -0.1, 0])"), "materials.m.f0[1]: ", "must be >= 0");
    expect_error(material(R"("f0": [0.5, 1.5, 0])"), "materials.m.f0: ", "must be <= 1");
    expect_error(material(R"("roughness_x": 0)"), "materials.m.roughness_x: ", "must be in [0.01, 1], got 0");
    expect_error(material(R"("roughness_y": 2)"), "materials.m.roughness_y: ", "must be in [0.01, 1]");
    expect_error(material(R"("minnaert_k": 5)"), "materials.m.minnaert_k: ", "must be in [0, 4], got 5");
}

// --- lab 4: shadows and translucency ------------------------------------------------

TEST(SceneLoader, ShadowDefaultsAreTheOnesOfSceneH) {
    const lab::Scene s = parse(light(R"({"type": "directional"})"));
    const lab::LightDesc& l = s.lights.at(0);
    const lab::ShadowDesc defaults;
    EXPECT_FALSE(l.cast_shadows);
    EXPECT_EQ(l.shadow.resolution, defaults.resolution);
    EXPECT_EQ(l.shadow.pcf, defaults.pcf);
    EXPECT_EQ(l.shadow.filter, defaults.filter);
    EXPECT_FLOAT_EQ(l.shadow.bias, defaults.bias);
    EXPECT_FLOAT_EQ(l.shadow.slope_bias, defaults.slope_bias);
    EXPECT_FLOAT_EQ(l.shadow.normal_offset, defaults.normal_offset);
    EXPECT_FALSE(l.shadow.fit_to_view);
    EXPECT_FLOAT_EQ(s.materials.at("m").opacity, 1.0f);
    EXPECT_TRUE(s.objects.at(0).cast_shadows);
}

TEST(SceneLoader, ShadowKeysParseForEveryLightType) {
    const char* lights[] = {
        R"({"type": "directional", "cast_shadows": true, "shadow": {"resolution": 512, "pcf": 5,
            "filter": "nearest", "bias": 0.005, "slope_bias": 2.5, "normal_offset": 0.75}})",
        R"({"type": "point", "cast_shadows": true, "shadow": {"resolution": 1, "pcf": 1, "filter": "bilinear",
            "bias": 0, "slope_bias": 0, "normal_offset": 0, "fit_to_view": true}})",
        R"({"type": "spot", "cast_shadows": false, "shadow": {"resolution": 16384, "pcf": 15}})"};
    const lab::LightDesc d = parse(light(lights[0])).lights.at(0);
    EXPECT_TRUE(d.cast_shadows);
    EXPECT_EQ(d.shadow.resolution, 512);
    EXPECT_EQ(d.shadow.pcf, 5);
    EXPECT_EQ(d.shadow.filter, lab::ShadowDesc::Filter::Nearest);
    EXPECT_FLOAT_EQ(d.shadow.bias, 0.005f);
    EXPECT_FLOAT_EQ(d.shadow.slope_bias, 2.5f);
    EXPECT_FLOAT_EQ(d.shadow.normal_offset, 0.75f);
    const lab::LightDesc p = parse(light(lights[1])).lights.at(0);
    EXPECT_TRUE(p.cast_shadows);
    EXPECT_EQ(p.shadow.resolution, 1);
    EXPECT_EQ(p.shadow.pcf, 1);
    EXPECT_EQ(p.shadow.filter, lab::ShadowDesc::Filter::Bilinear);
    EXPECT_FLOAT_EQ(p.shadow.bias, 0.0f);
    EXPECT_FLOAT_EQ(p.shadow.slope_bias, 0.0f);
    EXPECT_FLOAT_EQ(p.shadow.normal_offset, 0.0f);
    EXPECT_TRUE(p.shadow.fit_to_view);
    EXPECT_FALSE(d.shadow.fit_to_view);
    const lab::LightDesc sp = parse(light(lights[2])).lights.at(0);
    EXPECT_FALSE(sp.cast_shadows);
    EXPECT_EQ(sp.shadow.resolution, 16384);
    EXPECT_EQ(sp.shadow.pcf, 15);
    EXPECT_FLOAT_EQ(sp.shadow.bias, lab::ShadowDesc{}.bias);  // untouched keys keep their defaults
}

TEST(SceneLoader, OpacityAndObjectCastShadowsParse) {
    const lab::Scene s = parse(R"({"materials": {"glass": {"opacity": 0.25}, "wall": {"opacity": 0}, "solid": {"opacity": 1}},
        "objects": [{"mesh": "cube", "material": "glass", "cast_shadows": false},
                    {"mesh": "plane", "material": "wall", "cast_shadows": true}]})");
    EXPECT_FLOAT_EQ(s.materials.at("glass").opacity, 0.25f);
    EXPECT_FLOAT_EQ(s.materials.at("wall").opacity, 0.0f);
    EXPECT_FLOAT_EQ(s.materials.at("solid").opacity, 1.0f);
    EXPECT_FALSE(s.objects.at(0).cast_shadows);
    EXPECT_TRUE(s.objects.at(1).cast_shadows);
}

TEST(SceneLoader, BadShadowValuesAreRejected) {
    const auto shadow = [](const std::string& body) {
        return light(R"({"type": "spot", "cast_shadows": true, "shadow": {)" + body + "}}");
    };
    expect_error(shadow(R"("resolution": 0)"), "lights[0].shadow.resolution: ", "must be in [1, 16384], got 0");
    expect_error(shadow(R"("resolution": 16385)"), "lights[0].shadow.resolution: ", "must be in [1, 16384]");
    expect_error(shadow(R"("resolution": 1024.5)"), "lights[0].shadow.resolution: ", "expected an integer");
    expect_error(shadow(R"("pcf": 4)"), "lights[0].shadow.pcf: ", "must be odd");
    expect_error(shadow(R"("pcf": 0)"), "lights[0].shadow.pcf: ", "must be in [1, 15], got 0");
    expect_error(shadow(R"("pcf": 17)"), "lights[0].shadow.pcf: ", "must be in [1, 15], got 17");
    expect_error(shadow(R"("pcf": "3")"), "lights[0].shadow.pcf: ", "expected a number, got string");
    expect_error(shadow(R"("filter": "linear")"), "lights[0].shadow.filter: ", "unknown shadow filter 'linear'");
    expect_error(shadow(R"("filter": "bilinaer")"), "lights[0].shadow.filter: ", "did you mean 'bilinear'?");
    expect_error(shadow(R"("bias": -0.001)"), "lights[0].shadow.bias: ", "must be >= 0, got -0.001");
    expect_error(shadow(R"("slope_bias": -1)"), "lights[0].shadow.slope_bias: ", "must be >= 0");
    expect_error(shadow(R"("normal_offset": -1)"), "lights[0].shadow.normal_offset: ", "must be >= 0");
    expect_error(shadow(R"("fit_to_view": 1)"), "lights[0].shadow.fit_to_view: ", "expected true or false, got number");
    expect_error(shadow(R"("bias": 1e7)"), "lights[0].shadow.bias: ", "magnitude must be <= 1e6");
    expect_error(shadow(R"("pfc": 3)"), "lights[0].shadow.pfc: ", "did you mean 'pcf'?");
    expect_error(light(R"({"type": "point", "shadow": 2048})"), "lights[0].shadow: ", "expected an object");
    expect_error(light(R"({"type": "point", "cast_shadows": 1})"), "lights[0].cast_shadows: ", "expected true or false");
    expect_error(light(R"({"type": "point", "cast_shadow": true})"), "lights[0].cast_shadow: ",
                 "did you mean 'cast_shadows'?");
}

TEST(SceneLoader, BadOpacityAndObjectCastShadowsAreRejected) {
    const auto material = [](const std::string& body) { return R"({"objects": [], "materials": {"m": {)" + body + "}}}"; };
    expect_error(material(R"("opacity": 1.5)"), "materials.m.opacity: ", "must be in [0, 1], got 1.5");
    expect_error(material(R"("opacity": -0.5)"), "materials.m.opacity: ", "must be in [0, 1], got -0.5");
    expect_error(material(R"("opacity": "half")"), "materials.m.opacity: ", "expected a number");
    expect_error(material(R"("opacty": 0.5)"), "materials.m.opacty: ", "did you mean 'opacity'?");
    expect_error(object_with(R"("cast_shadows": "no")"), "objects[0].cast_shadows: ", "expected true or false");
}

// --- model_matrix -------------------------------------------------------------

namespace {

glm::vec3 transform_point(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
glm::vec3 transform_direction(const glm::mat4& m, const glm::vec3& d) { return glm::vec3(m * glm::vec4(d, 0.0f)); }

void expect_near(const glm::vec3& v, float x, float y, float z) {
    EXPECT_NEAR(v.x, x, 1e-6f);
    EXPECT_NEAR(v.y, y, 1e-6f);
    EXPECT_NEAR(v.z, z, 1e-6f);
}

lab::ObjectDesc object(glm::vec3 position, glm::vec3 rotation_deg, glm::vec3 scale) {
    lab::ObjectDesc o;
    o.position = position;
    o.rotation_deg = rotation_deg;
    o.scale = scale;
    return o;
}

}  // namespace

TEST(ModelMatrix, DefaultObjectIsIdentity) {
    const glm::mat4 m = lab::model_matrix(lab::ObjectDesc{});
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(m[c][r], c == r ? 1.0f : 0.0f);
}

TEST(ModelMatrix, RotationsFollowTheRightHandRule) {
    // 90° about Y: +X -> -Z, +Z -> +X.
    const glm::mat4 ry = lab::model_matrix(object({0, 0, 0}, {0, 90, 0}, {1, 1, 1}));
    expect_near(transform_direction(ry, {1, 0, 0}), 0, 0, -1);
    expect_near(transform_direction(ry, {0, 0, 1}), 1, 0, 0);
    // 90° about X: +Y -> +Z.
    expect_near(transform_direction(lab::model_matrix(object({0, 0, 0}, {90, 0, 0}, {1, 1, 1})), {0, 1, 0}), 0, 0, 1);
    // 90° about Z: +X -> +Y.
    expect_near(transform_direction(lab::model_matrix(object({0, 0, 0}, {0, 0, 90}, {1, 1, 1})), {1, 0, 0}), 0, 1, 0);
}

TEST(ModelMatrix, RotationOrderIsXThenYThenZ) {
    // M = Rz·Ry·Rx: X is applied first. With [90, 90, 0]: +Y -Rx-> +Z -Ry-> +X.
    // (The opposite order would give +Y -Ry-> +Y -Rx-> +Z.)
    expect_near(transform_direction(lab::model_matrix(object({0, 0, 0}, {90, 90, 0}, {1, 1, 1})), {0, 1, 0}), 1, 0, 0);
    // With [90, 90, 90]: +X -Rx-> +X -Ry-> -Z -Rz-> -Z, and +Y -> +Z -> +X -> +Y.
    const glm::mat4 m = lab::model_matrix(object({0, 0, 0}, {90, 90, 90}, {1, 1, 1}));
    expect_near(transform_direction(m, {1, 0, 0}), 0, 0, -1);
    expect_near(transform_direction(m, {0, 1, 0}), 0, 1, 0);
    expect_near(transform_direction(m, {0, 0, 1}), 1, 0, 0);
}

TEST(ModelMatrix, MatchesAHandComputedMatrix) {
    // T(1,2,3) · Ry(90°) · S(2,3,4). Ry(90°) has columns (0,0,-1), (0,1,0), (1,0,0);
    // scaling multiplies column i by s_i; the translation is the last column.
    const glm::mat4 m = lab::model_matrix(object({1, 2, 3}, {0, 90, 0}, {2, 3, 4}));
    const float expected[4][4] = {  // expected[column][row]
        {0, 0, -2, 0},
        {0, 3, 0, 0},
        {4, 0, 0, 0},
        {1, 2, 3, 1}};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], 1e-6f) << "column " << c << " row " << r;
    // Scale first, then rotate, then translate: (1,0,0) -> (2,0,0) -> (0,0,-2) -> (1,2,1).
    expect_near(transform_point(m, {1, 0, 0}), 1, 2, 1);
}

// --- models without a "material": their .mtl materials ---------------------------

TEST(SceneLoader, ModelWithoutMaterialUsesItsMtl) {
    TempDir dir;
    dir.write("two.mtl", "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 10\nnewmtl glow\nKd 0 0 1\nKe 0 1 0\n");
    // Two triangles of "red", one of "glow", one with no material.
    dir.write("two.obj",
              "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
              "f 1 2 3\nusemtl red\nf 1 2 3\nf 1 3 4\nusemtl glow\nf 1 3 4\n");
    dir.write("scene.json", R"({"materials": {}, "objects": [{"mesh": "two.obj", "position": [1, 2, 3]}]})");
    const lab::Scene s = lab::load_scene((dir.path() / "scene.json").string());
    ASSERT_EQ(s.objects.size(), 3u);  // one object per material used, in .mtl order, "no material" first
    EXPECT_EQ(s.objects[0].material, "two.obj#default");
    EXPECT_EQ(s.objects[0].obj_material, -1);
    EXPECT_EQ(s.objects[1].material, "two.obj#red");
    EXPECT_EQ(s.objects[1].obj_material, 0);
    EXPECT_EQ(s.objects[2].material, "two.obj#glow");
    EXPECT_EQ(s.objects[2].position, glm::vec3(1, 2, 3));
    const lab::MaterialDesc& red = s.materials.at("two.obj#red");
    EXPECT_EQ(red.albedo, glm::vec3(1, 0, 0));
    EXPECT_EQ(red.specular, glm::vec3(0.5f));
    EXPECT_EQ(red.shininess, 10.0f);
    EXPECT_EQ(s.materials.at("two.obj#glow").emissive, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.materials.at("two.obj#default").albedo, lab::MaterialDesc{}.albedo);
    // Each part's mesh holds exactly its own triangles.
    EXPECT_EQ(lab::make_mesh(s.objects[0]).indices.size(), 3u);
    EXPECT_EQ(lab::make_mesh(s.objects[1]).indices.size(), 6u);
    EXPECT_EQ(lab::make_mesh(s.objects[2]).indices.size(), 3u);
    // A MeshLibrary (one read of the file for all parts) gives the same parts.
    lab::MeshLibrary library;
    for (const lab::ObjectDesc& part : s.objects) {
        EXPECT_EQ(library.mesh(part).indices, lab::make_mesh(part).indices);
        EXPECT_EQ(library.mesh(part).vertices.size(), lab::make_mesh(part).vertices.size());
    }
}

TEST(SceneLoader, ModelWithAMaterialKeyIsOneObject) {
    TempDir dir;
    dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
    dir.write("scene.json", R"({"materials": {"m": {}}, "objects": [{"mesh": "m.obj", "material": "m"}]})");
    const lab::Scene s = lab::load_scene((dir.path() / "scene.json").string());
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].obj_material, lab::ObjectDesc::kAllTriangles);
    EXPECT_EQ(lab::make_mesh(s.objects[0]).indices.size(), 3u);
}

TEST(SceneLoader, BrokenModelWithoutMaterialIsASceneError) {
    TempDir dir;
    dir.write("bad.obj", "v 0 0 0\nf 1 2 3\n");
    dir.write("scene.json", R"({"materials": {}, "objects": [{"mesh": "bad.obj"}]})");
    try {
        lab::load_scene((dir.path() / "scene.json").string());
        FAIL() << "expected a SceneError";
    } catch (const lab::SceneError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("objects[0].mesh: "), std::string::npos) << message;
        EXPECT_NE(message.find("out of range"), std::string::npos) << message;
    }
}
