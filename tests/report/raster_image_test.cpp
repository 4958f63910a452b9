// Tests of report/raster_image: viridis, nice ticks, drawing and the PNG encoding.
#include "report/raster_image.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <string>
#include <utility>

namespace {

using pkmopt::raster::Rgb;

// Channels within 1/255 of matplotlib's viridis (#440154 at 0, #21918c at 0.5, #fde725 at 1):
// the table holds three decimals.
void expect_colour(Rgb c, int r, int g, int b) {
  EXPECT_NEAR(c.r, r, 1);
  EXPECT_NEAR(c.g, g, 1);
  EXPECT_NEAR(c.b, b, 1);
}

TEST(Viridis, EndsAndMiddleAreMatplotlibsTable) {
  expect_colour(pkmopt::raster::viridis(0.0), 0x44, 0x01, 0x54);
  expect_colour(pkmopt::raster::viridis(0.5), 0x21, 0x91, 0x8c);
  expect_colour(pkmopt::raster::viridis(1.0), 0xfd, 0xe7, 0x25);
  EXPECT_EQ(pkmopt::raster::hex(pkmopt::raster::viridis(-3.0)),
            pkmopt::raster::hex(pkmopt::raster::viridis(0.0)));  // clamped
  EXPECT_EQ(pkmopt::raster::hex(pkmopt::raster::viridis(7.0)),
            pkmopt::raster::hex(pkmopt::raster::viridis(1.0)));
  EXPECT_EQ(pkmopt::raster::hex(Rgb{0, 15, 255}), "#000fff");
}

void expect_ticks(const std::vector<double>& ticks, const std::vector<double>& expected) {
  ASSERT_EQ(ticks.size(), expected.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_NEAR(ticks[i], expected[i], 1e-12 * std::max(1.0, std::abs(expected[i])));
  }
}

TEST(NiceTicks, StepsOfOneTwoOrFiveCoveringTheRange) {
  // range / target = 0.2 -> step 0.2.
  expect_ticks(pkmopt::raster::nice_ticks(0.0, 1.0, 5), {0, 0.2, 0.4, 0.6, 0.8, 1});
  // 0.79 / 6 = 0.132 -> step 0.2 (the first of 0.1, 0.2, 0.5, 1 not below it).
  expect_ticks(pkmopt::raster::nice_ticks(-0.37, 0.42, 6), {-0.2, 0, 0.2, 0.4});
  // 3.37e6 / 6 = 5.6e5 -> step 1e6.
  expect_ticks(pkmopt::raster::nice_ticks(8.7e5, 4.24e6, 6), {1e6, 2e6, 3e6, 4e6});
  expect_ticks(pkmopt::raster::nice_ticks(2.0, 2.0, 5), {2.0});
}

// Decodes a PNG with libpng's simplified API into RGB bytes.
std::vector<std::uint8_t> decode(const std::string& png, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&image, png.data(), png.size()));
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return pixels;
}

TEST(RgbImage, DiscRingAndFillDecodeBackFromThePng) {
  pkmopt::raster::RgbImage image(40, 30, pkmopt::raster::kWhite);
  const Rgb red{200, 10, 20}, blue{10, 20, 200};
  image.disc(10.0, 10.0, 5.0, red);  // pixel centres within 5 px of (10, 10)
  image.ring(30.0, 15.0, 6.0, 1.5, blue);
  image.fill(0, 28, 40, 30, pkmopt::raster::kInk);
  image.fill(-5, -5, 2, 2, blue);  // clipped
  int width = 0, height = 0;
  const auto px = decode(image.encode_png(), width, height);
  ASSERT_EQ(width, 40);
  ASSERT_EQ(height, 30);
  auto at = [&](int x, int y) {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * 40 + x);
    return Rgb{px[i], px[i + 1], px[i + 2]};
  };
  auto same = [](Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; };
  int disc_pixels = 0;
  for (int y = 0; y < 28; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool inside = std::hypot(x + 0.5 - 10.0, y + 0.5 - 10.0) <= 5.0;
      if (x < 2 && y < 2) continue;
      EXPECT_EQ(same(at(x, y), red), inside) << x << "," << y;
      disc_pixels += inside;
    }
  }
  EXPECT_NEAR(disc_pixels, M_PI * 25.0, 6.0);             // area of the disc
  EXPECT_TRUE(same(at(30, 15), pkmopt::raster::kWhite));  // the ring's hole
  EXPECT_TRUE(same(at(35, 15), blue));                    // on the ring (distance 5.5)
  EXPECT_TRUE(same(at(0, 0), blue));
  EXPECT_TRUE(same(at(20, 29), pkmopt::raster::kInk));
}

