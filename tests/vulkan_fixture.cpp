#include "tests/vulkan_fixture.h"

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <filesystem>

namespace tessera::test {

void VulkanTest::SetUp() {
  ContextOptions options;
  options.device = "lavapipe";
  options.validation = true;
  ctx_ = create_context(options);
}

void VulkanTest::TearDown() {
  // Move the log out first: destroying the context may itself report (leaked objects).
  ValidationLog* log = ctx_->validation.get();
  ASSERT_NE(log, nullptr);
  std::unique_ptr<ValidationLog> keep = std::move(ctx_->validation);
  // Keep the messenger's user pointer alive until the instance is gone.
  ctx_.reset();
  EXPECT_EQ(keep->errors.load(), 0u) << "validation errors reported";
  EXPECT_EQ(keep->warnings.load(), 0u) << "validation warnings reported";
  for (const std::string& m : keep->messages) ADD_FAILURE() << m;
}

VulkanTest::Frame VulkanTest::render(const Scene& scene, uint32_t width, uint32_t height,
                                     RendererOptions options, uint32_t samples) {
  Renderer renderer(*ctx_, options);
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
