// `tessera view` in a real window on a virtual X server (Xvfb), on lavapipe with the
// validation layer: what it presents, read back from the swapchain image before the overlay,
// against headless renders of the same scene and camera; scripted camera moves against hand
// calculation; picking against projected object centres; resizes, minimising and a long run.
// Without an X server the tests are skipped, naming why.
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <thread>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/renderer.h"
#include "core/check.h"
#include "core/materials.h"
#include "host/scene_source.h"
#include "host/view_script.h"
#include "tests/vulkan_fixture.h"

namespace tessera::test {
namespace {

// One virtual X server for every viewer these tests run, with xvfb-run's screen (1280x1024,
// 24 bits), started on first use and stopped when the test program ends. A server per run
// (xvfb-run -a) cost each of the suite's 51 viewer runs about 0.2 s of waiting for it to start.
// The viewer leaves nothing on the server when it exits (its window goes with its connection).
// Where the server could not start, `display` is empty and `error` says why.
struct SharedXServer {
  std::string display;  // ":N"
  std::string error;
  pid_t pid = 0;
  SharedXServer() {
    std::string out;
    if (run_command("command -v Xvfb", out) != 0) {
      error = "Xvfb is not installed (Debian package xvfb)";
      return;
    }
    // Not a test's output folder, which its test may empty (fresh_folder).
    const std::string folder = std::filesystem::absolute("test_output/View.x_server").string();
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    // -displayfd: the server picks a free display and writes its number once it accepts
    // connections. Its output goes to files, so that no pipe of this program stays open in it.
    if (run_command("Xvfb -displayfd 3 -nolisten tcp -screen 0 1280x1024x24 3>" + folder +
                        "/display >/dev/null 2>" + folder + "/server.log & echo $!",
                    out) != 0 ||
        (pid = std::atoi(out.c_str())) <= 0) {
      error = "Xvfb does not start: " + out;
      return;
    }
    // At most 60 s, a guard against a server that never comes up, not a measurement.
    for (int i = 0; i < 6000 && display.empty(); ++i) {
      std::ifstream file(folder + "/display");
      int number = -1;
      if (file >> number) display = ":" + std::to_string(number);
      if (display.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (display.empty()) {
      std::ifstream log(folder + "/server.log");
      error = "Xvfb did not report a display within 60 s: " +
              std::string(std::istreambuf_iterator<char>(log), {});
    }
  }
  ~SharedXServer() {
    if (pid > 0) kill(pid, SIGTERM);
  }
};

const SharedXServer& x_server() {
  static const SharedXServer server;
  return server;
}

// Why no viewer can run here, or "" if one can.
const std::string& no_display_reason() {
  return x_server().error;
}

#define SKIP_WITHOUT_X_SERVER() \
  if (!no_display_reason().empty()) GTEST_SKIP() << no_display_reason()

struct ViewRun {
  int status = -1;
  std::string output;
};

// This test's output folder, emptied.
std::string fresh_folder() {
  const std::string folder = std::filesystem::path(output_path("x")).parent_path().string();
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

// Runs the viewer on lavapipe with validation (unless `validate` is false), replaying `script`,
// in the working folder `folder` if given.
ViewRun run_view(const std::string& script, const std::string& options, bool validate = true,
                 const std::string& folder = "") {
  const std::string path = std::filesystem::absolute(output_path("script.txt")).string();
  std::ofstream(path) << script;
  ViewRun run;
  run.status = run_command(
      (folder.empty() ? "" : "cd " + folder + " && ") + "DISPLAY=" + x_server().display +
          " XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} " TESSERA_BINARY " view --device lavapipe" +
          std::string(validate ? " --validate" : "") + " --vsync off --script " + path + " " +
          options,
      run.output);
  return run;
}

// The last camera the viewer printed ("frame N: camera position x y z target x y z").
bool last_camera(const std::string& output, Camera& camera) {
  static const std::regex line("camera position (\\S+) (\\S+) (\\S+) target (\\S+) (\\S+) (\\S+)");
  bool found = false;
  for (auto it = std::sregex_iterator(output.begin(), output.end(), line);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    camera.position = {std::stof(m[1]), std::stof(m[2]), std::stof(m[3])};
    camera.target = {std::stof(m[4]), std::stof(m[5]), std::stof(m[6])};
    found = true;
  }
  return found;
}

std::vector<uint64_t> numbers_after(const std::string& output, const std::string& label) {
  std::vector<uint64_t> values;
  const std::regex pattern(label + " (\\d+)");
  for (auto it = std::sregex_iterator(output.begin(), output.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    values.push_back(std::stoull((*it)[1]));
  }
  return values;
}

class View : public VulkanTest {
 protected:
  // The scene `name` as the viewer loads it, and its frame settings at `width` x `height`.
  static Scene scene_named(const std::string& name, FrameSettings& frame, uint32_t width,
                           uint32_t height) {
    SceneFile file = load_scene_argument(name, false, true);
    frame.width = width;
    frame.height = height;
    apply_render_defaults(file.render, frame, true, false, false, false);
    return std::move(file.scene);
  }

  Image8 headless(const Scene& scene, const FrameSettings& frame) {
    Renderer renderer(context());
    renderer.set_scene(scene);
    renderer.render(frame);
    return renderer.read_ldr();
  }

  void expect_same_image(const std::string& png, const Image8& expected) {
    const Image8 shown = read_png(png);
    ASSERT_EQ(shown.width, expected.width) << png;
    ASSERT_EQ(shown.height, expected.height) << png;
    size_t differing = 0;
    for (size_t i = 0; i < shown.pixels.size(); ++i)
      differing += shown.pixels[i] != expected.pixels[i];
    EXPECT_EQ(differing, 0u) << png << ": pixels differing from the headless render";
  }
};

TEST(ViewScript, ReadsEveryEvent) {
  const std::vector<ScriptEvent> events = parse_view_script(
      "# a comment\n"
      "0 key Z ctrl\n1 drag middle 1 2 3 4 shift\n2 click 5 6\n2 wheel -1.5\n"
      "3 resize 333 77\n4 minimise\n5 restore\n6 screenshot a.png\n7 save b.json\n"
      "7 memory\n8 exit # the end\n"
      "9 light add\n9 light 2 position -1 2.5 3\n9 light 0 delete\n",
      "s.txt");
  ASSERT_EQ(events.size(), 14u);
  EXPECT_EQ(events[11].event.kind, EventKind::light);
  EXPECT_EQ(events[11].event.field, "add");
  EXPECT_EQ(events[12].event.index, 2u);
  EXPECT_EQ(events[12].event.field, "position");
  EXPECT_EQ(events[12].event.value, glm::vec3(-1.0f, 2.5f, 3.0f));
  EXPECT_EQ(events[13].event.field, "delete");
  EXPECT_EQ(events[0].event.kind, EventKind::key);
  EXPECT_EQ(events[0].event.key, 'Z');
  EXPECT_TRUE(events[0].event.ctrl);
  EXPECT_EQ(events[1].event.button, MouseButton::middle);
  EXPECT_EQ(events[1].event.from, glm::vec2(1, 2));
  EXPECT_EQ(events[1].event.to, glm::vec2(3, 4));
  EXPECT_TRUE(events[1].event.shift);
  EXPECT_EQ(events[2].frame, 2u);
  EXPECT_EQ(events[3].event.wheel, -1.5f);
  EXPECT_EQ(events[4].event.width, 333u);
  EXPECT_EQ(events[4].event.height, 77u);
  EXPECT_EQ(events[7].event.path, "a.png");
  EXPECT_EQ(events[8].event.path, "b.json");
  EXPECT_EQ(events[10].event.kind, EventKind::exit);
  EXPECT_EQ(events[10].frame, 8u);
}

// What a scene file may hold, a script may set (validate_scene's limits).
TEST(ViewScript, LightValuesReachTheScenesLimits) {
  const std::vector<ScriptEvent> events =
      parse_view_script("1 light 0 intensity 1e26\n2 light 0 position -1e15 0 1e15\n", "s.txt");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].event.value.x, 1e26f);
  EXPECT_EQ(events[1].event.value, glm::vec3(-1e15f, 0.0f, 1e15f));
}

TEST(ViewScript, ErrorsNameFileLineAndWhatIsWrong) {
  const std::pair<const char*, const char*> cases[] = {
      {"1 exit\n0 exit\n", "s.txt:2: frame 0 comes before the previous line's frame 1"},
      {"x exit\n", "s.txt:1: expects a frame number first, got 'x'"},
      {"1 jump\n", "s.txt:1: unknown event 'jump'"},
      {"\n1 key\n", "s.txt:2: key: missing key name (key NAME [ctrl] [shift])"},
      {"1 key Tab\n", "s.txt:1: unknown key 'Tab'"},
      {"1 drag left 1 2 3\n", "s.txt:1: drag: missing Y1 (drag left|middle X0 Y0 X1 Y1 [shift])"},
      // Named as the form names them (a fresh user's trial got "missing x" for X1).
      {"1 drag left 10 20\n", "s.txt:1: drag: missing X1 (drag left|middle X0 Y0 X1 Y1 [shift])"},
      {"1 click 5\n", "s.txt:1: click: missing Y (click X Y)"},
      {"1 drag up 1 2 3 4\n", "s.txt:1: unknown button 'up'"},
      // A right drag does nothing in the window.
      {"1 drag right 1 2 3 4\n", "s.txt:1: unknown button 'right' (left orbits, middle pans)"},
      {"1 tonemap filmic\n", "s.txt:1: unknown tone map 'filmic' (aces, reinhard, clamp)"},
      {"1 exposure\n", "s.txt:1: exposure: missing exposure (exposure EV)"},
      {"1 click 1 2 3\n", "s.txt:1: unexpected '3'"},
      {"1 resize 0 5\n", "s.txt:1: width expects a number from 1 to 16384, got '0'"},
      {"1 resize 2.5 5\n", "s.txt:1: width expects a whole number"},
      {"1 screenshot a.jpg\n", "s.txt:1: screenshot expects a .png path"},
      {"1 key A alt\n", "s.txt:1: unexpected 'alt'"},
      {"1 light 0 dim\n", "s.txt:1: unknown light action 'dim'"},
      {"1 light 1.5 delete\n", "s.txt:1: light index expects a whole number"},
      // The scene's own limits (a fresh user's trial: 1e9 was the script's, 1e26 a file's).
      {"1 light 0 intensity 1e27\n", "s.txt:1: intensity expects a number from 0 to 1e+26, got"},
      {"1 light 0 position 2e15 0 0\n",
       "s.txt:1: coordinate expects a number from -1e+15 to 1e+15, got '2e15'"},
  };
  for (const auto& [text, message] : cases) {
    try {
      parse_view_script(text, "s.txt");
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
          << "'" << e.what() << "' lacks '" << message << "'";
    }
  }
  try {
    load_view_script("no/such/script.txt");
    ADD_FAILURE() << "no error for a missing script";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "script file 'no/such/script.txt' not found");
  }
}

TEST_F(View, PresentedImageEqualsTheHeadlessRender) {
  SKIP_WITHOUT_X_SERVER();
  for (const std::string path : {"direct", "copy"}) {
    for (const std::string name : {"spheres", "lights"}) {
      const std::string png = output_path(name + "_" + path + ".png");
      const ViewRun run = run_view("2 screenshot " + png + "\n2 exit\n",
                                   "--scene " + name + " --size 160x120 --present " + path);
      ASSERT_EQ(run.status, 0) << run.output;
      FrameSettings frame;
      const Scene scene = scene_named(name, frame, 160, 120);
      expect_same_image(png, headless(scene, frame));
    }
  }
}

// Both ways to the swapchain image (the resolve pass writing it, or Tessera's image copied into
// it) and both kinds of format (lavapipe's X11 surfaces offer B8G8R8A8 UNORM and sRGB) show the
// headless render's bytes: an sRGB image holds the encoded bytes once, as the PNG does.
TEST_F(View, EveryPresentPathAndFormatShowsTheHeadlessRender) {
  SKIP_WITHOUT_X_SERVER();
  FrameSettings frame;
  const Scene scene = scene_named("lights", frame, 96, 72);
  const Image8 expected = headless(scene, frame);
  struct Case {
    const char* options;
    const char* says;
    bool validate;
  };
  const Case cases[] = {
      {"--present auto --surface-format unorm", "B8G8R8A8_UNORM images directly", true},
      {"--present copy --surface-format unorm", "B8G8R8A8_UNORM images by copy", true},
      {"--present auto --surface-format srgb", "B8G8R8A8_SRGB images by copy", true},
      // Valid usage that the installed validation layer reports falsely (VUID-
      // VkSwapchainCreateInfoKHR-imageFormat-01778 for storage use through the UNORM view of a
      // mutable-format swapchain, whose images count as created with EXTENDED_USAGE), so this
      // one case runs without the layer.
      {"--present direct --surface-format srgb", "B8G8R8A8_SRGB images directly", false},
  };
  for (const Case& c : cases) {
    const std::string png = output_path("path.png");
    std::filesystem::remove(png);
    const ViewRun run =
        run_view("2 screenshot " + png + "\n2 exit\n",
                 std::string("--scene lights --size 96x72 ") + c.options, c.validate);
    ASSERT_EQ(run.status, 0) << c.options << "\n" << run.output;
    EXPECT_NE(run.output.find(std::string("presenting ") + c.says), std::string::npos)
        << c.options << "\n"
        << run.output;
    expect_same_image(png, expected);
  }
}

TEST_F(View, ResizesToOddSizesMinimisesAndRestores) {
  SKIP_WITHOUT_X_SERVER();
  for (const std::string path : {"direct", "copy"}) {
    const std::string tiny = output_path("1x1.png"), odd = output_path("333x77.png"),
                      back = output_path("restored.png");
    const ViewRun run = run_view(
        "1 resize 1 1\n"
        "4 screenshot " +
            tiny +
            "\n"
            "5 resize 333 77\n"
            "8 screenshot " +
            odd +
            "\n"
            "9 minimise\n"
            "15 restore\n"
            "16 resize 96 64\n"
            "19 screenshot " +
            back +
            "\n"
            "19 exit\n",
        "--scene spheres --size 160x120 --present " + path);
    ASSERT_EQ(run.status, 0) << run.output;
    FrameSettings frame;
    const Scene scene = scene_named("spheres", frame, 1, 1);
    expect_same_image(tiny, headless(scene, frame));
    frame.width = 333;
    frame.height = 77;
    expect_same_image(odd, headless(scene, frame));
    frame.width = 96;
    frame.height = 64;
    expect_same_image(back, headless(scene, frame));
  }
}

TEST_F(View, ScriptedOrbitMovesTheCameraAsComputedByHand) {
  SKIP_WITHOUT_X_SERVER();
  const std::string png = output_path("orbit.png");
  // core/orbit_camera.h: a drag turns pi per window height (96 px here): yaw -= dx pi / 96,
  // pitch += dy pi / 96. So 100 px right, then 40 px up.
  const ViewRun run = run_view(
      "1 drag left 10 50 110 50\n"
      "2 drag left 110 50 110 10\n"
      "4 screenshot " +
          png + "\n4 exit\n",
      "--scene spheres --size 128x96 --overlay off");  // the panel would take the drags
  ASSERT_EQ(run.status, 0) << run.output;
  Camera camera;
  ASSERT_TRUE(last_camera(run.output, camera)) << run.output;
  // The spheres camera stands at (0, 0, 22) looking at the origin: yaw 0, pitch 0, with the
  // orbit basis r = +x, u = +y, b = +z. The eye goes to
  // 22 (cos(pitch) sin(yaw), sin(pitch), cos(pitch) cos(yaw)).
  const float pi = 3.14159265358979f;
  const float d = 22.0f, azimuth = -100.0f * pi / 96.0f, elevation = -40.0f * pi / 96.0f;
  const glm::vec3 expected{d * std::cos(elevation) * std::sin(azimuth), d * std::sin(elevation),
                           d * std::cos(elevation) * std::cos(azimuth)};
  EXPECT_NEAR(camera.position.x, expected.x, 1e-4f);
  EXPECT_NEAR(camera.position.y, expected.y, 1e-4f);
  EXPECT_NEAR(camera.position.z, expected.z, 1e-4f);
  EXPECT_EQ(camera.target, glm::vec3(0.0f));
  // And the window showed that camera's image.
  FrameSettings frame;
  Scene scene = scene_named("spheres", frame, 128, 96);
  scene.camera.position = camera.position;
  scene.camera.target = camera.target;
  expect_same_image(png, headless(scene, frame));
}

TEST_F(View, ClickSelectsTheObjectUnderThePixel) {
  SKIP_WITHOUT_X_SERVER();
  FrameSettings frame;
  const Scene scene = scene_named("spheres", frame, 160, 120);
  // Each sphere's centre, projected by hand-built matrices; spheres do not overlap on screen
  // from the front, so the centre's pixel shows that sphere.
  const glm::mat4 clip =
      projection_matrix(scene.camera, 160.0f / 120.0f) * view_matrix(scene.camera);
  std::string script;
  std::vector<uint32_t> expected;
  for (uint32_t i : {0u, 8u, 24u, 48u}) {
    const glm::vec4 c = clip * scene.objects[i].transform * glm::vec4(0, 0, 0, 1);
    const float x = (c.x / c.w * 0.5f + 0.5f) * 160.0f, y = (c.y / c.w * 0.5f + 0.5f) * 120.0f;
    script += std::to_string(expected.size() + 1) + " click " + std::to_string(int(x)) + " " +
              std::to_string(int(y)) + "\n";
    expected.push_back(i);
  }
  // The background, then a save without edits (a selection is none): no file is written.
  script += "9 click 0 0\n9 key S ctrl\n10 exit\n";
  // In a folder of its own: notes of autosaves left where tests run would name them here.
  const ViewRun run =
      run_view(script, "--scene spheres --size 160x120 --overlay off", true, fresh_folder());
  ASSERT_EQ(run.status, 0) << run.output;
  std::vector<uint64_t> selected = numbers_after(run.output, "selected object");
  ASSERT_EQ(selected.size(), expected.size()) << run.output;
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(selected[i], expected[i]);
  EXPECT_NE(run.output.find("click at 0 0: nothing under the cursor"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("nothing to save: no edits since the scene was loaded or saved "
                            "(spheres.json not written)"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("-1"), std::string::npos) << run.output;
}

TEST_F(View, MaterialEditGivesTheEditedScenesImage) {
  SKIP_WITHOUT_X_SERVER();
  // In a folder of its own, where the unsaved edit's autosave goes (not where tests run).
  const std::string folder = fresh_folder();
  const std::string png = std::filesystem::absolute(output_path("gold.png")).string();
  // The centre pixel shows sphere 24, the middle of the 7x7 grid.
  const ViewRun run = run_view(
      "1 click 80 60\n2 material preset gold\n3 material roughness 0.2\n"
      "4 screenshot " +
          png + "\n4 exit\n",
      "--scene spheres --size 160x120 --overlay off", true, folder);
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_NE(run.output.find("selected object 24"), std::string::npos) << run.output;
  FrameSettings frame;
  Scene scene = scene_named("spheres", frame, 160, 120);
  Material& m = scene.materials[scene.objects[24].material];
  m.base_color = find_metal_preset("gold")->f0;
  m.metallic = 1.0f;
  m.roughness = 0.2f;
  expect_same_image(png, headless(scene, frame));
}

TEST_F(View, DeleteUndoAndSaveGiveTheHeadlessImages) {
  SKIP_WITHOUT_X_SERVER();
  const std::string before = output_path("before.png"), deleted = output_path("deleted.png"),
                    undone = output_path("undone.png"), saved = output_path("saved.json");
  const ViewRun run = run_view("0 screenshot " + before +
                                   "\n"
                                   "1 click 80 60\n2 key Delete\n3 screenshot " +
                                   deleted + "\n4 key Z ctrl\n5 screenshot " + undone +
                                   "\n6 key Y ctrl\n7 save " + saved + "\n7 exit\n",
                               "--scene spheres --size 160x120 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_NE(run.output.find("selected object 24"), std::string::npos) << run.output;
  FrameSettings frame;
  Scene scene = scene_named("spheres", frame, 160, 120);
  const Image8 original = headless(scene, frame);
  expect_same_image(before, original);
  expect_same_image(undone, original);
  scene.objects.erase(scene.objects.begin() + 24);
  const Image8 without = headless(scene, frame);
  expect_same_image(deleted, without);
  // The saved scene (the redone deletion) reloads to the same image.
  SceneFile reloaded = load_scene_file(saved);
  EXPECT_EQ(reloaded.scene.objects.size(), 48u);
  const Image8 again = headless(reloaded.scene, frame);
  EXPECT_EQ(again.pixels, without.pixels);
}

// A small scene, so that many frames take seconds on lavapipe.
std::string write_ball_scene() {
  const std::string scene = output_path("ball.json");
  std::ofstream(scene) << R"({"version": 1,
    "camera": {"position": [0, 0, 4], "target": [0, 0, 0]},
    "materials": [{"name": "red", "base_color": [0.8, 0.1, 0.1], "roughness": 0.4}],
    "meshes": [{"name": "ball", "type": "sphere", "segments": 8}],
    "objects": [{"mesh": "ball", "material": "red"}],
    "lights": [{"type": "point", "position": [2, 4, 3], "intensity": 60}]})";
  return scene;
}

// core/orbit_camera.h: a scripted fly key moves target and eye together by
// fly_distances_per_second (1) * distance * 0.1 s, along the view direction (W), the view's
// right axis (D) or world up (E). The ball's camera stands at (0, 0, 4) looking down -z, so
// each step is 0.4 m along -z, +x and +y.
TEST_F(View, FlyKeysMoveTheCameraByTheHandComputedDistance) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_ball_scene();
  const std::string png = output_path("fly.png");
  const ViewRun run = run_view("1 key W\n2 key D\n3 key E\n5 screenshot " + png + "\n5 exit\n",
                               "--scene " + scene_path + " --size 64x48");
  ASSERT_EQ(run.status, 0) << run.output;
  Camera camera;
  ASSERT_TRUE(last_camera(run.output, camera)) << run.output;
  const glm::vec3 target{0.4f, 0.4f, -0.4f}, position{0.4f, 0.4f, 3.6f};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(camera.target[i], target[i], 1e-5f) << i;
    EXPECT_NEAR(camera.position[i], position[i], 1e-5f) << i;
  }
  FrameSettings frame;
  Scene scene = scene_named(scene_path, frame, 64, 48);
  scene.camera.position = camera.position;
  scene.camera.target = camera.target;
  expect_same_image(png, headless(scene, frame));
}

// A unit ball at the origin and one of scale 0.5 at (3, 0, 0), seen from (0, 0, 4).
std::string write_two_balls_scene() {
  const std::string scene_path = output_path("two_balls.json");
  std::ofstream(scene_path) << R"({"version": 1,
    "camera": {"position": [0, 0, 4], "target": [0, 0, 0]},
    "materials": [{"name": "red", "base_color": [0.8, 0.1, 0.1], "roughness": 0.4}],
    "meshes": [{"name": "ball", "type": "sphere", "segments": 8}],
    "objects": [{"mesh": "ball", "material": "red"},
                {"mesh": "ball", "material": "red", "translation": [3, 0, 0], "scale": 0.5}],
    "lights": [{"type": "point", "position": [2, 4, 3], "intensity": 60}]})";
  return scene_path;
}