TEST(RgbImage, TextDrawsGlyphsAndSkipsUnknownCharacters) {
  pkmopt::raster::RgbImage image(200, 20, pkmopt::raster::kWhite);
  EXPECT_EQ(image.text_width("abc"), 3 * pkmopt::raster::kGlyphAdvance - 2);
  image.text(0, 0, "m^3 (N)", pkmopt::raster::kInk);
  int width = 0, height = 0;
  const auto px = decode(image.encode_png(), width, height);
  auto inked_in_column_range = [&](int x0, int x1) {
    int n = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = x0; x < x1; ++x) n += px[3 * (static_cast<std::size_t>(y) * width + x)] == 20;
    }
    return n;
  };
  const int a = pkmopt::raster::kGlyphAdvance;
  EXPECT_GT(inked_in_column_range(0, a), 0);          // m
  EXPECT_GT(inked_in_column_range(a, 2 * a), 0);      // ^
  EXPECT_EQ(inked_in_column_range(3 * a, 4 * a), 0);  // the space
  EXPECT_GT(inked_in_column_range(5 * a, 6 * a), 0);  // N
}

TEST(RgbImage, CapitalsWithoutAGlyphAreDrawnAsSmallLetters) {
  pkmopt::raster::RgbImage upper(60, 20, pkmopt::raster::kWhite);
  pkmopt::raster::RgbImage lower(60, 20, pkmopt::raster::kWhite);
  upper.text(0, 0, "Hex", pkmopt::raster::kInk);
  lower.text(0, 0, "hex", pkmopt::raster::kInk);
  EXPECT_EQ(upper.encode_png(), lower.encode_png());
  pkmopt::raster::RgbImage blank(60, 20, pkmopt::raster::kWhite);
  EXPECT_NE(upper.encode_png(), blank.encode_png());
}

// The plot range: 5 % of the span on each side; an empty span 5 % of the value (1 about 0);
// inverted or NaN ranges become [0, 1].
TEST(PaddedRange, WidensByFivePercent) {
  auto padded = [](double low, double high) {
    pkmopt::raster::padded_range(low, high);
    return std::pair{low, high};
  };
  EXPECT_EQ(padded(0.0, 10.0), std::pair(-0.5, 10.5));
  EXPECT_EQ(padded(4.0, 4.0), std::pair(3.8, 4.2));
  EXPECT_EQ(padded(0.0, 0.0), std::pair(-1.0, 1.0));
  EXPECT_EQ(padded(2.0, 1.0), std::pair(0.0, 1.0));
  EXPECT_EQ(padded(std::nan(""), 1.0), std::pair(0.0, 1.0));
}

// The axes map their value ranges onto the frame (y downwards) and draw one grid line, tick
// and label per tick, and the frame.
TEST(PlotAxes, MapRangesOntoTheFrameAndDrawEveryTick) {
  pkmopt::raster::PlotAxes axes;
  axes.left = 100;
  axes.top = 50;
  axes.plot_width = 400;
  axes.plot_height = 200;
  axes.x_low = -1.0;
  axes.x_high = 3.0;
  axes.y_low = 10.0;
  axes.y_high = 20.0;
  axes.x_ticks = {-1.0, 0.0, 1.0, 2.0, 3.0};
  axes.y_ticks = {10.0, 15.0, 20.0};
  EXPECT_EQ(axes.screen_x(-1.0), 100.0);
  EXPECT_EQ(axes.screen_x(3.0), 500.0);
  EXPECT_EQ(axes.screen_y(10.0), 250.0);
  EXPECT_EQ(axes.screen_y(20.0), 50.0);
  EXPECT_EQ(axes.frame_right(), 500);
  EXPECT_EQ(axes.frame_bottom(), 250);
  const std::string svg = pkmopt::raster::svg_axes(axes);
  std::size_t lines = 0, texts = 0;
  for (std::size_t at = svg.find("<line"); at != std::string::npos; at = svg.find("<line", at + 1))
    ++lines;
  for (std::size_t at = svg.find("<text"); at != std::string::npos; at = svg.find("<text", at + 1))
    ++texts;
  EXPECT_EQ(lines, 2u * 8u);  // grid line and tick mark per tick
  EXPECT_EQ(texts, 8u);
  EXPECT_NE(svg.find(">15</text>"), std::string::npos);
  EXPECT_NE(svg.find("<rect x=\"100\" y=\"50\" width=\"400\" height=\"200\""), std::string::npos);
  pkmopt::raster::RgbImage image(600, 300, pkmopt::raster::kWhite);
  pkmopt::raster::draw_axes(image, axes);
  pkmopt::raster::RgbImage frame_only(600, 300, pkmopt::raster::kWhite);
  frame_only.frame(100, 50, 501, 251, pkmopt::raster::kInk);
  EXPECT_NE(image.encode_png(), frame_only.encode_png());
}

}  // namespace
