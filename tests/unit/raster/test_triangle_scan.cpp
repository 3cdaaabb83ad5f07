// TriangleScanner: the strategy dispatch every renderer scans through.
// Span and bounding box give identical spans; B-Convert falls back to the
// bounding box (counted) for a face far larger than the image; names parse.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "raster/bconvert_scan.h"
#include "raster/raster_target.h"
#include "raster/screen_triangle.h"
#include "raster/triangle_scan.h"

namespace zs {
namespace {

void expect_same_spans(const FaceSpans& a, const FaceSpans& b, int n) {
  ASSERT_EQ(a.size(), b.size()) << "triangle " << n;
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.rows[k].y, b.rows[k].y) << "triangle " << n;
    ASSERT_EQ(a.rows[k].x0, b.rows[k].x0) << "triangle " << n;
    ASSERT_EQ(a.rows[k].x1, b.rows[k].x1) << "triangle " << n;
  }
}

// Scans `tri` through a scanner into `out` (cleared first).
bool scan_with(TriangleScanner& sc, const ScreenVertex tri[3], const Viewport& vp, FaceSpans& out,
               ScanCounters& c) {
  ScreenTriangle st;
  const bool ok = setup_triangle(tri, false, &st);
  sc.prepare(tri, ok);
  out.clear();
  if (ok) sc.scan(st, vp, out, c);
  return ok;
}

TEST(TriangleScanner, SpanAndBBoxGiveIdenticalSpans) {
  const Viewport image{0, 0, 96, 80};
  const Viewport tiles[] = {{0, 0, 96, 80}, {0, 0, 32, 32}, {32, 32, 64, 64}, {64, 48, 96, 80}, {10, 5, 11, 70}};
  TriangleScanner span(ScanStrategy::Span, BConvertVariant::Truncate, image);
  TriangleScanner bbox(ScanStrategy::BBox, BConvertVariant::Truncate, image);
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> ux(-20, 116), uy(-20, 100), big(-1e4, 1e4);
  std::uniform_int_distribution<int> shape(0, 5);
  uint64_t pixels = 0;
  int scanned = 0;
  for (int n = 0; n < 5000; ++n) {
    ScreenVertex v[3];
    for (int k = 0; k < 3; ++k) {
      double x = ux(rng), y = uy(rng);
      switch (shape(rng)) {
        case 0: x = big(rng); break;                                  // far outside the image
        case 1: x = std::round(x), y = std::round(y); break;          // on pixel centres
        case 2: if (k) y = v[0].y; break;                             // a horizontal edge
        default: break;
      }
      v[k] = {x, y, 1.0 + 0.25 * k, 0.5 * k, uint32_t(3 * n + k)};
    }
    const Viewport vp = tiles[n % 5];
    FaceSpans a, b;
    ScanCounters ca, cb;
    const bool ok = scan_with(span, v, vp, a, ca);
    scan_with(bbox, v, vp, b, cb);
    if (!ok) continue;
    ++scanned;
    expect_same_spans(a, b, n);
    EXPECT_EQ(ca.pixel_hits, cb.pixel_hits);
    EXPECT_EQ(a.pixels(), cb.pixel_hits);
    for (const RowSpan& r : a.rows) {
      ASSERT_LE(vp.x0, r.x0);
      ASSERT_LE(r.x0, r.x1);
      ASSERT_LT(r.x1, vp.x1);
      ASSERT_LE(vp.y0, r.y);
      ASSERT_LT(r.y, vp.y1);
    }
    pixels += a.pixels();
  }
  EXPECT_GT(scanned, 4500);
  EXPECT_GT(pixels, 100000u);  // the comparison is not between empty scans
  // Neither strategy is B-Convert: nothing to fall back from.
  EXPECT_EQ(span.take_bconvert_fallbacks(), 0u);
  EXPECT_EQ(bbox.take_bconvert_fallbacks(), 0u);
}