// F frames the whole scene. Two unit-sphere balls, one at the origin and one of scale 0.5 at
// (3, 0, 0): their bounding spheres' box spans x in [-1, 3.5], so the centre is (1.25, 0, 0)
// and the radius max(1.25 + 1, 1.75 + 0.5) = 2.25. In a 128x96 window the vertical field
// (45 degrees) is the narrower, so the distance is 2.25 / sin(22.5 degrees); yaw and pitch stay
// 0, so the eye is that far along +z from the centre.
TEST_F(View, FKeyFramesTheWholeScene) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_two_balls_scene();
  const ViewRun run = run_view("1 key F\n2 exit\n", "--scene " + scene_path + " --size 128x96");
  ASSERT_EQ(run.status, 0) << run.output;
  Camera camera;
  ASSERT_TRUE(last_camera(run.output, camera)) << run.output;
  const float distance = 2.25f / std::sin(glm::radians(22.5f));
  EXPECT_NEAR(camera.target.x, 1.25f, 1e-5f);
  EXPECT_NEAR(camera.target.y, 0.0f, 1e-5f);
  EXPECT_NEAR(camera.target.z, 0.0f, 1e-5f);
  EXPECT_NEAR(camera.position.x, 1.25f, 1e-5f);
  EXPECT_NEAR(camera.position.y, 0.0f, 1e-5f);
  EXPECT_NEAR(camera.position.z, distance, 1e-4f);
}

