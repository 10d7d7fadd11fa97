#include "host/cli.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <tuple>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/closest_name.h"
#include "core/mapped_file.h"
#include "host/cli_values.h"
#include "host/scene_source.h"
#include "host/tradeoff.h"
#include "tessera_version.h"  // generated at build time (cmake/version_header.cmake)

namespace tessera {
namespace {

const std::vector<std::string> kCommands = {"render",   "bench",   "view",
                                            "tradeoff", "devices", "scenes"};

// A file named on the command line that is not there is a bad command line, as a mistyped
// scene name is. What is in a file that exists is read when the command runs, where its errors
// name file and place.
void check_file_exists(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("no file '" + path + "'");
  // A FIFO, a device, a folder: named so now, rather than when the command reads it.
  require_regular_file(path);
}

// The same for a scene or model file; one written as a built-in scene's file name (metals.json,
// from a folder without it) points to the built-in scene.
void check_scene_file_exists(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("'" + path +
                "' is a folder, not a scene file (.json) or model (.gltf, .glb, .obj)");
  if (std::filesystem::exists(path, ec)) {
    require_regular_file(path);
    check_scene_file_format(path);
    return;
  }
  std::string message = "no file '" + path + "'";
  const std::string stem = std::filesystem::path(path).stem().string();
  const std::vector<std::string> known = known_scene_names();
  if (std::find(known.begin(), known.end(), stem) != known.end())
    message += "; the built-in scene '" + stem + "' is --scene " + stem;
  throw Error(message);
}

// Checks that a scene exists, naming every known scene otherwise (as `tessera scenes` lists
// them).
CLI::Validator builtin_scene() {
  return checked_by([](const std::string& name) {
    // A model's file name, even without a folder, is a file, not an unknown scene.
    if (is_scene_path(name) || is_model_path(name)) {
      check_scene_file_exists(name);
    } else {
      check_scene_name(name);
    }
  });
}

// A benchmark family, a built-in scene or a scene or model file; an unknown name is told all three.
CLI::Validator bench_scene() {
  return checked_by([](const std::string& name) {
    if (is_scene_path(name) || is_model_path(name)) {
      check_scene_file_exists(name);
    } else if (!is_builtin_scene(name) && !is_named_scene(name)) {
      try {
        make_bench_scene(name, 1, 8, 1.0f);
      } catch (const Error& e) {
        std::string scenes;
        for (const std::string& s : known_scene_names()) scenes += (scenes.empty() ? "" : ", ") + s;
        throw Error(std::string(e.what()) + "; or a built-in scene (" + scenes +
                    "); or a scene file (.json) or model (.gltf, .glb, .obj)");
      }
    }
  });
}

// A count of at most 9 digits (so it fits uint32_t), for options whose own validation then
// checks the value; anything else is an Error saying what `expected`.
uint32_t parse_count(const std::string& text, const std::string& expected) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    throw Error("expects " + expected + ", got '" + text + "'");
  return uint32_t(std::stoul(text));
}

// A device index past the devices present, naming them (as `tessera devices` lists them). It
// asks the Vulkan loader, so an index on the command line costs an instance here.
void check_device_index(uint32_t index) {
  const std::vector<DeviceInfo> devices = list_devices();
  if (devices.empty())
    throw Error("no Vulkan device found (for the CPU driver: Debian package mesa-vulkan-drivers)");
  if (index < devices.size()) return;
  std::string names;
  for (const DeviceInfo& d : devices)
    names += (d.index ? ", " : "") + std::to_string(d.index) + " '" + d.name + "'";
  throw Error("device index " + std::to_string(index) + " is out of range: only " +
              std::to_string(devices.size()) + (devices.size() == 1 ? " device: " : " devices: ") +
              names + " (`tessera devices`)");
}

// --device: what create_context's choose_device accepts (and, for render, the CPU
// reference), checked here so that a misspelt device is a bad command line (exit status 2).
CLI::Validator device_choice(bool reference, const std::string& reference_here = "") {
  return checked_by([reference, reference_here](const std::string& text) {
    const bool index = !text.empty() && text.size() <= 9 &&
                       text.find_first_not_of("0123456789") == std::string::npos;
    if (index) {
      check_device_index(uint32_t(std::stoul(text)));
      return;
    }
    std::vector<std::string> names = {"lavapipe", "gpu", "auto"};
    if (reference) names.push_back("reference");
    if (std::find(names.begin(), names.end(), text) != names.end()) return;
    // Where the command has the CPU reference in another form, the user meant that.
    if (text == "reference" && !reference_here.empty())
      throw Error("'reference' is not a device for this command: " + reference_here);
    // `tessera devices` prints lavapipe's device by its Vulkan name, llvmpipe.
    const std::string near = closest_name(text, names);
    throw Error("unknown device '" + text + "' (lavapipe, gpu, " +
                (reference ? "reference, " : "") + "or a device index of `tessera devices`)" +
                (near.empty() ? "" : ", did you mean '" + near + "'?"));
  });
}

// --lod and --lod-error, for render and bench.
void add_lod_options(CLI::App& app, Lod& lod, float& error_px) {
  add_choice(app, "--lod", lod, {{"off", Lod::off}, {"auto", Lod::automatic}},
             "level of detail: off (default) draws meshes as\n"
             "they are; auto draws each object at the\n"
             "coarsest level of its chain whose error\n"
             "projects to at most --lod-error, chosen on the\n"
             "GPU every frame");
  app.add_option("--lod-error", error_px,
                 "largest projected error of a level under\n"
                 "--lod auto, in pixels, 0.001..1000 (default\n"
                 "0.5)")
      ->type_name("PIXELS")
      ->check(finite_number(0.001, 1000.0));
}

// --hdr-format, --tile-size and --quality, for render, bench and tradeoff.
void add_hdr_format(CLI::App& app, HdrFormat& format) {
  add_choice(app, "--hdr-format", format, {{"fp16", HdrFormat::fp16}, {"fp32", HdrFormat::fp32}},
             "storage of the linear HDR image: fp16\n"
             "(default; radiance x 2^EV saturates at 65504)\n"
             "or fp32 (no such clamp, twice the bytes)");
}

void add_tile_size(CLI::App& app, uint32_t& tile_size) {
  app.add_option("--tile-size", tile_size,
                 "side of the screen tiles large triangles are\n"
                 "binned into, 8 or 16 (default) px; the image\n"
                 "is the same with either")
      ->type_name("N")
      ->check(checked_by([](const std::string& text) {
        validate_tile_size(parse_count(text, "a tile size of 8 or 16 px"));
      }));
}

// --depth-rejection, for render and bench.
void add_depth_rejection(CLI::App& app, bool& on) {
  add_choice(app, "--depth-rejection", on, {{"on", true}, {"off", false}},
             "hierarchical depth rejection: on (default)\n"
             "skips triangles behind what each tile already\n"
             "drew; off rasterizes all. The image is the same");
}

// --raster-shade, for render and bench.
void add_raster_shade(CLI::App& app, bool& on) {
  add_choice(app, "--raster-shade", on, {{"on", true}, {"off", false}},
             "small frames (up to 512 raster triangles the\n"
             "frame before, one sample) rasterized and shaded\n"
             "in one pass: on, or off for the separate passes.\n"
             "The image is the same. Default: the device's\n"
             "(on for GPUs)");
}

// --shade-tiles, for render and bench.
void add_shade_tiles(CLI::App& app, bool& on) {
  add_choice(app, "--shade-tiles", on, {{"on", true}, {"off", false}},
             "shading by tiles: on runs the shading code\n"
             "only in tiles something was drawn into, the\n"
             "background apart; off shades every pixel. The\n"
             "image is the same. Default: the device's (on\n"
             "for CPU devices such as lavapipe)");
}

// --tile-lists, for render and bench.
void add_tile_lists(CLI::App& app, TileLists& lists) {
  add_choice(app, "--tile-lists", lists,
             {{"automatic", TileLists::automatic},
              {"direct", TileLists::direct},
              {"counted", TileLists::counted}},
             "layout of the binned triangles' tile lists:\n"
             "direct (a fixed room per tile: two passes\n"
             "fewer), counted (counted and packed: least\n"
             "memory) or automatic (direct unless it takes\n"
             "over twice the memory). The image is the\n"
             "same. Default: the device's (automatic on\n"
             "GPUs, counted on CPU devices such as lavapipe)");
}

void add_quality(CLI::App& app, Quality& quality, const std::string& sets) {
  add_choice(app, "--quality", quality,
             {{"draft", Quality::draft},
              {"balanced", Quality::balanced},
              {"reference", Quality::reference}},
             "a preset picked from the measured Pareto\n"
             "fronts (docs/tradeoffs.md, \"Presets\"): sets\n" +
                 sets + ";\noptions given explicitly win");
}

// Whether `app`'s command line gave the option `name`.
std::function<bool(const std::string&)> given_in(const CLI::App& app) {
  return [&app](const std::string& name) {
    return app.get_option_no_throw(name) != nullptr && app.count(name) > 0;
  };
}

// --samples: visibility samples per pixel (FrameSettings::samples).
CLI::Option* add_samples(CLI::App& app, uint32_t& samples, const std::string& help) {
  return app.add_option("--samples", samples, help)
      ->type_name("N")
      ->check(checked_by([](const std::string& text) {
        // One wording for "x" and for "3" (validate_samples words the library's own error).
        const std::string expected = "1, 4, 8 or 16 samples per pixel";
        const uint32_t n = parse_count(text, expected);
        if (n != 1 && n != 4 && n != 8 && n != 16)
          throw Error("expects " + expected + ", got '" + text + "'");
      }));
}

// A coverage mode other than count weighs a pixel's visibility samples; at 1 sample there is
// nothing to weigh and the frame would drop the option silently. That is a bad command line,
// as --samples above 1 is where the hardware backend renders (an option given explicitly that
// the rest of the command line makes do nothing is refused, not ignored).
void check_aa_coverage(const CLI::App& command, uint32_t samples, Quality quality,
                       const std::string& help_command) {
  const CLI::Option* option = command.get_option_no_throw("--aa-coverage");
  if (!option || option->count() == 0 || samples > 1) return;
  const std::string mode = option->results().back();
  if (mode == "count") return;  // one sample's count is that sample: the 1-sample image
  const std::string whence = command.count("--samples") > 0 ? "--samples 1"
                             : quality != Quality::none
                                 ? "1 sample per pixel (--quality " +
                                       command.get_option("--quality")->results().back() + "'s)"
                                 : "1 sample per pixel (the default of --samples)";
  throw UsageError("--aa-coverage " + mode + " does nothing at " + whence +
                       ": it weighs the visibility samples of a pixel; add --samples 4, 8 or 16",
                   help_command);
}

// --aa-walk-steps: the silhouette coverage walk's steps (FrameSettings::silhouette_steps).
void add_aa_walk_steps(CLI::App& app, uint32_t& steps) {
  app.add_option("--aa-walk-steps", steps,
                 "with --aa-coverage silhouette: steps of the\n"
                 "walk that measures a pixel's outline, 2..32,\n"
                 "or 0 (default) for no limit; fewer are faster\n"
                 "and, where triangles are small against a\n"
                 "pixel, less exact")
      ->type_name("N")
      ->check(checked_by([](const std::string& text) {
        const std::string expected = "0 (no limit) or 2..32 steps";
        const uint32_t steps = parse_count(text, expected);
        if (steps == 1 || steps > 32) throw Error("expects " + expected + ", got '" + text + "'");
      }));
}

// --aa-walk-steps shapes the silhouette walk alone: with another coverage mode it would do
// nothing, so it is refused rather than ignored.
void check_aa_walk_steps(AaCoverage coverage, uint32_t steps, const std::string& help_command) {
  // 0, the default (no limit), limits nothing: given or not, there is nothing to ignore.
  if (steps == 0 || coverage == AaCoverage::silhouette) return;
  throw UsageError(
      "--aa-walk-steps does nothing without --aa-coverage silhouette: it limits the walk that "
      "measures a pixel's outline under silhouette coverage",
      help_command);
}

// --aa-coverage: how anti-aliasing weighs a pixel's triangles (FrameSettings::aa_coverage).
void add_aa_coverage(CLI::App& app, AaCoverage& coverage) {
  add_choice(app, "--aa-coverage", coverage,
             {{"count", AaCoverage::count},
              {"analytic", AaCoverage::analytic},
              {"silhouette", AaCoverage::silhouette}},
             "with --samples above 1: count (default)\n"
             "weighs each triangle of a pixel by its share\n"
             "of the samples; analytic, where they see one\n"
             "triangle and the background, by the pixel's\n"
             "area inside its outline edges; silhouette,\n"
             "where they see one surface and the\n"
             "background, by the pixel's area its front\n"
             "faces cover");
}

CLI::Option* add_size(CLI::App& app, uint32_t& width, uint32_t& height, const std::string& help) {
  auto set = [&width, &height](const std::string& text) {
    std::tie(width, height) = read_size(text);
  };
  return app.add_option_function<std::string>("--size", set, help)
      ->type_name("WxH")
      ->check(image_size());
}

// --validate of the commands that only report it (render's help says more).
void add_validate(CLI::App& app, bool& validate) {
  app.add_flag("--validate", validate,
               "enable the Khronos validation layer (exit\nstatus 3 on reports)");
}

// --strict of the commands that load scene files.
void add_strict(CLI::App& app, bool& strict) {
  app.add_flag("--strict", strict,
               "unknown keys in a scene file, and a model's\nwarnings, are errors");
}

// --chart of bench and tradeoff.
void add_chart(CLI::App& app, std::string& chart, const std::string& help) {
  app.add_option("--chart", chart, help)
      ->type_name("FILE")
      ->check(file_with_suffix({".svg", ".png"}))
      ->check(writable_output());
}

// --camera N, for the commands that show a scene file's view. Whether camera N exists is known
// once the scene is loaded (use_model_camera); what is not a camera number at all is refused
// here, in words (CLI11's own text for -1 was "Could not convert: --camera = -1").
void add_camera_option(CLI::App& app, uint32_t& camera) {
  app.add_option("--camera", camera,
                 "view through camera N (from 0) of the scene\n"
                 "file's models or of the model file (glTF\n"
                 "cameras, placed as their model's first\n"
                 "instance) instead of the scene's camera")
      ->type_name("N")
      ->check(checked_by([](const std::string& text) {
        parse_count(text,
                    "a camera number (0 for the first camera of the scene file's models, "
                    "1 for the next, ...)");
      }));
}

void add_render_options(CLI::App& app, RenderArgs& a) {
  app.add_option("--scene", a.scene,
                 "built-in scene (default spheres; see\n"
                 "`tessera scenes`) or a scene file\n"
                 "(docs/scene-format.md), whose \"render\" block\n"
                 "sets size, exposure, tone map and BRDF unless\n"
                 "given here; or a .gltf/.glb/.obj model, seen\n"
                 "from +z with its bounds framed, lit by its own\n"
                 "lights or, having none, by a default sun")
      ->type_name("NAME|FILE")
      ->check(builtin_scene());
  add_size(app, a.frame.width, a.frame.height,
           "image size in pixels, each side 1..16384 and\n"
           "the whole within the device's buffers (on\n"
           "lavapipe 16 M pixels at 1 sample); default\n"
           "512x512");
  app.add_option("--out", a.out, "display image, sRGB (default tessera.png)")
      ->type_name("FILE.png")
      ->check(file_with_suffix({".png"}))
      ->check(writable_output());
  app.add_option("--hdr-out", a.hdr_out,
                 "linear HDR image too, .pfm (exact floats) or\n.hdr (RGBE)")
      ->type_name("FILE")
      ->check(file_with_suffix({".pfm", ".hdr"}))
      ->check(writable_output());
  app.add_option("--device", a.device,
                 "lavapipe, gpu, a device index (default: a\n"
                 "discrete GPU if there is one, else lavapipe),\n"
                 "or reference: the CPU reference renderer in\n"
                 "double precision")
      ->type_name("D")
      ->check(device_choice(true));
  app.add_option("--exposure", a.frame.exposure_ev,
                 "exposure in stops, applied before tone\nmapping, -64..64 (default 0)")
      ->type_name("EV")
      ->check(finite_number(-64.0, 64.0));
  add_choice(app, "--tonemap", a.frame.tonemap,
             {{"aces", ToneMap::aces}, {"reinhard", ToneMap::reinhard}, {"clamp", ToneMap::clamp}},
             "tone curve (default aces)");
  add_choice(app, "--brdf", a.frame.brdf,
             {{"classic", Brdf::classic},
              {"filament", Brdf::filament},
              {"blinn-phong", Brdf::blinn_phong}},
             "classic (default: GGX, Schlick-GGX Smith,\n"
             "Schlick Fresnel), filament (height-correlated\n"
             "Smith) or blinn-phong");
  app.add_flag("--energy-compensation", a.frame.energy_compensation,
               "multiple-scattering energy compensation of\n"
               "the specular lobe (classic and filament), from\n"
               "a DFG table");
  app.add_option("--env", a.env,
                 "light the scene with an environment, also\n"
                 "drawn behind it: FILE.hdr (Radiance) or\n"
                 "FILE.pfm, equirectangular; sky (a procedural\n"
                 "sky); none (the scene's lights only). Default:\n"
                 "the scene's own (only `environment` has one)")
      ->type_name("E")
      ->check(file_with_suffix({".hdr", ".pfm"}, {"sky", "none"}))
      // A missing file is a bad command line, as a missing scene or script is.
      ->check(checked_by([](const std::string& text) {
        if (text != "sky" && text != "none") check_file_exists(text);
      }));
  app.add_option("--env-size", a.env_options.specular_size,
                 "side of the prefiltered specular cube, a\npower of two 1..512 (default 128)")
      ->type_name("N")
      ->check(whole_number(1, 512))
      ->check(checked_by([](const std::string& text) {
        EnvironmentOptions options;
        options.specular_size = uint32_t(std::stoul(text));
        validate_environment_options(options);
      }));
  app.add_option("--env-samples", a.env_options.specular_samples,
                 "GGX samples per cube texel when prefiltering,\n1..65536 (default 128)")
      ->type_name("N")
      ->check(whole_number(1, 65536));
  app.add_option("--env-irradiance-size", a.env_options.irradiance_size,
                 "width of the map level the irradiance is\nprojected from, 1..16384 (default 64)")
      ->type_name("N")
      ->check(whole_number(1, 16384));
  app.add_option("--env-reference-samples", a.env_reference_samples,
                 "Monte Carlo directions per lobe and pixel\n"
                 "with --device reference, 1..1048576 (default\n"
                 "1024)")
      ->type_name("N")
      ->check(whole_number(1, 1u << 20));
  app.add_option("--anisotropy", a.frame.max_anisotropy,
                 "texture filtering: 1 trilinear (default),\n2..16 anisotropic")
      ->type_name("N")
      ->check(whole_number(1, 16));
  add_samples(app, a.frame.samples,
              "anti-aliasing: visibility samples per pixel,\n"
              "1 (default), 4, 8 or 16; each triangle in a\n"
              "pixel is shaded once, weighted by its samples");
  add_aa_coverage(app, a.frame.aa_coverage);
  add_aa_walk_steps(app, a.frame.silhouette_steps);
  add_lod_options(app, a.frame.lod, a.frame.lod_error_px);
  add_hdr_format(app, a.frame.hdr_format);
  add_tile_size(app, a.tile_size);
  add_depth_rejection(app, a.depth_rejection);
  add_shade_tiles(app, a.shade_tiles);
  add_raster_shade(app, a.raster_shade);
  add_tile_lists(app, a.tile_lists);
  add_quality(app, a.quality,
              "--brdf, --energy-compensation, --samples,\n"
              "--lod, --lod-error, --anisotropy, --env-size,\n"
              "--env-samples, --hdr-format, --tile-size");
  add_choice(app, "--view", a.frame.view,
             {{"shaded", View::shaded},
              {"normal", View::normal},
              {"uv", View::uv},
              {"triangle", View::triangle},
              {"object", View::object}},
             "shaded (default), or a debug view: normal,\n"
             "uv, triangle (a colour per triangle) or object\n"
             "(a colour per object)");
  app.add_option("--repeat", a.repeat,
                 "frames timed after the first, 1..1000\n"
                 "(default 3): their median, min and max GPU\n"
                 "times are reported; the first frame's apart,\n"
                 "as it includes pipeline compilation. With\n"
                 "--device reference: default 0 (the first\n"
                 "frame alone). A progress line every 2 s or\n"
                 "more when given")
      ->type_name("K")
      ->check(whole_number(1, 1000));
  app.add_flag("--validate", a.validate,
               "enable the Khronos validation layer\n"
               "(synchronization too); exit status 3 if it\n"
               "reports anything");
  app.add_flag("--quiet", a.quiet, "print nothing but errors");
  add_strict(app, a.strict);
  add_camera_option(app, a.camera);
}

void add_bench_options(CLI::App& app, BenchArgs& a) {
  app.add_option("--scene", a.scene,
                 "grid (default), scatter, huge or yardstick;\n"
                 "or a built-in scene of `tessera scenes` (one\n"
                 "point: its own object count); or a scene file\n"
                 "or .gltf/.glb/.obj model placed N times on the\n"
                 "grid")
      ->type_name("NAME")
      ->check(bench_scene());
  app.add_option(
         "--objects", a.objects,
         "object counts, e.g. 1,10,100,1000 (default\n1,10,100); with a scene file or model, how\n"
         "many times its content is placed (the table\ncounts objects: 19 parts placed 4 times\n"
         "are 76)")
      ->type_name("LIST")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(whole_number(1, 1u << 24));  // as many as a scene file may hold (SceneFileOptions)
  add_size(app, a.width, a.height,
           "image size, each side 1..16384 and the whole\n"
           "within the device's buffers (on lavapipe 16 M\n"
           "pixels at 1 sample); default 512x512");
  add_samples(app, a.samples,
              "anti-aliasing samples per pixel, 1 (default),\n"
              "4, 8 or 16; compute and reference backends\n"
              "only (the default backends are then compute)");
  add_aa_coverage(app, a.aa_coverage);
  add_aa_walk_steps(app, a.silhouette_steps);
  app.add_option("--segments", a.segments,
                 "sphere slices, 4..4096; S/2 stacks (default\n32: 960 triangles)")
      ->type_name("S")
      ->check(whole_number(4, 4096));
  app.add_option("--device", a.device,
                 "lavapipe, gpu or an index (default: a\ndiscrete GPU, else lavapipe)")
      ->type_name("D")
      ->check(
          device_choice(false, "the CPU reference is one of its backends (--backends reference)"));
  app.add_option("--backends", a.backends,
                 "compute, hardware, reference (default\ncompute,hardware)")
      ->type_name("LIST")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(one_of({"compute", "hardware", "reference"}));
  app.add_option("--repeat", a.repeat,
                 "timed frames per point, 1..1000 (default 10;\n"
                 "the reference backend: at most 3)")
      ->type_name("K")
      ->check(whole_number(1, 1000));
  app.add_option("--warmup", a.warmup, "untimed frames first, at least, 0..100\n(default 2)")
      ->type_name("K")
      ->check(whole_number(0, 100));
  app.add_option("--warmup-ms", a.warmup_ms,
                 "and for at least MS ms after the first, then\n"
                 "until the median of the last 5 frames is\n"
                 "within 2 % of the 5 before (at most 4 x MS),\n"
                 "0..600000 (default 500; 0: --warmup frames\n"
                 "only)")
      ->type_name("MS")
      ->check(whole_number(0, 600000));
  app.add_option("--runs", a.runs,
                 "repeat the whole sweep K times, 1..100\n"
                 "(default 1): figures are the medians of the\n"
                 "runs' medians, with their spread")
      ->type_name("K")
      ->check(whole_number(1, 100));
  app.add_option("--compare", a.compare,
                 "print each point's time against a saved\n"
                 "--json run (old, new, new / old), matched by\n"
                 "scene, objects, size and backend")
      ->type_name("BASE.json");
  app.add_option("--reference-max-triangles", a.reference_max_triangles,
                 "skip the reference above T triangles\n(default 2000000)")
      ->type_name("T")
      ->check(whole_number(1, 4'000'000'000u));
  app.add_option("--small-triangle-area", a.small_triangle_area,
                 "pixel-box area up to which a triangle is\n"
                 "rasterized by one thread; larger ones are\n"
                 "binned into tiles (default 128; 4096 on a CPU\n"
                 "device such as lavapipe)")
      ->type_name("A")
      ->check(whole_number(0, 1u << 24));
  add_lod_options(app, a.lod, a.lod_error_px);
  add_hdr_format(app, a.hdr_format);
  add_tile_size(app, a.tile_size);
  add_depth_rejection(app, a.depth_rejection);
  add_shade_tiles(app, a.shade_tiles);
  add_raster_shade(app, a.raster_shade);
  add_tile_lists(app, a.tile_lists);
  add_quality(app, a.quality,
              "--samples, --lod, --lod-error, --hdr-format,\n"
              "--small-triangle-area (GPUs only: a CPU\n"
              "device keeps its 4096), --tile-size");
  app.add_flag("--generic-shading", a.generic_shading,
               "shade with the generic pipeline instead of one\n"
               "specialized to the scene's light counts, to\n"
               "measure what specialization saves");
  app.add_option("--csv", a.csv,
                 "write every measurement as CSV, each row with\n"
                 "the settings it was measured with")
      ->type_name("FILE")
      ->check(writable_output());
  app.add_option("--json", a.json, "the same as JSON, with device, driver and\ncommand")
      ->type_name("FILE")
      ->check(writable_output());
  add_chart(app, a.chart,
            "time against objects (log-log, one line per\n"
            "backend) and the compute path's per-pass\n"
            "breakdown, as SVG or PNG");
  add_validate(app, a.validate);
  app.add_flag("--quiet", a.quiet,
               "no progress bar or results table (--compare's\ntable still prints)");
  add_strict(app, a.strict);
}

void add_view_options(CLI::App& app, ViewArgs& a) {
  app.add_option("--scene", a.scene,
                 "built-in scene (default spheres; see\n"
                 "`tessera scenes`) or a scene file; Ctrl+S\n"
                 "saves it; unsaved edits at exit go to\n"
                 "FILE.autosave.json beside it, or\n"
                 "NAME.builtin-autosave.json here; or a\n"
                 ".gltf/.glb/.obj model, framed and lit as by\n"
                 "render (Ctrl+S: FILE.json)")
      ->type_name("NAME|FILE")
      ->check(builtin_scene());
  app.add_option("--device", a.device,
                 "lavapipe, gpu or an index (default: a\ndiscrete GPU, else lavapipe)")
      ->type_name("D")
      ->check(
          device_choice(false,
                        "the viewer draws with Vulkan only (`tessera render --device reference` "
                        "renders an image with the CPU reference)"));
  add_size(app, a.frame.width, a.frame.height,
           "window size in pixels at the start (default:\nthe scene's, else 512x512)");
  add_choice(app, "--vsync", a.vsync, {{"on", true}, {"off", false}},
             "on (default): present at the display's rate;\n"
             "off: as fast as frames are rendered");
  app.add_option("--script", a.script,
                 "replay input events at frame numbers from\n"
                 "FILE (keys, drags, clicks, resizes,\n"
                 "screenshots, exit; see README)")
      ->type_name("FILE")
      // What is there but not a file (a FIFO, a folder) is refused here too, with the option's
      // name as every option error has it (stat only: opening a FIFO would block).
      ->check(checked_by([](const std::string& path) {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec)) throw Error("script file '" + path + "' not found");
        require_regular_file(path);
      }));
  add_choice(app, "--present", a.present,
             {{"auto", PresentPath::automatic},
              {"copy", PresentPath::copy},
              {"direct", PresentPath::direct}},
             "direct: the resolve pass writes the swapchain\n"
             "image; copy: it writes Tessera's image, which\n"
             "is copied; auto (default): direct where the\n"
             "surface allows storage use");
  add_choice(app, "--surface-format", a.surface_format,
             {{"auto", SurfaceFormat::automatic},
              {"unorm", SurfaceFormat::unorm},
              {"srgb", SurfaceFormat::srgb}},
             "the swapchain's 8-bit format: auto (default)\n"
             "takes UNORM where offered, else sRGB; the\n"
             "window shows the PNG's colours with either");
  add_choice(app, "--overlay", a.overlay, {{"on", true}, {"off", false}},
             "the Dear ImGui panel (default on; F1 toggles\nit)");
  add_validate(app, a.validate);
  add_strict(app, a.strict);
  add_camera_option(app, a.camera);
}

void add_tradeoff_options(CLI::App& app, TradeoffArgs& a) {
  app.add_option("--scene", a.scene,
                 "built-in scene (default spheres), scene file,\n"
                 ".gltf/.glb/.obj model (framed and lit as by\n"
                 "render), or a benchmark family: grid,\n"
                 "scatter, huge, yardstick")
      ->type_name("S")
      ->check(bench_scene());
  app.add_option("--objects", a.objects,
                 "objects of a benchmark family (grid, scatter,\nhuge, yardstick; default 100)")
      ->type_name("N")
      ->check(whole_number(1, 1u << 24));  // as bench's --objects
  app.add_option("--knob", a.knobs,
                 "the knobs to sweep, e.g. brdf,tessellation:\n"
                 "brdf, tessellation, lod, anisotropy, env-size,\n"
                 "env-samples, samples, aa-coverage,\n"
                 "aa-walk-steps, hdr, small-triangle, tile-size,\n"
                 "depth-rejection, shade-tiles, raster-shade\n"
                 "(docs/tradeoffs.md)")
      ->type_name("K[,K...]")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->required()
      ->check(checked_by([](const std::string& knob) { knob_settings(knob, {}, {}); }));
  app.add_option("--device", a.device,
                 "lavapipe, gpu or an index (default: a\ndiscrete GPU, else lavapipe)")
      ->type_name("D")
      ->check(
          device_choice(false,
                        "the CPU reference renders every knob's ground truth; --device picks the "
                        "Vulkan device timed"));
  add_size(app, a.frame.width, a.frame.height,
           "image size, each side 1..16384 and the whole\n"
           "within the device's buffers (on lavapipe 16 M\n"
           "pixels at 1 sample); default: the scene's,\n"
           "else 512x512");
  add_hdr_format(app, a.frame.hdr_format);
  add_tile_size(app, a.tile_size);
  add_quality(app, a.quality,
              "the base every knob's settings start from:\n"
              "BRDF and energy compensation, samples, level\n"
              "of detail and its error, anisotropy,\n"
              "environment size and samples, HDR format,\n"
              "small-triangle area (GPUs only: a CPU device\n"
              "keeps its 4096), tile size");
  app.add_option("--repeat", a.repeat, "timed frames per setting and round, 1..1000\n(default 10)")
      ->type_name("K")
      ->check(whole_number(1, 1000));
  app.add_option("--warmup", a.warmup,
                 "untimed frames per setting and round, at\nleast, 0..100 (default 2)")
      ->type_name("K")
      ->check(whole_number(0, 100));
  app.add_option("--warmup-ms", a.warmup_ms,
                 "and for at least MS ms after the first, then\n"
                 "until the frame time settles, as `tessera\n"
                 "bench`, 0..600000 (default 200; 0: --warmup\n"
                 "frames only)")
      ->type_name("MS")
      ->check(whole_number(0, 600000));
  app.add_option("--rounds", a.rounds,
                 "passes over all settings, interleaved so that\n"
                 "clock changes affect all alike, 1..100\n(default 3)")
      ->type_name("R")
      ->check(whole_number(1, 100));
  app.add_option("--truth-samples", a.truth_samples,
                 "N: N x N samples per pixel of the ground\ntruth, 1..32 (default 8)")
      ->type_name("N")
      ->check(whole_number(1, 32));
  app.add_option("--truth-env-samples", a.truth_env_samples,
                 "environment directions per lobe and pixel of\n"
                 "the ground truth, 1..1048576 (default 1024)")
      ->type_name("N")
      ->check(whole_number(1, 1u << 20));
  app.add_option("--json", a.json, "every point as JSON, with device and command")
      ->type_name("FILE")
      ->check(writable_output());
  add_chart(app, a.chart,
            "error against GPU time, a series per knob,\n"
            "each knob's Pareto front joined, SVG or PNG");
  add_validate(app, a.validate);
  app.add_flag("--quiet", a.quiet, "no progress or table");
  add_strict(app, a.strict);
}

// CLI11's message, reworded where it is unclear: a missing value, an option given twice.
std::string message_of(const CLI::ParseError& e) {
  const std::string what = e.what();
  const size_t colon = what.find(':');
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) && colon != std::string::npos) {
    if (what.ends_with(" missing")) return what.substr(0, colon) + " needs a value";
    const std::string twice = ": At Most 1 required but received ";
    if (what.find(twice) == colon) {
      return what.substr(0, colon) + ": given " + what.substr(colon + twice.size()) +
             " times; give it once";
    }
  }
  return what;
}

