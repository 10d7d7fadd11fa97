#include "tests/support/image_assertions.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace tessera::testing {
namespace {

std::string file_stem(const char* expression) {
  std::string s;
  for (const char* p = expression; *p; ++p) s += std::isalnum(uint8_t(*p)) ? *p : '_';
  while (s.find("__") != std::string::npos) s.erase(s.find("__"), 1);
  return s.substr(0, 60);
}

bool within(const ImageDifference& d, const ImageTolerance& t) {
  const double hard = t.hard_max_error >= 0.0         ? t.hard_max_error
                      : t.allowed_fraction_over > 0.0 ? std::numeric_limits<double>::infinity()
                                                      : t.max_error;
  return d.max_abs_error <= hard && d.fraction_over <= t.allowed_fraction_over;
}

Image8 to_display(const ImageF& image) {
  Image8 out{image.width, image.height, std::vector<glm::u8vec4>(image.pixels.size())};
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      out.pixels[i][c] = uint8_t(std::clamp(double(image.pixels[i][c]), 0.0, 1.0) * 255.0 + 0.5);
    }
    out.pixels[i].a = 255;
  }
  return out;
}

template <typename Image>
::testing::AssertionResult report(const char* actual_expr, const char* expected_expr,
                                  const Image& actual, const Image& expected,
                                  const ImageTolerance& tolerance) {
  if (actual.width != expected.width || actual.height != expected.height) {
    return ::testing::AssertionFailure()
           << actual_expr << " is " << actual.width << "x" << actual.height << " but "
           << expected_expr << " is " << expected.width << "x" << expected.height;
  }
  const ImageDifference d = compare_images(actual, expected, tolerance.max_error);
  if (within(d, tolerance)) return ::testing::AssertionSuccess();
  const std::string stem = file_stem(actual_expr);
  const std::string a = test_output_path(stem + "_actual.png");
  const std::string e = test_output_path(stem + "_expected.png");
  const std::string diff = test_output_path(stem + "_difference.png");
  const double scale = std::max(tolerance.max_error * 4.0, 1e-6);
  if constexpr (std::is_same_v<Image, ImageF>) {
    write_png(a, to_display(actual));
    write_png(e, to_display(expected));
    write_hdr_image(test_output_path(stem + "_actual.pfm"), actual);
    write_hdr_image(test_output_path(stem + "_expected.pfm"), expected);
  } else {
    write_png(a, actual);
    write_png(e, expected);
  }
  write_png(diff, difference_image(actual, expected, scale));
  std::ostringstream m;
  m << actual_expr << " differs from " << expected_expr << " beyond the tolerance (max error "
    << tolerance.max_error << ", fraction over " << tolerance.allowed_fraction_over << ", hard max "
    << tolerance.hard_max_error << "):\n"
    << "  max error " << d.max_abs_error << " at (" << d.worst_x << ", " << d.worst_y
    << "): actual (" << d.worst_actual.r << ", " << d.worst_actual.g << ", " << d.worst_actual.b
    << "), expected (" << d.worst_expected.r << ", " << d.worst_expected.g << ", "
    << d.worst_expected.b << ")\n"
    << "  RMSE " << d.rmse << ", PSNR " << d.psnr_db << " dB, " << d.pixels_over << " of "
    << d.pixels << " pixels (" << d.fraction_over * 100.0 << " %) over " << tolerance.max_error
    << "\n"
    << "  images: " << a << ", " << e << ", " << diff
    << " (difference: black equal, red >= " << scale << ")";
  return ::testing::AssertionFailure() << m.str();
}

}  // namespace

std::string test_output_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = "test_output";
  if (info) dir /= std::string(info->test_suite_name()) + "." + info->name();
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

::testing::AssertionResult ImagesNear(const char* actual_expr, const char* expected_expr,
                                      const char*, const Image8& actual, const Image8& expected,
                                      const ImageTolerance& tolerance) {
  return report(actual_expr, expected_expr, actual, expected, tolerance);
}

::testing::AssertionResult ImagesNear(const char* actual_expr, const char* expected_expr,
                                      const char*, const ImageF& actual, const ImageF& expected,
                                      const ImageTolerance& tolerance) {
  return report(actual_expr, expected_expr, actual, expected, tolerance);
}

::testing::AssertionResult MatchesGolden(const char* actual_expr, const char*, const char*,
                                         const Image8& actual, const std::string& golden_path,
                                         const ImageTolerance& tolerance) {
  const char* update = std::getenv("TESSERA_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    std::filesystem::path p(golden_path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    write_png(golden_path, actual);
    std::printf("updated golden %s\n", golden_path.c_str());
    return ::testing::AssertionSuccess();
  }
  if (!std::filesystem::exists(golden_path)) {
    return ::testing::AssertionFailure()
           << "golden image " << golden_path
           << " does not exist; run the test with TESSERA_UPDATE_GOLDENS=1 "
              "to create it from "
           << actual_expr << ", then review and commit it";
  }
  const Image8 golden = read_png(golden_path);
  return report(actual_expr, golden_path.c_str(), actual, golden, tolerance);
}

bool same_bits(const ImageF& a, const ImageF& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

}  // namespace tessera::testing