// F on a model smaller than the scene camera's near distance (a ball of radius 2 mm, near plane
// 0.1 m): framed from 0.002 / sin(22.5 degrees) = 5.2 mm, the near plane comes in to half the
// gap (1.6 mm), so the ball fills the middle of the image rather than being clipped away to
// the background (it was, before the F key moved the near plane).
TEST_F(View, FKeyFramesAModelInsideTheNearDistance) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = output_path("tiny_ball.json");
  std::ofstream(scene_path) << R"({"version": 1, "background": [0, 0, 0],
    "camera": {"position": [0, 0, 4], "target": [0, 0, 0]},
    "materials": [{"name": "red", "base_color": [0.8, 0.1, 0.1], "roughness": 1}],
    "meshes": [{"name": "ball", "type": "sphere", "segments": 8}],
    "objects": [{"mesh": "ball", "material": "red", "scale": 0.002}],
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 3}]})";
  const std::string png = output_path("tiny_ball.png");
  const ViewRun run = run_view("1 key F\n2 screenshot " + png + "\n3 exit\n",
                               "--scene " + scene_path + " --size 64x48 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  const Image8 shown = read_png(png);
  const auto centre = shown.at(32, 24);
  EXPECT_GT(centre.r, 100) << "the ball is lit red in the middle, not the black background";
  EXPECT_LT(centre.g, centre.r / 2);
}

