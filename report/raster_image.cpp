#include "report/raster_image.hpp"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

namespace pkmopt::raster {
namespace {

// ---- A 5x7 bitmap font for the PNG labels (rows top to bottom, bit 4 = leftmost column). ----
const std::map<char, std::array<std::uint8_t, 7>>& font() {
  static const std::map<char, std::array<std::uint8_t, 7>> glyphs = {
      {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
      {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
      {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
      {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
      {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
      {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
      {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
      {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
      {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
      {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
      {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
      {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
      {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
      {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
      {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
      {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
      {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
      {'[', {0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E}},
      {']', {0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E}},
      {'*', {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00}},
      {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}},
      {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}},
      {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
      {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
      {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
      {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}},
      {'g', {0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
      {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
      {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}},
      {'j', {0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0C}},
      {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}},
      {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
      {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
      {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
      {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}},
      {'p', {0x00, 0x00, 0x1E, 0x11, 0x1E, 0x10, 0x10}},
      {'q', {0x00, 0x00, 0x0D, 0x13, 0x0F, 0x01, 0x01}},
      {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}},
      {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
      {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
      {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}},
      {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
      {'w', {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}},
      {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}},
      {'y', {0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
      {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
      {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
      {'^', {0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00}},
      {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
      {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
      {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
      {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
      {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},
  };
  return glyphs;
}

}  // namespace

// Viridis at 9 evenly spaced points (matplotlib's table), interpolated linearly.
Rgb viridis(double t) {
  static constexpr std::array<std::array<double, 3>, 9> kTable = {{{0.267, 0.005, 0.329},
                                                                   {0.279, 0.175, 0.483},
                                                                   {0.230, 0.322, 0.546},
                                                                   {0.173, 0.449, 0.558},
                                                                   {0.128, 0.567, 0.551},
                                                                   {0.158, 0.684, 0.502},
                                                                   {0.369, 0.789, 0.383},
                                                                   {0.678, 0.864, 0.190},
                                                                   {0.993, 0.906, 0.144}}};
  t = std::clamp(t, 0.0, 1.0) * 8.0;
  const int i = std::min(7, static_cast<int>(t));
  const double f = t - i;
  Rgb c;
  auto mix = [&](int k) {
    const double v = (1 - f) * kTable[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] +
                     f * kTable[static_cast<std::size_t>(i + 1)][static_cast<std::size_t>(k)];
    return static_cast<std::uint8_t>(std::lround(255.0 * v));
  };
  c.r = mix(0);
  c.g = mix(1);
  c.b = mix(2);
  return c;
}

std::string hex(Rgb c) { return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b); }

// Ticks at a "nice" step (1, 2 or 5 times a power of ten) covering [low, high].
std::vector<double> nice_ticks(double low, double high, int target) {
  std::vector<double> ticks;
  const double range = high - low;
  if (!(range > 0.0)) return {low};
  const double raw = range / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  for (double t = std::ceil(low / step) * step; t <= high + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-9 * step ? 0.0 : t);
  }
  return ticks;
}

RgbImage::RgbImage(int width, int height, Rgb fill)
    : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, fill) {}

void RgbImage::set(int x, int y, Rgb c) {
  if (x >= 0 && y >= 0 && x < width_ && y < height_) {
    pixels_[static_cast<std::size_t>(y) * width_ + x] = c;
  }
}

void RgbImage::fill(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) set(x, y, c);
  }
}

void RgbImage::frame(int x0, int y0, int x1, int y1, Rgb c) {
  fill(x0, y0, x1, y0 + 1, c);
  fill(x0, y1 - 1, x1, y1, c);
  fill(x0, y0, x0 + 1, y1, c);
  fill(x1 - 1, y0, x1, y1, c);
}

void RgbImage::disc(double cx, double cy, double r, Rgb c) { ring(cx, cy, r, r, c); }

void RgbImage::ring(double cx, double cy, double r, double width, Rgb c) {
  const double inner = std::max(0.0, r - width);
  for (int y = static_cast<int>(std::floor(cy - r)); y <= static_cast<int>(std::ceil(cy + r));
       ++y) {
    for (int x = static_cast<int>(std::floor(cx - r)); x <= static_cast<int>(std::ceil(cx + r));
         ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      if (d <= r && (inner == 0.0 || d >= inner)) set(x, y, c);
    }
  }
}

int RgbImage::text_width(std::string_view text) const {
  return static_cast<int>(text.size()) * kGlyphAdvance - kGlyphScale;
}

void RgbImage::text(int x, int y, std::string_view text, Rgb c) {
  for (char ch : text) {
    auto it = font().find(ch);
    // Capitals without a glyph of their own are drawn as small letters (labels stay legible).
    if (it == font().end() && ch >= 'A' && ch <= 'Z')
      it = font().find(static_cast<char>(ch - 'A' + 'a'));
    if (it != font().end()) {
      for (int row = 0; row < 7; ++row) {
        for (int col = 0; col < 5; ++col) {
          if (it->second[static_cast<std::size_t>(row)] & (0x10 >> col)) {
            fill(x + col * kGlyphScale, y + row * kGlyphScale, x + (col + 1) * kGlyphScale,
                 y + (row + 1) * kGlyphScale, c);
          }
        }
      }
    }
    x += kGlyphAdvance;
  }
}

std::string RgbImage::encode_png() const {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) throw std::runtime_error("libpng: cannot create a write struct");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("libpng: cannot create an info struct");
  }
  std::string bytes;
  std::vector<png_bytep> rows(static_cast<std::size_t>(height_));
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(width_) * height_ * 3);
  for (std::size_t p = 0; p < pixels_.size(); ++p) {
    raw[3 * p] = pixels_[p].r;
    raw[3 * p + 1] = pixels_[p].g;
    raw[3 * p + 2] = pixels_[p].b;
  }
  for (int y = 0; y < height_; ++y) {
    rows[static_cast<std::size_t>(y)] = raw.data() + static_cast<std::size_t>(y) * width_ * 3;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: encoding the picture failed");
  }
  png_set_write_fn(
      png, &bytes,
      [](png_structp p, png_bytep data, png_size_t length) {
        static_cast<std::string*>(png_get_io_ptr(p))
            ->append(reinterpret_cast<const char*>(data), length);
      },
      nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width_), static_cast<png_uint_32>(height_), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, rows.data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

void padded_range(double& low, double& high) {
  if (!(low <= high)) {
    low = 0.0;
    high = 1.0;
    return;
  }
  const double pad = high > low ? 0.05 * (high - low) : (low != 0.0 ? 0.05 * std::abs(low) : 1.0);
  low -= pad;
  high += pad;
}

std::string svg_axes(const PlotAxes& a) {
  const int bottom = a.frame_bottom(), right = a.frame_right();
  std::string out;
  for (double t : a.x_ticks) {
    out += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"{5}\"/>\n"
        "<line x1=\"{0:.1f}\" y1=\"{2}\" x2=\"{0:.1f}\" y2=\"{3}\" stroke=\"#141414\"/>\n"
        "<text x=\"{0:.1f}\" y=\"{4}\" text-anchor=\"middle\">{6:.4g}</text>\n",
        a.screen_x(t), a.top, bottom, bottom + 6, bottom + 20, hex(kGridColour), t);
  }
  for (double t : a.y_ticks) {
    const double y = a.screen_y(t);
    out += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{4}\"/>\n"
        "<line x1=\"{3}\" y1=\"{1:.1f}\" x2=\"{0}\" y2=\"{1:.1f}\" stroke=\"#141414\"/>\n"
        "<text x=\"{5}\" y=\"{6:.1f}\" text-anchor=\"end\">{7:.4g}</text>\n",
        a.left, y, right, a.left - 6, hex(kGridColour), a.left - 9, y + 4, t);
  }
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#141414\"/>\n",
      a.left, a.top, a.plot_width, a.plot_height);
  return out;
}

void draw_axes(RgbImage& image, const PlotAxes& a) {
  const int bottom = a.frame_bottom(), right = a.frame_right();
  for (double t : a.x_ticks) {
    const int x = static_cast<int>(std::lround(a.screen_x(t)));
    image.fill(x, a.top, x + 1, bottom, kGridColour);
    image.fill(x, bottom, x + 1, bottom + 6, kInk);
    const std::string label = fmt::format("{:.4g}", t);
    image.text(x - image.text_width(label) / 2, bottom + 9, label, kInk);
  }
  for (double t : a.y_ticks) {
    const int y = static_cast<int>(std::lround(a.screen_y(t)));
    image.fill(a.left, y, right, y + 1, kGridColour);
    image.fill(a.left - 6, y, a.left, y + 1, kInk);
    const std::string label = fmt::format("{:.4g}", t);
    image.text(a.left - 9 - image.text_width(label), y - kGlyphHeight / 2, label, kInk);
  }
  image.frame(a.left, a.top, right + 1, bottom + 1, kInk);
}

}  // namespace pkmopt::raster
