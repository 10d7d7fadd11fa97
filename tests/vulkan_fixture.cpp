#include "tests/vulkan_fixture.h"

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "compute/vk_check.h"

namespace tessera::test {

namespace {

// One lavapipe context for every Vulkan test of the process. lavapipe translates each pipeline's
// SPIR-V anew for every device (its disk cache keeps only the machine code), which cost each test
// about 0.7 s before it rendered anything; with one device, a test suite's tests (ctest runs a
// suite per process: tests/suite_tests.cmake) build each pipeline once between them.
std::unique_ptr<Context>& shared_context() {
  static std::unique_ptr<Context> ctx;
  return ctx;
}

// The validation layer is on unless TESSERA_TEST_VALIDATION=0. The plain suite keeps it on;
// scripts/test-sanitize.sh turns it off because the same tests have already run under it there
// (nothing a sanitizer changes reaches Vulkan), and under AddressSanitizer's allocator the layer
// made in-process tests about 25 % slower (Shading, ShadeTiles and TileLists: 103 -> 80 s).
// The tool's own --validate runs (CLI tests) keep it either way.
bool validation_wanted() {
  const char* value = std::getenv("TESSERA_TEST_VALIDATION");
  return value == nullptr || std::string(value) != "0";
}

// Fails the test (ADD_FAILURE) for every report `log` holds, then empties it.
void report_validation(ValidationLog& log, const char* when) {
  EXPECT_EQ(log.errors.load(), 0u) << "validation errors reported " << when;
  EXPECT_EQ(log.warnings.load(), 0u) << "validation warnings reported " << when;
  for (const std::string& m : log.messages) ADD_FAILURE() << m;
  log.clear();
}

// Destroys the shared context when the test program ends, and fails the program if the layer
// reports anything then (objects a test leaked are reported as the device is destroyed).
class SharedContextEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    std::unique_ptr<Context>& ctx = shared_context();
    if (!ctx) return;
    // Move the log out first: destroying the context may itself report (leaked objects).
    std::unique_ptr<ValidationLog> keep = std::move(ctx->validation);
    // Keep the messenger's user pointer alive until the instance is gone.
    ctx.reset();
    if (keep) report_validation(*keep, "while the device was destroyed");
  }
};
::testing::Environment* const kSharedContextEnvironment =
    ::testing::AddGlobalTestEnvironment(new SharedContextEnvironment);

}  // namespace

void VulkanTest::SetUp() {
  std::unique_ptr<Context>& ctx = shared_context();
  if (!ctx) {
    ContextOptions options;
    options.device = "lavapipe";
    options.validation = validation_wanted();
    ctx = create_context(options);
  }
  // An earlier test's reports failed that test already.
  if (ctx->validation) ctx->validation->clear();
}

void VulkanTest::TearDown() {
  Context& ctx = *shared_context();
  VK_CHECK(vkDeviceWaitIdle(ctx.device));
  if (ctx.validation) report_validation(*ctx.validation, "during the test");
}

Context& VulkanTest::context() {
  return *shared_context();
}

VulkanTest::Frame VulkanTest::render(const Scene& scene, uint32_t width, uint32_t height,
                                     RendererOptions options, uint32_t samples) {
  Renderer renderer(context(), options);
  return render(renderer, scene, width, height, samples, options.debug_coverage);
}

VulkanTest::Frame VulkanTest::render(Renderer& renderer, const Scene& scene, uint32_t width,
                                     uint32_t height, uint32_t samples, bool coverage) {
  FrameSettings settings;
  settings.width = width;
  settings.height = height;
  settings.samples = samples;
  return render(renderer, scene, settings, coverage);
}

VulkanTest::Frame VulkanTest::render(Renderer& renderer, const Scene& scene,
                                     const FrameSettings& settings, bool coverage) {
  renderer.set_scene(scene);
  Frame f;
  f.stats = renderer.render(settings);
  f.hdr = renderer.read_hdr();
  f.ldr = renderer.read_ldr();
  f.visibility = renderer.read_visibility();
  if (coverage) f.coverage = renderer.read_coverage();
  return f;
}

FrameSettings frame_of(uint32_t width, uint32_t height, uint32_t samples) {
  FrameSettings f;
  f.width = width;
  f.height = height;
  f.samples = samples;
  return f;
}

std::string output_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path("test_output") /
                              (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

int run_command(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
  int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace tessera::test