// Shift+F frames the selected object alone and Home goes back to the scene's camera. In the
// two balls' scene framed by F (target (1.25, 0, 0), distance 2.25 / sin(22.5 degrees) =
// 5.8796, looking down -z), the small ball's centre (3, 0, 0) is 1.75 m right of the target, so
// at x = (1.75 / 5.8796 / (tan(22.5 degrees) 128 / 96) + 1) 64 = 98.3 px, y = 48. Its sphere is
// the unit sphere's (the mesh's vertices all lie on it) at scale 0.5, so Shift+F puts the
// target at (3, 0, 0) and the eye 0.5 / sin(22.5 degrees) = 1.30656 m along +z: the sphere just
// fits the vertical field, the narrower one.
TEST_F(View, ShiftFFramesTheSelectionAndHomeGoesBack) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_two_balls_scene();
  const ViewRun run = run_view("1 key F\n2 click 98 48\n3 key F shift\n4 exit\n",
                               "--scene " + scene_path + " --size 128x96 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_NE(run.output.find("selected object 1"), std::string::npos) << run.output;
  Camera camera;
  ASSERT_TRUE(last_camera(run.output, camera)) << run.output;
  const float distance = 0.5f / std::sin(glm::radians(22.5f));
  const glm::vec3 target{3.0f, 0.0f, 0.0f}, position{3.0f, 0.0f, distance};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(camera.target[i], target[i], 1e-5f) << i;
    EXPECT_NEAR(camera.position[i], position[i], 1e-5f) << i;
  }
  const ViewRun home = run_view("1 key F\n2 key Home\n3 exit\n",
                                "--scene " + scene_path + " --size 128x96 --overlay off");
  ASSERT_EQ(home.status, 0) << home.output;
  ASSERT_TRUE(last_camera(home.output, camera)) << home.output;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(camera.target[i], 0.0f, 1e-5f) << i;
    EXPECT_NEAR(camera.position[i], i == 2 ? 4.0f : 0.0f, 1e-5f) << i;
  }
}

