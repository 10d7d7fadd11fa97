#include "host/cli.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>

#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

uint32_t parse_uint(const std::string& option, const std::string& text, uint32_t min,
                    uint32_t max) {
  uint64_t value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < min || value > max) {
    throw Error(option + " expects a whole number from " + std::to_string(min) + " to " +
                std::to_string(max) + ", got '" + text + "'");
  }
  return uint32_t(value);
}

namespace {

float parse_float(const std::string& option, const std::string& text) {
  float value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw Error(option + " expects a number, got '" + text + "'");
  }
  return value;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool parse_options(const std::vector<std::string>& args,
                   const std::map<std::string, ValueHandler>& with_value,
                   const std::map<std::string, std::function<void()>>& flags,
                   const std::string& command) {
  for (size_t i = 0; i < args.size(); ++i) {
    std::string name = args[i];
    std::string value;
    bool has_inline_value = false;
    if (size_t eq = name.find('='); name.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_inline_value = true;
    }
    if (name == "--help" || name == "-h") return false;
    if (auto f = flags.find(name); f != flags.end() && !has_inline_value) {
      f->second();
      continue;
    }
    auto h = with_value.find(name);
    if (h == with_value.end())
      throw Error("unknown option '" + args[i] + "' (see " + command + " --help)");
    if (!has_inline_value) {
      if (i + 1 >= args.size()) throw Error(name + " needs a value");
      value = args[++i];
    }
    h->second(value);
  }
  return true;
}

void parse_size(const std::string& text, uint32_t& width, uint32_t& height) {
  const size_t x = text.find('x');
  if (x == std::string::npos) throw Error("--size expects WxH (e.g. 512x512), got '" + text + "'");
  width = parse_uint("--size width", text.substr(0, x), 1, TS_MAX_IMAGE_SIDE);
  height = parse_uint("--size height", text.substr(x + 1), 1, TS_MAX_IMAGE_SIDE);
}

std::string main_help() {
  return "tessera: a triangle rasterizer and PBR shader written entirely in Vulkan compute\n"
         "\n"
         "usage: tessera <command> [options]\n"
         "\n"
         "commands:\n"
         "  render     render a scene to a PNG (tessera render --help)\n"
         "  bench      sweep a benchmark scene over object counts and backends (tessera bench "
         "--help)\n"
         "  devices    list the Vulkan devices and whether Tessera can use them\n"
         "  scenes     list the built-in scenes\n";
}

std::string render_help() {
  return "usage: tessera render [options]\n"
         "\n"
         "  --scene NAME|FILE   built-in scene (default spheres; see `tessera scenes`) or a\n"
         "                      scene file (docs/scene-format.md); its \"render\" block sets\n"
         "                      size, exposure, tone map and BRDF unless given here\n"
         "  --strict            unknown keys in a scene file are errors, not warnings\n"
         "  --size WxH          image size in pixels, each side 1..16384 (default 512x512)\n"
         "  --out FILE.png      display image, sRGB (default tessera.png)\n"
         "  --hdr-out FILE      linear HDR image too, .pfm (exact floats) or .hdr (RGBE)\n"
         "  --device D          lavapipe, gpu, a device index (default: a discrete GPU if\n"
         "                      there is one, else lavapipe), or reference: the CPU\n"
         "                      reference renderer in double precision\n"
         "  --exposure EV       exposure in stops, applied before tone mapping (default 0)\n"
         "  --tonemap OP        aces (default), reinhard or clamp\n"
         "  --brdf B            classic (default: GGX, Schlick-GGX Smith, Schlick Fresnel),\n"
         "                      filament (height-correlated Smith) or blinn-phong\n"
         "  --energy-compensation  multiple-scattering energy compensation of the specular\n"
         "                      lobe (classic and filament), from a DFG table\n"
         "  --env E             light the scene with an environment, also drawn behind it:\n"
         "                      FILE.hdr (Radiance) or FILE.pfm, equirectangular; sky (a\n"
         "                      procedural sky); none (the scene's lights only). Default:\n"
         "                      the scene's own (only `environment` has one)\n"
         "  --env-size N        side of the prefiltered specular cube, a power of two\n"
         "                      1..512 (default 128)\n"
         "  --env-samples N     GGX samples per cube texel when prefiltering (default 128)\n"
         "  --env-irradiance-size N  width of the map level the irradiance is projected\n"
         "                      from (default 64)\n"
         "  --env-reference-samples N  Monte Carlo directions per lobe and pixel with\n"
         "                      --device reference (default 1024)\n"
         "  --anisotropy N      texture filtering: 1 trilinear (default), 2..16 anisotropic\n"
         "  --view V            shaded (default), or a debug view: normal, uv, triangle\n"
         "                      (a colour per triangle) or object (a colour per object)\n"
         "  --repeat K          render K frames (1..1000) and report median GPU timings\n"
         "  --validate          enable the Khronos validation layer (synchronization too)\n"
         "  --quiet             print nothing but errors\n"
         "  --help              this text\n";
}

bool parse_render_args(const std::vector<std::string>& args, RenderArgs& out) {
  const std::map<std::string, ValueHandler> with_value = {
      {"--scene", [&](const std::string& v) { out.scene = v; }},
      {"--size",
       [&](const std::string& v) {
         parse_size(v, out.width, out.height);
         out.size_given = true;
       }},
      {"--out",
       [&](const std::string& v) {
         if (!ends_with(v, ".png")) throw Error("--out must name a .png file, got '" + v + "'");
         out.out = v;
       }},
      {"--hdr-out",
       [&](const std::string& v) {
         if (!ends_with(v, ".pfm") && !ends_with(v, ".hdr")) {
           throw Error("--hdr-out must name a .pfm or .hdr file, got '" + v + "'");
         }
         out.hdr_out = v;
       }},
      {"--device", [&](const std::string& v) { out.device = v; }},
      {"--exposure",
       [&](const std::string& v) {
         out.exposure_ev = parse_float("--exposure", v);
         out.exposure_given = true;
         if (std::abs(out.exposure_ev) > 64.0f)
           throw Error("--exposure must be within [-64, 64] EV");
       }},
      {"--tonemap",
       [&](const std::string& v) {
         out.tonemap_given = true;
         if (v == "aces")
           out.tonemap = ToneMap::aces;
         else if (v == "reinhard")
           out.tonemap = ToneMap::reinhard;
         else if (v == "clamp")
           out.tonemap = ToneMap::clamp;
         else
           throw Error("--tonemap expects aces, reinhard or clamp, got '" + v + "'");
       }},
      {"--view",
       [&](const std::string& v) {
         const std::map<std::string, View> views = {{"shaded", View::shaded},
                                                    {"normal", View::normal},
                                                    {"uv", View::uv},
                                                    {"triangle", View::triangle},
                                                    {"object", View::object}};
         auto it = views.find(v);
         if (it == views.end()) {
           throw Error("--view expects shaded, normal, uv, triangle or object, got '" + v + "'");
         }
         out.view = it->second;
       }},
      {"--brdf",
       [&](const std::string& v) {
         out.brdf_given = true;
         if (v == "classic")
           out.brdf = Brdf::classic;
         else if (v == "filament")
           out.brdf = Brdf::filament;
         else if (v == "blinn-phong")
           out.brdf = Brdf::blinn_phong;
         else
           throw Error("--brdf expects classic, filament or blinn-phong, got '" + v + "'");
       }},
      {"--repeat", [&](const std::string& v) { out.repeat = parse_uint("--repeat", v, 1, 1000); }},
      {"--env",
       [&](const std::string& v) {
         if (v != "sky" && v != "none" && !ends_with(v, ".hdr") && !ends_with(v, ".pfm")) {
           throw Error("--env expects a .hdr or .pfm file, sky or none, got '" + v + "'");
         }
         out.env = v;
       }},
      {"--env-size",
       [&](const std::string& v) {
         out.env_options.specular_size = parse_uint("--env-size", v, 1, 512);
         validate_environment_options(out.env_options);
       }},
      {"--env-samples",
       [&](const std::string& v) {
         out.env_options.specular_samples = parse_uint("--env-samples", v, 1, 65536);
       }},
      {"--env-irradiance-size",
       [&](const std::string& v) {
         out.env_options.irradiance_size = parse_uint("--env-irradiance-size", v, 1, 16384);
       }},
      {"--env-reference-samples",
       [&](const std::string& v) {
         out.env_reference_samples = parse_uint("--env-reference-samples", v, 1, 1u << 20);
       }},
      {"--anisotropy",
       [&](const std::string& v) { out.anisotropy = parse_uint("--anisotropy", v, 1, 16); }},
  };
  const std::map<std::string, std::function<void()>> flags = {
      {"--validate", [&] { out.validate = true; }},
      {"--quiet", [&] { out.quiet = true; }},
      {"--strict", [&] { out.strict = true; }},
      {"--energy-compensation", [&] { out.energy_compensation = true; }},
  };
  return parse_options(args, with_value, flags, "tessera render");
}

}  // namespace tessera