// An argument that no option took: an unknown option, or a value where none belongs.
void reject_extras(const CLI::App& command, const std::string& help_command) {
  const std::vector<std::string> extras = command.remaining();
  if (extras.empty()) return;
  const std::string& first = extras.front();
  if (!first.starts_with("-"))
    throw UsageError("unexpected argument '" + first + "'", help_command);
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  }
  const std::string given = first.substr(0, first.find('='));  // --name=value
  const std::string near = closest_name(given, names);
  throw UsageError(
      "unknown option '" + first + "'" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
      help_command);
}

// CLI11 drops the empty entries of a comma-separated list ("1,,2" reads as 1 and 2): a slip in
// a list is a bad command line rather than a silently shorter list.
void reject_empty_list_entries(const std::vector<std::string>& args,
                               const std::string& help_command) {
  for (size_t i = 0; i < args.size(); ++i) {
    for (const char* name : {"--objects", "--backends", "--knob"}) {
      const std::string prefix = std::string(name) + "=";
      std::string value;
      if (args[i] == name && i + 1 < args.size()) {
        value = args[i + 1];
      } else if (args[i].starts_with(prefix)) {
        value = args[i].substr(prefix.size());
      } else {
        continue;
      }
      if (value.empty() || value.front() == ',' || value.back() == ',' ||
          value.find(",,") != std::string::npos)
        throw UsageError(std::string(name) + ": an empty entry in '" + value + "'", help_command);
    }
  }
}