// The panel's render options are edits like the others: a scripted tone map and exposure show
// in the image, are saved in the render block, and undo restores the options (and so the
// saved block); setting an option to what it is adds no step, and Ctrl+S without edits leaves
// the file alone. With the panel shown, a click where it was drawn is the panel's (nothing
// picked), one beside it picks the ball.
TEST_F(View, RenderOptionsAreUndoableEditsSavedInTheRenderBlock) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_ball_scene();
  const std::string png = output_path("reinhard.png"), edited = output_path("options.json"),
                    undone = output_path("options_undone.json");
  std::string before;
  {
    std::ifstream in(scene_path);
    before.assign(std::istreambuf_iterator<char>(in), {});
  }
  // A 640 x 240 window: the panel is 40% of the width, 256 px from x = 8; the ball is at the
  // centre.
  const ViewRun run = run_view(
      "0 key S ctrl\n1 tonemap reinhard\n1 tonemap reinhard\n"
      "2 exposure 1.5\n3 screenshot " +
          png + "\n3 save " + edited + "\n4 key Z ctrl\n5 key Z ctrl\n6 save " + undone +
          "\n6 click 20 20\n6 click 320 120\n7 exit\n",
      "--scene " + scene_path + " --size 640x240");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("nothing to save"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("tone map reinhard: already so"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("click at 20 20: on the panel"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("selected object 0"), std::string::npos) << run.output;
  // Two undo steps took both options back: the session ends without unsaved edits.
  EXPECT_EQ(run.output.find("unsaved edits written"), std::string::npos) << run.output;
  std::string after;
  {
    std::ifstream in(scene_path);
    after.assign(std::istreambuf_iterator<char>(in), {});
  }
  EXPECT_EQ(after, before);
  const SceneFile saved = load_scene_file(edited);
  EXPECT_EQ(saved.render.tonemap, ToneMap::reinhard);
  EXPECT_EQ(saved.render.exposure_ev, 1.5f);
  const SceneFile back = load_scene_file(undone);
  EXPECT_FALSE(back.render.tonemap.has_value());
  EXPECT_FALSE(back.render.exposure_ev.has_value());
  FrameSettings frame;
  const Scene scene = scene_named(scene_path, frame, 640, 240);
  frame.tonemap = ToneMap::reinhard;
  frame.exposure_ev = 1.5f;
  expect_same_image(png, headless(scene, frame));
}

// The panel's light controls, replayed by the script through the same changes the panel makes:
// add a light at the eye, move and dim it, delete the scene's own light. The window then shows
// the headless render of the scene edited by hand.
TEST_F(View, PanelLightControlsGiveTheEditedScenesImage) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_ball_scene();
  const std::string png = output_path("lights_edited.png");
  const ViewRun run = run_view(
      "1 light add\n2 light 1 position -2 1 3\n3 light 1 intensity 30\n"
      "3 light 1 color 0.5 0.75 1\n4 light 0 delete\n6 screenshot " +
          png + "\n6 exit\n",
      "--scene " + scene_path + " --size 64x48");
  ASSERT_EQ(run.status, 0) << run.output;
  FrameSettings frame;
  Scene scene = scene_named(scene_path, frame, 64, 48);
  Light light;  // a point light, as the panel's button adds
  light.position = {-2.0f, 1.0f, 3.0f};
  light.intensity = 30.0f;
  light.color = {0.5f, 0.75f, 1.0f};
  scene.lights = {light};
  expect_same_image(png, headless(scene, frame));
}

// A screenshot that cannot be written says why, and the session goes on (the next one is
// written); as a script is a test, the failed scripted one makes the exit status 1, said at
// the end.
TEST_F(View, UnwritableScreenshotSaysWhyAndFailsTheScript) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_ball_scene();
  const std::string png = output_path("after_unwritable.png");
  std::filesystem::remove(png);
  const ViewRun run =
      run_view("1 screenshot /nonexistent-dir/shot.png\n2 screenshot " + png + "\n3 exit\n",
               "--scene " + scene_path + " --size 32x24");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("frame 1: screenshot /nonexistent-dir/shot.png not written: folder "
                            "'/nonexistent-dir' does not exist"),
            std::string::npos)
      << run.output;
  EXPECT_TRUE(std::filesystem::exists(png)) << run.output;
  EXPECT_NE(run.output.find("tessera: error: 1 script command failed (said above)\n"),
            std::string::npos)
      << run.output;
}