TEST(TriangleScanner, BConvertFallsBackToBBoxForHugeFaces) {
  const Viewport image{0, 0, 64, 48};
  for (BConvertVariant variant : {BConvertVariant::Truncate, BConvertVariant::Round, BConvertVariant::Dilate,
                                  BConvertVariant::Dda3d, BConvertVariant::RunLength}) {
    TriangleScanner bc(ScanStrategy::BConvert, variant, image);
    TriangleScanner bbox(ScanStrategy::BBox, variant, image);
    FaceSpans a, b;
    ScanCounters ca, cb;
    // A small face inside the image: B-Convert's own lists, no fallback.
    const ScreenVertex small[3] = {{10.2, 5.3, 1, 0, 0}, {30.7, 9.1, 1, 0, 1}, {18.4, 28.8, 1, 0, 2}};
    ASSERT_TRUE(scan_with(bc, small, image, a, ca));
    EXPECT_GT(a.pixels(), 100u);
    EXPECT_EQ(bc.take_bconvert_fallbacks(), 0u) << to_string(variant);
    // A face reaching far beyond the image (its limit: 4 image sizes + 16
    // pixels past an edge) covering all of it: counted, and scanned as the
    // bounding box would.
    const ScreenVertex huge[3] = {{-1e5, -1e5, 1, 0, 3}, {1e5, -1e5, 1, 0, 4}, {0, 1e5, 1, 0, 5}};
    ASSERT_TRUE(scan_with(bc, huge, image, a, ca));
    ASSERT_TRUE(scan_with(bbox, huge, image, b, cb));
    EXPECT_EQ(bc.take_bconvert_fallbacks(), 1u) << to_string(variant);
    EXPECT_EQ(bc.take_bconvert_fallbacks(), 0u);  // taking resets the count
    expect_same_spans(a, b, 0);
    EXPECT_EQ(a.pixels(), uint64_t(64) * 48);
    // Just past the limit on one side only, on a tile of the image: the
    // test is against the whole image, so still a fallback.
    const Viewport tile{32, 16, 48, 32};
    const ScreenVertex wide[3] = {{20, 20, 1, 0, 6}, {64 + 4 * 64 + 17, 22, 1, 0, 7}, {25, 30, 1, 0, 8}};
    ASSERT_TRUE(scan_with(bc, wide, tile, a, ca));
    ASSERT_TRUE(scan_with(bbox, wide, tile, b, cb));
    EXPECT_EQ(bc.take_bconvert_fallbacks(), 1u) << to_string(variant);
    expect_same_spans(a, b, 1);
    EXPECT_GT(a.pixels(), 0u);
    // Several huge faces count one each; a degenerate one is never counted.
    for (int i = 0; i < 3; ++i) scan_with(bc, huge, image, a, ca);
    const ScreenVertex flat[3] = {{1e6, 0, 1, 0, 9}, {2e6, 0, 1, 0, 10}, {3e6, 0, 1, 0, 11}};
    EXPECT_FALSE(scan_with(bc, flat, image, a, ca));
    EXPECT_EQ(bc.take_bconvert_fallbacks(), 3u);
  }
}

TEST(TriangleScanner, StrategyAndVariantNamesRoundTrip) {
  for (ScanStrategy s : {ScanStrategy::BBox, ScanStrategy::BConvert, ScanStrategy::Span}) {
    ScanStrategy back = s == ScanStrategy::BBox ? ScanStrategy::Span : ScanStrategy::BBox;
    ASSERT_TRUE(parse_scan_strategy(to_string(s), &back)) << to_string(s);
    EXPECT_EQ(back, s);
  }
  EXPECT_STREQ(to_string(ScanStrategy::BBox), "bbox");
  EXPECT_STREQ(to_string(ScanStrategy::BConvert), "bconvert");
  EXPECT_STREQ(to_string(ScanStrategy::Span), "span");
  ScanStrategy untouched = ScanStrategy::Span;
  for (const char* bad : {"", "BBox", "spans", "b-convert", "bbox "}) {
    EXPECT_FALSE(parse_scan_strategy(bad, &untouched)) << bad;
    EXPECT_EQ(untouched, ScanStrategy::Span);
  }
  for (BConvertVariant v : {BConvertVariant::Truncate, BConvertVariant::Round, BConvertVariant::Dilate,
                            BConvertVariant::Dda3d, BConvertVariant::RunLength}) {
    BConvertVariant back = v == BConvertVariant::Round ? BConvertVariant::Truncate : BConvertVariant::Round;
    ASSERT_TRUE(parse_bconvert_variant(to_string(v), &back)) << to_string(v);
    EXPECT_EQ(back, v);
  }
  BConvertVariant bv = BConvertVariant::Dilate;
  EXPECT_FALSE(parse_bconvert_variant("nope", &bv));
  EXPECT_EQ(bv, BConvertVariant::Dilate);
}

}  // namespace
}  // namespace zs
