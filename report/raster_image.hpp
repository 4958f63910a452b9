// Small drawing helpers shared by the picture writers (workspace slices, Pareto plots):
// 8-bit RGB colours, the viridis colour map, "nice" axis ticks, the axes of a scatter plot (SVG
// or raster), and an RGB raster with a 5x7 bitmap font that encodes itself as PNG (libpng).
//
//   viridis(t)            matplotlib's viridis at t in [0, 1] (9 table points, linear in between)
//   nice_ticks(lo, hi, n) about n ticks at a step of 1, 2 or 5 times a power of ten in [lo, hi]
//   padded_range(lo, hi)  a plot range 5 % wider than the data
//   PlotAxes              a plot frame in pixels and the value ranges it maps; svg_axes and
//                         draw_axes draw its grid, ticks, tick labels and frame
//
//   pkmopt::raster::RgbImage image(320, 200, pkmopt::raster::kWhite);
//   image.disc(50, 50, 4, pkmopt::raster::viridis(0.3));
//   image.text(10, 10, "x [mm]", pkmopt::raster::kInk);
//   const std::string png = image.encode_png();
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pkmopt::raster {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

inline constexpr Rgb kWhite{255, 255, 255};
inline constexpr Rgb kInk{20, 20, 20};

/// Viridis (matplotlib's table at 9 evenly spaced points, interpolated linearly); t clamped.
Rgb viridis(double t);
/// "#rrggbb".
std::string hex(Rgb c);
/// Ticks at a "nice" step (1, 2 or 5 times a power of ten) covering [low, high], about `target`
/// of them; {low} when high <= low.
std::vector<double> nice_ticks(double low, double high, int target);

/// A plot range from the data range: 5 % wider on each side; an empty range widened by 5 % of
/// its value (1 about 0); an inverted or non-finite one becomes [0, 1].
void padded_range(double& low, double& high);

inline constexpr Rgb kGridColour{230, 230, 230};

/// A scatter plot's frame (pixels; screen y grows downwards) and the value ranges it maps.
struct PlotAxes {
  int left = 0, top = 0, plot_width = 0, plot_height = 0;
  double x_low = 0, x_high = 1, y_low = 0, y_high = 1;
  std::vector<double> x_ticks, y_ticks;  ///< values

  double screen_x(double v) const { return left + plot_width * (v - x_low) / (x_high - x_low); }
  double screen_y(double v) const {
    return top + plot_height * (1.0 - (v - y_low) / (y_high - y_low));
  }
  int frame_right() const { return left + plot_width; }
  int frame_bottom() const { return top + plot_height; }
};

/// Grid lines (kGridColour), tick marks and tick labels ({:.4g}) below and left of the frame,
/// and the frame, as SVG elements (13 px labels).
std::string svg_axes(const PlotAxes& axes);

inline constexpr int kGlyphScale = 2;
inline constexpr int kGlyphAdvance = 6 * kGlyphScale;  ///< pixels per character
inline constexpr int kGlyphHeight = 7 * kGlyphScale;   ///< pixels

/// An RGB picture; (0, 0) is the top-left pixel. Drawing outside the picture is clipped.
class RgbImage {
 public:
  RgbImage(int width, int height, Rgb fill);

  void set(int x, int y, Rgb c);
  /// Fills [x0, x1) x [y0, y1).
  void fill(int x0, int y0, int x1, int y1, Rgb c);
  /// A one-pixel rectangle outline of [x0, x1) x [y0, y1).
  void frame(int x0, int y0, int x1, int y1, Rgb c);
  /// A filled disc of radius r (pixels) about (cx, cy).
  void disc(double cx, double cy, double r, Rgb c);
  /// A ring between radii r - width and r about (cx, cy).
  void ring(double cx, double cy, double r, double width, Rgb c);
  int text_width(std::string_view text) const;
  /// Text with its top-left corner at (x, y); characters without a glyph are left blank
  /// (digits, lower-case letters, N and + - . , = / _ [ ] * ^ ( ) : have one).
  void text(int x, int y, std::string_view text, Rgb c);

  /// The picture as an 8-bit RGB PNG file. Throws std::runtime_error if libpng fails.
  std::string encode_png() const;

 private:
  int width_, height_;
  std::vector<Rgb> pixels_;
};

/// svg_axes drawn into a picture (tick positions rounded to pixels, the bitmap font).
void draw_axes(RgbImage& image, const PlotAxes& axes);

}  // namespace pkmopt::raster