// Every scripted command the viewer cannot carry out says why, as the frame's log line, and
// counts: the session goes on, and at the end the count is said and the exit status is 1.
// Here: a light the scene lacks (the ball scene has one), a material edit and a delete with
// nothing selected, an undo with nothing to undo. Doing what is asked, or finding it already
// done (an option set to what it is, a save with nothing to save), is no failure.
TEST_F(View, ScriptCommandsThatCannotBeCarriedOutFailTheScript) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene_path = write_ball_scene();
  const ViewRun run = run_view(
      "1 light 9 intensity 3\n2 material roughness 0.5\n3 key Delete\n4 key Z ctrl\n"
      "5 tonemap aces\n5 key S ctrl\n6 light 0 intensity 3\n7 exit\n",
      "--scene " + scene_path + " --size 32x24 --overlay off");
  EXPECT_EQ(run.status, 1) << run.output;
  for (const std::string said :
       {"frame 1: no light 9 (the scene has 1)\n",
        "frame 2: no object selected to change the material of\n",
        "frame 3: no object selected to delete\n", "frame 4: nothing to undo\n"})
    EXPECT_NE(run.output.find(said), std::string::npos) << said << " in\n" << run.output;
  EXPECT_NE(run.output.find("tessera: error: 4 script commands failed (said above)\n"),
            std::string::npos)
      << run.output;
  // The session went on: the last edit was made, and kept in the autosave.
  EXPECT_NE(run.output.find("change light 0"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("tessera: note: unsaved edits written to "), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("tone map aces: already so"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("nothing to save"), std::string::npos) << run.output;
}

// A starting size the device cannot render is refused as `render` refuses it, before the
// window and the renderer: --size is a bad command line (status 2) naming --size, a scene file's
// "render" size an error placed at its entry (line 2, column 12). 16384 x 16384 keys of 8
// bytes are 2048 MiB; lavapipe's storage buffers hold 128 MiB, 2^24 keys: 4096 x 4096.
TEST_F(View, AStartingSizeTheDeviceCannotRenderIsRefusedAsRenderRefusesIt) {
  SKIP_WITHOUT_X_SERVER();
  const std::string too_big =
      "needs a 2048 MiB visibility buffer, more than this device's maxStorageBufferRange (128 "
      "MiB): it takes at most 16777216 pixels at 1 sample, e.g. 4096x4096";
  ViewRun run = run_view("1 exit\n", "--size 16384x16384", false);
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("tessera: error: --size 16384x16384: " + too_big + "\n"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("tessera view --help"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("compiling shaders"), std::string::npos) << run.output;
  const std::string big_scene = output_path("big_view.json");
  std::ofstream(big_scene) << "{\"ambient\": [1, 1, 1],\n \"render\": {\"width\": 16384, "
                              "\"height\": 16384}}\n";
  run = run_view("1 exit\n", "--scene " + big_scene, false);
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(
      run.output.find("tessera: error: " + big_scene + ":2:12: render: the size 16384x16384 " +
                      too_big + " (--size overrides it)\n"),
      std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("compiling shaders"), std::string::npos) << run.output;
  // --size overrides it.
  run = run_view("1 exit\n", "--scene " + big_scene + " --size 32x24", false);
  EXPECT_EQ(run.status, 0) << run.output;
}

// A scene with nothing to light it is noted (not warned about: --strict still opens it); a lit
// one is not.
TEST_F(View, UnlitSceneIsNoted) {
  SKIP_WITHOUT_X_SERVER();
  const std::string unlit = output_path("unlit.json");
  std::ofstream(unlit) << R"({"materials": [{"name": "m"}],
    "meshes": [{"name": "c", "type": "cube"}], "objects": [{"mesh": "c", "material": "m"}]})";
  ViewRun run = run_view("1 exit\n", "--strict --scene " + unlit + " --size 32x24");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: " + unlit +
                            " has no lights, ambient light, environment or emissive material: "
                            "its objects are black\n"),
            std::string::npos)
      << run.output;
  run = run_view("1 exit\n", "--strict --scene " + write_ball_scene() + " --size 32x24");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("has no lights"), std::string::npos) << run.output;
}

// A light within 1 cm of an object is noted as `render` notes it (scene_file_test.cpp): a cube
// of side 2 um and a light 2 um above its top.
TEST_F(View, LightsWithinTheDistanceFloorAreNoted) {
  SKIP_WITHOUT_X_SERVER();
  const std::string micro = output_path("micro.json");
  std::ofstream(micro) << R"({"materials": [{"name": "m"}],
    "meshes": [{"name": "c", "type": "cube"}], "objects": [{"mesh": "c", "material": "m",
    "scale": 1e-6}], "camera": {"position": [0, 0, 8e-6], "near": 1e-6},
    "lights": [{"type": "point", "position": [0, 3e-6, 0], "intensity": 1e-12}]})";
  const ViewRun run = run_view("1 exit\n", "--scene " + micro + " --size 32x24");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: light 0 of " + micro +
                            " lies 2e-06 m from object 0: the shading treats "
                            "distances below 1 cm as 1 cm, "),
            std::string::npos)
      << run.output;
}

TEST_F(View, LeavingWithUnsavedEditsWritesAnAutosave) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const std::string autosave = output_path("ball.autosave.json");
  std::filesystem::remove(autosave);
  const ViewRun run = run_view("1 click 32 24\n2 key Delete\n3 exit\n",
                               "--scene " + scene + " --size 64x48 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: unsaved edits written to " + autosave),
            std::string::npos)
      << run.output;
  EXPECT_TRUE(load_scene_file(autosave).scene.objects.empty());
  EXPECT_EQ(load_scene_file(scene).scene.objects.size(), 1u);  // the scene file is untouched
}