// The first entry of `list` that an earlier one equals, or null.
template <typename T>
const T* first_repeated(const std::vector<T>& list) {
  for (size_t i = 0; i < list.size(); ++i) {
    if (std::find(list.begin(), list.begin() + i, list[i]) != list.begin() + i) return &list[i];
  }
  return nullptr;
}

}  // namespace

std::string version_text() {
  return "tessera " TESSERA_VERSION;
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
  if (args.empty()) {
    throw UsageError("a command is required: " + list_of_choices(kCommands), "tessera --help");
  }
  const std::string& command = args.front();
  if (command == "--version") {
    if (args.size() > 1) throw UsageError("--version takes nothing after it", "tessera --help");
    CommandLine line;
    line.command = Command::help;  // a text to print, and success
    line.help = version_text() + "\n";
    return line;
  }
  const bool asks_help = command == "--help" || command == "-h" || command == "help";
  if (!asks_help && std::find(kCommands.begin(), kCommands.end(), command) == kCommands.end()) {
    const std::string near = command.starts_with("-") ? "" : closest_name(command, kCommands);
    throw UsageError((command.starts_with("-") ? "unknown option '" : "unknown command '") +
                         command + "'" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                     "tessera --help");
  }

  CommandLine line;
  CLI::App app("a triangle rasterizer and PBR shader written entirely in Vulkan compute",
               "tessera");
  // Names of up to 28 characters, descriptions of up to 49: 80 columns.
  app.get_formatter()->column_width(31);
  app.require_subcommand(1);
  // Answered above; declared for the help text.
  app.set_version_flag("--version", version_text(), "print the version and exit");
  CLI::App* render = app.add_subcommand("render", "render a scene to a PNG");
  add_render_options(*render, line.render);
  CLI::App* bench =
      app.add_subcommand("bench", "sweep a benchmark scene over object counts and backends");
  add_bench_options(*bench, line.bench);
  CLI::App* view =
      app.add_subcommand("view", "show a scene in a window: camera, picking, live edits");
  add_view_options(*view, line.view);
  CLI::App* tradeoff =
      app.add_subcommand("tradeoff", "chart GPU time against error from the truth, knob by knob");
  add_tradeoff_options(*tradeoff, line.tradeoff);
  CLI::App* devices =
      app.add_subcommand("devices", "list the Vulkan devices and whether Tessera can use them");
  CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes");
  const std::string exit_statuses =
      "Exit status: 0 success, 1 a failure while running, 2 a bad command line,\n"
      "3 reports of the validation layer (--validate).";
  app.footer("Run `tessera COMMAND --help` for a command's options.\n" + exit_statuses);
  // A sweep stopped by a signal keeps what it measured (host/stop_signal.h).
  const std::string stopped_status =
      "\n130 (SIGINT, Ctrl+C) or 143 (SIGTERM): stopped early; what was measured\n"
      "is printed and written, marked as interrupted (a second signal ends at once).";
  for (CLI::App* sub : {render, bench, view, tradeoff, devices, scenes}) {
    sub->allow_extras();
    sub->footer(exit_statuses);
  }
  render->footer(exit_statuses +
                 "\n130 (SIGINT, Ctrl+C) or 143 (SIGTERM): --repeat stopped between frames;\n"
                 "the image and the times of the frames rendered are written and printed\n"
                 "(a second signal ends at once).");
  bench->footer(
      "Figures are medians of GPU timestamps over --repeat frames after the\n"
      "warm-up (--warmup, --warmup-ms; its frames and time are reported), with\n"
      "the fastest and slowest frame: around the frame for the compute path,\n"
      "and per pass in as many frames more (timestamps between the passes add\n"
      "to a frame: their frames' total is per_pass_total_ms in CSV and JSON);\n"
      "around the render pass for the hardware baseline; wall time for the CPU\n"
      "reference.\n"
      "With --runs K, the median of the K runs' medians and their spread,\n"
      "(max - min) / median.\n" +
      exit_statuses + stopped_status);
  // What the charts' errors are against (truth_shading): a reader would take one truth for all.
  tradeoff->footer(
      "The ground truth is the CPU reference (exact spheres, --truth-samples).\n"
      "The brdf knob is measured against the filament BRDF with energy\n"
      "compensation, every other knob against the settings' BRDF (--quality's,\n"
      "else the scene file's, else classic), so that its error is its own and\n"
      "not the BRDF's: the knobs are not measured against one truth, and their\n"
      "errors do not add up (docs/tradeoffs.md, \"The ground truth\").\n\n" +
      exit_statuses + stopped_status);

  // CLI11 takes the arguments last first.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  if (command == "help") reversed.back() = "--help";
  const std::string help_command = asks_help ? "tessera --help" : "tessera " + command + " --help";
  reject_empty_list_entries(args, help_command);
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    line.command = Command::help;
    line.help = app.help();
    return line;
  } catch (const CLI::CallForVersion&) {
    // `tessera --help --version`: the version, as `tessera --version` prints it.
    line.command = Command::help;
    line.help = version_text() + "\n";
    return line;
  } catch (const CLI::ParseError& e) {
    throw UsageError(message_of(e), help_command);
  }
  for (CLI::App* sub : {render, bench, view, tradeoff, devices, scenes})
    reject_extras(*sub, help_command);
  RenderArgs& r = line.render;
  r.size_given = render->count("--size") > 0;
  r.camera_given = render->count("--camera") > 0;
  r.repeat_given = render->count("--repeat") > 0;
  r.exposure_given = render->count("--exposure") > 0;
  r.samples_given = render->count("--samples") > 0;
  r.tonemap_given = render->count("--tonemap") > 0;
  apply_quality(r.quality, given_in(*render), &r.frame, &r.env_options, &r.tile_size, nullptr);
  r.brdf_given = render->count("--brdf") > 0 || r.quality != Quality::none;
  r.view_given = render->count("--view") > 0;
  r.depth_rejection_given = render->count("--depth-rejection") > 0;
  r.shade_tiles_given = render->count("--shade-tiles") > 0;
  r.raster_shade_given = render->count("--raster-shade") > 0;
  r.lod_error_given = render->count("--lod-error") > 0;
  r.anisotropy_given = render->count("--anisotropy") > 0;
  r.env_size_given = render->count("--env-size") > 0;
  r.env_samples_given = render->count("--env-samples") > 0;
  r.env_reference_samples_given = render->count("--env-reference-samples") > 0;
  r.tile_lists_given = render->count("--tile-lists") > 0;
  check_aa_coverage(*render, r.frame.samples, r.quality, help_command);
  check_aa_walk_steps(r.frame.aa_coverage, r.frame.silhouette_steps, help_command);
  line.view.size_given = view->count("--size") > 0;
  line.view.camera_given = view->count("--camera") > 0;
  BenchArgs& b = line.bench;
  {
    FrameSettings preset;
    preset.samples = b.samples;
    preset.lod = b.lod;
    preset.lod_error_px = b.lod_error_px;
    preset.hdr_format = b.hdr_format;
    apply_quality(b.quality, given_in(*bench), &preset, nullptr, &b.tile_size,
                  &b.small_triangle_area);
    b.samples = preset.samples;
    b.lod = preset.lod;
    b.lod_error_px = preset.lod_error_px;
    b.hdr_format = preset.hdr_format;
  }
  b.size_given = bench->count("--size") > 0;
  b.samples_given = bench->count("--samples") > 0;
  b.small_triangle_area_given = bench->count("--small-triangle-area") > 0;
  b.depth_rejection_given = bench->count("--depth-rejection") > 0;
  b.shade_tiles_given = bench->count("--shade-tiles") > 0;
  b.raster_shade_given = bench->count("--raster-shade") > 0;
  b.tile_lists_given = bench->count("--tile-lists") > 0;
  // A built-in scene, or a scene by name, is one point of its own objects: a count given for it
  // would be measured as something else without a word.
  if (bench->count("--objects") > 0 && !is_scene_path(b.scene) && !is_model_path(b.scene) &&
      !is_bench_family(b.scene))
    throw UsageError("--objects: '" + b.scene +
                         "' is a scene with objects of its own, measured as one point; "
                         "--objects applies to the benchmark families (" +
                         bench_family_names() + ") and to scene or model files",
                     help_command);
  // A count twice would be two points of one name: --compare matches points by count.
  if (const uint32_t* n = first_repeated(b.objects))
    throw UsageError("--objects: " + std::to_string(*n) + " is given twice", help_command);
  if (!b.compare.empty()) {
    std::error_code ec;
    if (!std::filesystem::exists(b.compare, ec))
      throw UsageError("--compare: no file '" + b.compare + "'", help_command);
    if (std::filesystem::is_directory(b.compare, ec))
      throw UsageError("--compare: '" + b.compare + "' is a folder, not a --json file",
                       help_command);
  }
  check_aa_coverage(*bench, b.samples, b.quality, help_command);
  check_aa_walk_steps(b.aa_coverage, b.silhouette_steps, help_command);
  const bool hardware =
      std::find(b.backends.begin(), b.backends.end(), "hardware") != b.backends.end();
  // What the hardware baseline cannot render leaves it out of the default backends. A preset's
  // value is named as the preset's, with the option that overrides it.
  const bool samples_given = b.samples_given;
  const bool hdr_given = bench->count("--hdr-format") > 0;
  const std::string compute_only =
      b.samples > 1
          ? option_source(b.quality, samples_given, "--samples", std::to_string(b.samples)) +
                ": the hardware backend renders 1 sample per pixel"
      : b.hdr_format != HdrFormat::fp16
          ? option_source(b.quality, hdr_given, "--hdr-format", "fp32") +
                ": the hardware backend renders into an fp16 image"
          : std::string();
  const std::string override_preset = b.samples > 1
                                          ? (samples_given ? "" : ", or add --samples 1")
                                          : (hdr_given ? "" : ", or add --hdr-format fp16");
  if (!compute_only.empty() && hardware) {
    if (bench->count("--backends") > 0)
      throw UsageError(compute_only + "; leave it out of --backends" + override_preset,
                       help_command);
    b.backends = {"compute"};
  }
  TradeoffArgs& t = line.tradeoff;
  if (tradeoff->count("--objects") > 0 && !is_bench_family(t.scene))
    throw UsageError("--objects applies to the benchmark families (" + bench_family_names() +
                         "), not to '" + t.scene + "'",
                     help_command);
  // A knob twice would be measured twice, its settings' points and Pareto front doubled.
  if (const std::string* knob = first_repeated(t.knobs))
    throw UsageError("--knob: '" + *knob + "' is given twice", help_command);
  apply_quality(t.quality, given_in(*tradeoff), &t.frame, &t.env_options, &t.tile_size,
                &t.small_triangle_area);
  t.size_given = tradeoff->count("--size") > 0;
  t.brdf_given = t.quality != Quality::none;
  reject_extras(app, help_command);
  line.command = render->parsed()     ? Command::render
                 : bench->parsed()    ? Command::bench
                 : view->parsed()     ? Command::view
                 : tradeoff->parsed() ? Command::tradeoff
                 : devices->parsed()  ? Command::devices
                                      : Command::scenes;
  return line;
}

}  // namespace tessera
