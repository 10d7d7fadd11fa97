#pragma once
// The drawing surfaces of host/chart.h's charts: SVG and PNG, and what both kinds of chart
// draw on them (log-log axes, numbers).

#include <cstdint>
#include <functional>
#include <string>

namespace tessera {

struct Colour {
  uint8_t r, g, b;
};

// The first ten are the common "category10" colours; the next ten are hues and shades apart
// from them, for charts with more series (`tradeoff --knob` takes fifteen knobs).
inline constexpr Colour kPalette[] = {
    {31, 119, 180},  {255, 127, 14},  {44, 160, 44},   {214, 39, 40},   {148, 103, 189},
    {140, 86, 75},   {227, 119, 194}, {127, 127, 127}, {188, 189, 34},  {23, 190, 207},
    {0, 0, 128},     {128, 0, 0},     {0, 128, 128},   {255, 200, 0},   {200, 0, 200},
    {150, 190, 240}, {250, 160, 120}, {0, 90, 40},     {210, 180, 140}, {90, 90, 150}};
inline constexpr Colour kInk{40, 40, 40};
inline constexpr Colour kGrid{220, 220, 220};

/// The colour of series `k`: distinct for the first 20 series, then repeating (a chart with more
/// also tells series apart by shape: series_hollow).
Colour palette(size_t k);

/// Whether series `k`'s marks are drawn as outlines rather than filled: every other run of ten,
/// so that series whose colours look alike (or, past 20, repeat) differ in shape too.
bool series_hollow(size_t k);

/// A drawing surface with the few primitives the charts need, in pixels (y down).
struct Canvas {
  virtual ~Canvas() = default;
  virtual void line(double x0, double y0, double x1, double y1, Colour c, double width) = 0;
  virtual void rect(double x, double y, double w, double h, Colour c) = 0;
  // anchor: 0 left, 1 centre, 2 right; `size` is the text height in pixels.
  virtual void text(double x, double y, const std::string& s, double size, Colour c, int anchor,
                    bool vertical = false) = 0;
  // The width `text` gives `s`, in pixels (an estimate where the viewer picks the font).
  virtual double text_width(const std::string& s, double size) const = 0;
};

/// The width Canvas::text_width gives `s` on the canvas a file `path` is written with
/// (write_canvas): for laying a chart out before its canvas exists.
using TextWidth = double (*)(const std::string& s, double size);
TextWidth text_width_for(const std::string& path);

/// Draws with `paint` onto an SVG or PNG canvas of width x height, chosen by `path`'s suffix,
/// and writes it. Throws Error for another suffix or a file that cannot be written.
void write_canvas(const std::string& path, double width, double height,
                  const std::function<void(Canvas&)>& paint);

/// `v` as an axis labels it: 1e+06, 200, 0.05, 1e-04.
std::string format_number(double v);

struct Box {
  double x, y, w, h;
};

/// Log-log axes over [xmin, xmax] x [ymin, ymax] (all > 0), rounded out to powers of ten.
struct LogAxes {
  Box b;
  double lx0, lx1, ly0, ly1;
  double px(double x) const;
  double py(double y) const;
};
LogAxes log_axes(Box b, double xmin, double xmax, double ymin, double ymax);

/// A chart's title centred across `width` above plots that start 60 px down: one line of 16 px
/// text where it fits in width - 20 px, else two, broken at the ", " nearest the middle (a
/// long title drawn on one line was shrunk to a quarter of its size to fit).
void draw_title(Canvas& c, double width, const std::string& title);

/// Grid lines, ticks, axis lines and the axes' titles.
void draw_log_axes(Canvas& c, const LogAxes& a, const std::string& x_label,
                   const std::string& y_label);

}  // namespace tessera