// A window made larger than the device renders (on lavapipe, 128 MiB of visibility buffer)
// is left undrawn, said once, until it is made smaller; the session and its edits go on.
TEST_F(View, AWindowTooLargeForTheDeviceWaitsUntilMadeSmaller) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const std::string autosave = output_path("ball.autosave.json");
  const std::string png = output_path("after_resize.png");
  std::filesystem::remove(autosave);
  std::filesystem::remove(png);
  // 8192 x 4097 pixels of 8-byte keys is 256 MiB and 8192 B over, so 257 MiB rounded up.
  // The screenshot asked for while the window is too large waits for the next drawn frame.
  const ViewRun run =
      run_view("1 click 32 24\n2 key Delete\n3 resize 8192 4097\n" + std::string("5 screenshot ") +
                   png + "\n6 resize 64 48\n9 exit\n",
               "--scene " + scene + " --size 64x48 --overlay off", false);
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string refused =
      "the window's 8192x4097 pixels are not drawn: a frame of that size needs a 257 MiB "
      "visibility buffer, more than this device's maxStorageBufferRange (128 MiB)";
  const size_t first = run.output.find(refused);
  EXPECT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(refused, first + 1), std::string::npos) << run.output;  // once
  EXPECT_NE(run.output.find("frame 5: screenshot " + png +
                            " waits: the window is too large to draw (said above)"),
            std::string::npos)
      << run.output;
  const Image8 shot = read_png(png);
  EXPECT_EQ(shot.width, 64u);
  EXPECT_EQ(shot.height, 48u);
  EXPECT_TRUE(load_scene_file(autosave).scene.objects.empty());  // the edit was kept
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// An earlier session's autosave holds edits this session does not have: it is noted at the
// start, and this session's unsaved edits go beside it under the next free name.
TEST_F(View, AnEarlierSessionsAutosaveIsNeverOverwritten) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = fresh_folder();
  const std::string scene = write_ball_scene();
  const std::string earlier = folder + "/ball.autosave.json";
  std::ofstream(earlier) << "the earlier session's edits";
  const std::string script = "1 click 32 24\n2 key Delete\n3 exit\n";
  const std::string options = "--scene " + scene + " --size 64x48 --overlay off";
  ViewRun run = run_view(script, options);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(
      run.output.find("tessera: note: " + earlier + " holds unsaved edits of an earlier session"),
      std::string::npos)
      << run.output;
  const std::string second = folder + "/ball.autosave-2.json";
  EXPECT_NE(run.output.find("unsaved edits written to " + second + " (" + earlier +
                            ", of an earlier session, left as it is)"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(read_text(earlier), "the earlier session's edits");
  EXPECT_TRUE(load_scene_file(second).scene.objects.empty());
  // A third session notes both and writes a third.
  run = run_view(script, options);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: " + second + " holds unsaved edits"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("unsaved edits written to " + folder + "/ball.autosave-3.json"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(read_text(earlier), "the earlier session's edits");
}

// A built-in scene's autosave has a name no scene file's autosave has: NAME.json saved beside
// it (whose autosave is NAME.autosave.json) and the built-in NAME never take each other's
// autosaves for their own. Both were NAME.autosave.json: each session noted the other scene's
// as its own earlier session's, and wrote NAME.autosave-2.json beside it.
TEST_F(View, ABuiltInScenesAutosaveIsNotASceneFilesOfTheSameName) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = fresh_folder();
  std::filesystem::copy_file(write_ball_scene(), folder + "/spheres.json");
  std::ofstream(folder + "/spheres.autosave.json") << "the scene file's earlier edits";
  ViewRun run = run_view("1 click 80 60\n2 key Delete\n3 exit\n",
                         "--scene spheres --size 160x120 --overlay off", true, folder);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("spheres.autosave.json holds"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("tessera: note: unsaved edits written to "
                            "spheres.builtin-autosave.json\n"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(read_text(folder + "/spheres.autosave.json"), "the scene file's earlier edits");
  EXPECT_EQ(load_scene_file(folder + "/spheres.builtin-autosave.json").scene.objects.size(), 48u);
  // The scene file's session notes its own autosave, not the built-in's, and writes beside it.
  run = run_view("1 click 32 24\n2 key Delete\n3 exit\n",
                 "--scene spheres.json --size 64x48 --overlay off", true, folder);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: spheres.autosave.json holds unsaved edits of an "
                            "earlier session"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("spheres.builtin-autosave.json holds"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("unsaved edits written to spheres.autosave-2.json "
                            "(spheres.autosave.json, of an earlier session, left as it is)"),
            std::string::npos)
      << run.output;
  EXPECT_TRUE(load_scene_file(folder + "/spheres.autosave-2.json").scene.objects.empty());
  // The built-in's next session notes only its own.
  run = run_view("1 exit\n", "--scene spheres --size 160x120 --overlay off", true, folder);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("tessera: note: spheres.builtin-autosave.json holds unsaved edits"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("spheres.autosave"), std::string::npos) << run.output;
}

// Ctrl+S and a scripted `save` on a built-in scene write NAME.json in the working folder, but
// never over a NAME.json the session did not write: the first free NAME-N.json instead, which
// is then the session's file.
TEST_F(View, SavingABuiltInSceneNeverOverwritesAnUnrelatedFile) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = fresh_folder();
  std::ofstream(folder + "/spheres.json") << "an unrelated file";
  const ViewRun run = run_view(
      "1 click 80 60\n2 key Delete\n3 key S ctrl\n4 exposure 1.5\n"
      "5 save\n6 exit\n",
      "--scene spheres --size 160x120 --overlay off", true, folder);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(read_text(folder + "/spheres.json"), "an unrelated file");
  EXPECT_NE(run.output.find("frame 3: saved spheres-2.json (spheres.json was there already and is "
                            "not this session's file: left as it is)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("frame 5: saved spheres-2.json\n"), std::string::npos) << run.output;
  const SceneFile saved = load_scene_file(folder + "/spheres-2.json");
  EXPECT_EQ(saved.scene.objects.size(), 48u);
  ASSERT_TRUE(saved.render.exposure_ev.has_value());
  EXPECT_EQ(*saved.render.exposure_ev, 1.5f);
  EXPECT_EQ(run.output.find("unsaved edits written"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(folder + "/spheres-3.json"));
}

// A failed save says why; a failed scripted save makes the exit status 1.
TEST_F(View, AFailedScriptedSaveSaysWhyAndExitsWithStatus1) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = fresh_folder();
  const std::string scene = write_ball_scene();
  const std::string target = folder + "/ro.json";
  std::filesystem::create_directories(target + ".tmp");
  const ViewRun run = run_view("1 click 32 24\n2 key Delete\n3 save " + target + "\n4 exit\n",
                               "--scene " + scene + " --size 64x48 --overlay off");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("frame 3: not saved: cannot write the scene file '" + target +
                            "': its temporary file '" + target + ".tmp': it is a folder"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("tessera: error: 1 script command failed (said above)\n"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(std::filesystem::exists(target));
  // The edits were not saved: they went to the autosave.
  EXPECT_TRUE(load_scene_file(folder + "/ball.autosave.json").scene.objects.empty());
}

// After `save PATH` the session's scene is PATH: nothing is unsaved (no autosave), and Ctrl+S
// saves there.
TEST_F(View, SaveUnderAnotherNameMakesThatFileTheSessions) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = fresh_folder();
  const std::string scene = write_ball_scene();
  const std::string other = folder + "/other.json";
  ViewRun run = run_view("1 click 32 24\n2 key Delete\n3 save " + other + "\n4 exit\n",
                         "--scene " + scene + " --size 64x48 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("unsaved edits written"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(folder + "/ball.autosave.json"));
  EXPECT_TRUE(load_scene_file(other).scene.objects.empty());
  EXPECT_EQ(load_scene_file(scene).scene.objects.size(), 1u);
  run = run_view("1 save " + other + "\n2 light add\n3 key S ctrl\n4 exit\n",
                 "--scene " + scene + " --size 64x48 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("frame 3: saved " + other), std::string::npos) << run.output;
  EXPECT_EQ(load_scene_file(other).scene.lights.size(), 2u);
  EXPECT_EQ(load_scene_file(scene).scene.lights.size(), 1u);
  EXPECT_FALSE(std::filesystem::exists(folder + "/ball.autosave.json"));
}

// A change that needs a shading pipeline not built before in the session (a light added, a
// BRDF not drawn yet) stalls a CPU device for seconds; the viewer says so before the frame.
// Undo and redo go back to light sets already built: nothing to say. The ball has one point
// light, drawn with the classic BRDF at the start.
TEST_F(View, NewLightSetsAreSaidToBeSpecialized) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const ViewRun run = run_view("1 light add\n2 key Z ctrl\n3 key Y ctrl\n4 brdf filament\n5 exit\n",
                               "--scene " + scene + " --size 32x24 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string specializing =
      ": specializing the shaders to the new set of lights and "
      "options (seconds on a CPU device; once a session for each "
      "set)...\n";
  EXPECT_NE(run.output.find("frame 1: add light" + specializing), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("frame 4: BRDF filament" + specializing), std::string::npos)
      << run.output;
  size_t said = 0;
  for (size_t at = run.output.find("specializing"); at != std::string::npos;
       at = run.output.find("specializing", at + 1))
    said++;
  EXPECT_EQ(said, 2u) << run.output;
}

// A camera move that leaves the camera where it was is no change: no log line, no upload. The
// ball's viewport is 64 x 48, so a drag turns pi / 48 per pixel of height (core/orbit_camera.h):
// 40 px down raises the eye by 2.6 rad, past the 89 degrees pitch is clamped to, and a second
// such drag finds it there.
TEST_F(View, CameraMovesThatChangeNothingAreNoChange) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const ViewRun run = run_view(
      "1 drag left 10 5 10 5\n2 wheel 0\n3 drag left 10 5 10 45\n4 drag left 10 5 10 45\n"
      "5 exit\n",
      "--scene " + scene + " --size 64x48 --overlay off");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("frame 3: camera position"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("frame 3: camera: uploaded"), std::string::npos) << run.output;
  for (const std::string frame : {"frame 1: ", "frame 2: ", "frame 4: "})
    EXPECT_EQ(run.output.find(frame), std::string::npos) << frame << " in\n" << run.output;
  // At the pole: pitch 89 degrees, the eye 4 m from the target.
  Camera camera;
  ASSERT_TRUE(last_camera(run.output, camera)) << run.output;
  EXPECT_NEAR(camera.position.y, 4.0f * std::sin(glm::radians(89.0f)), 1e-5f);
}

// A scripted click outside the window (here 64 x 64: x and y run 0..63) picks nothing and is a
// script command that cannot be carried out.
TEST_F(View, ClickOutsideTheWindowFailsTheScript) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const ViewRun run = run_view("1 click 500 500\n2 click 64 10\n3 click 63 63\n4 exit\n",
                               "--scene " + scene + " --size 64x64 --overlay off");
  EXPECT_EQ(run.status, 1) << run.output;
  for (const std::string said : {"frame 1: click at 500 500: outside the 64x64 window\n",
                                 "frame 2: click at 64 10: outside the 64x64 window\n",
                                 "frame 3: click at 63 63: nothing under the cursor\n",
                                 "tessera: error: 2 script commands failed (said above)\n"})
    EXPECT_NE(run.output.find(said), std::string::npos) << said << " in\n" << run.output;
}

// The X server going away (here: killed while the viewer runs a script that has edited) ends
// the session as an error does: the unsaved edits go to the autosave, and the error says what
// happened. Xlib's own handler would have exited at once ("XIO: fatal IO error ..."). The
// viewer runs on an Xvfb of this test's own (-displayfd picks a free display), so that the
// server alone can be killed.
TEST_F(View, LosingTheXServerWritesTheAutosave) {
  SKIP_WITHOUT_X_SERVER();
  const std::string folder = std::filesystem::absolute(fresh_folder()).string();
  const std::string scene = std::filesystem::absolute(write_ball_scene()).string();
  const std::string script = folder + "/script.txt";
  std::ofstream(script) << "1 click 32 24\n2 key Delete\n1000000 exit\n";
  // Waits (at most 600 s, a guard against a hang, not a measurement) for the display, then for
  // the deletion to be on screen; kills the server, and gives the viewer's exit status.
  const std::string command =
      "cd " + folder +
      " && (Xvfb -displayfd 3 -nolisten tcp -screen 0 640x480x24 3>display 2>server.log & "
      "echo $! > server) && n=0; until [ -s display ] || [ $n -ge 6000 ]; do sleep 0.1; "
      "n=$((n+1)); done; DISPLAY=:$(head -n 1 display) XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} " +
      TESSERA_BINARY " view --device lavapipe --vsync off --overlay off --size 64x48 --script " +
      script + " --scene " + scene +
      " > log 2>&1 & viewer=$!; n=0; until grep -q 'delete object 0:' log || "
      "! kill -0 $viewer 2>/dev/null || [ $n -ge 6000 ]; do sleep 0.1; n=$((n+1)); done; "
      "kill $(cat server); wait $viewer; echo $? > status; cat log";
  std::string output;
  run_command(command, output);
  int status = -1;
  std::ifstream(folder + "/status") >> status;
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("frame 2: delete object 0: uploaded"), std::string::npos) << output;
  const std::string autosave = folder + "/ball.autosave.json";
  EXPECT_NE(output.find("tessera: note: unsaved edits written to " + autosave), std::string::npos)
      << output;
  EXPECT_NE(output.find("tessera: error: lost the connection to the X server (display \":"),
            std::string::npos)
      << output;
  EXPECT_EQ(output.find("XIO"), std::string::npos) << output;
  ASSERT_TRUE(std::filesystem::exists(autosave)) << output;
  EXPECT_TRUE(load_scene_file(autosave).scene.objects.empty());
}

TEST_F(View, AThousandFramesLeaveMemoryFlat) {
  SKIP_WITHOUT_X_SERVER();
  const std::string scene = write_ball_scene();
  const ViewRun run =
      run_view("100 memory\n1000 memory\n1000 exit\n", "--scene " + scene + " --size 32x24");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::vector<uint64_t> kib = numbers_after(run.output, "resident memory");
  ASSERT_EQ(kib.size(), 2u) << run.output;
  // Allocator noise is a few hundred KiB; a leak of one small object per frame would be more.
  EXPECT_LT(int64_t(kib[1]) - int64_t(kib[0]), 1024)
      << kib[0] << " KiB at frame 100, " << kib[1] << " KiB at frame 1000";
}

}  // namespace
}  // namespace tessera::test
