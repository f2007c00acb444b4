// `lumis compare` internals that need no rendering: option parsing, the reference cache key, the reports, the
// HTML viewer's self-containedness, the shared error scale, the montage layout and its crop row, and the log-log plot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "app/compare.h"
#include "app/montage.h"
#include "app/plot.h"

using namespace lumis;

namespace {

CompareReport sample_report() {
  CompareReport r;
  r.scene = "scenes/cornell-sphere.json";
  r.width = 32;
  r.height = 32;
  r.spp = 16;
  r.reference_source = "rendered";
  r.reference_spp = 256;
  r.error_scale = 0.05;
  for (const char* n : {"uniform", "nee_mis"}) {
    VariantResult v;
    v.name = n;
    v.spp = 16;
    v.seconds = 0.5;
    v.samples = 16 * 32 * 32;
    v.rays = 3 * v.samples;
    v.mse = 0.01;
    v.rel_mse = std::string(n) == "uniform" ? 0.4 : 0.02;
    v.png = v.name + ".png";
    v.error_png = "error-" + v.name + ".png";
    v.convergence = {{1, 0.01, 0.5, 4.0}, {2, 0.02, 0.25, 2.0}};
    r.variants.push_back(v);
  }
  return r;
}

}  // namespace

TEST(CompareOptions, CropAndIntegratorList) {
  {  // Crop
    const CropRect c = parse_crop("4, 8,16,2", 32, 32);
    EXPECT_EQ(c.x, 4);
    EXPECT_EQ(c.y, 8);
    EXPECT_EQ(c.w, 16);
    EXPECT_EQ(c.h, 2);
    EXPECT_THROW(parse_crop("1,2,3", 32, 32), std::invalid_argument);
    EXPECT_THROW(parse_crop("1,2,3,x", 32, 32), std::invalid_argument);
    EXPECT_THROW(parse_crop("1,2,3,4.5", 32, 32), std::invalid_argument);
    EXPECT_THROW(parse_crop("20,0,16,16", 32, 32), std::invalid_argument);  // runs off the right edge
    EXPECT_THROW(parse_crop("0,0,0,4", 32, 32), std::invalid_argument);
    // Sums past INT_MAX must not wrap around into the image.
    EXPECT_THROW(parse_crop("2147483647,0,1,1", 32, 32), std::invalid_argument);
    EXPECT_THROW(parse_crop("1,1,2147483647,4", 32, 32), std::invalid_argument);
    EXPECT_THROW(parse_crop("0,4,4,2147483647", 32, 32), std::invalid_argument);
    // The message names what is wrong: a zero width is no "not inside the image", a huge integer no "not an integer".
    auto crop_error = [](const std::string& text) {
      try {
        parse_crop(text, 32, 32);
      } catch (const std::invalid_argument& e) {
        return std::string(e.what());
      }
      return std::string();
    };
    EXPECT_NE(crop_error("0,0,0,4").find("0,0,0,4: the width and height must be at least 1 pixel"), std::string::npos)
        << crop_error("0,0,0,4");
    EXPECT_NE(crop_error("99999999999,0,1,1").find("'99999999999' is out of range"), std::string::npos)
        << crop_error("99999999999,0,1,1");
  }
  {  // IntegratorList
    EXPECT_EQ(parse_integrator_list("mis,bsdf"), (std::vector<std::string>{"mis", "bsdf"}));
    EXPECT_EQ(parse_integrator_list("uniform,bsdf,light,mis,nee_mis").size(), 5u);
    EXPECT_THROW(parse_integrator_list("mis,mis"), std::invalid_argument);
    EXPECT_THROW(parse_integrator_list("mis,photon"), std::invalid_argument);
    EXPECT_THROW(parse_integrator_list(""), std::invalid_argument);
    try {  // a trailing comma: an empty entry, not "unknown integrator ''"
      parse_integrator_list("bsdf,");
      ADD_FAILURE() << "bsdf, accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'bsdf,' has an empty entry"), std::string::npos) << e.what();
    }
  }
}

TEST(CompareReference, HashFollowsWhatChangesTheImage) {
  RenderSettings s;
  const std::string scene = fnv1a_hex("{\"version\": 1}");  // the scene file's hash
  const std::string h = reference_hash(scene, "", s, 256);
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, reference_hash(scene, "", s, 256));
  // The recipe of earlier versions (the scene file's bytes, then the key), so that their cached references stay valid.
  EXPECT_EQ(h, fnv1a_hex("{\"version\": 1}\n--lumis reference key--\n" + reference_key(s, 256).dump()));
  RenderSettings t = s;
  t.threads = 3;  // thread count does not change the image
  t.integrator = "uniform";  // nor does the comparison's integrator: the reference is always nee_mis
  EXPECT_EQ(h, reference_hash(scene, "", t, 256));
  EXPECT_NE(h, reference_hash(scene, "", s, 512));
  EXPECT_NE(h, reference_hash(fnv1a_hex("{\"version\": 1} "), "", s, 256));
  EXPECT_NE(h, reference_hash(scene, "\ninput cbf29ce484222325", s, 256));  // what follows the scene file counts
  for (auto change : {+[](RenderSettings& r) { r.width = 31; }, +[](RenderSettings& r) { r.max_depth = 2; },
                      +[](RenderSettings& r) { r.rr_depth = 0; }, +[](RenderSettings& r) { r.seed = 5; },
                      +[](RenderSettings& r) { r.light_selection = LightSelection::Uniform; }}) {
    RenderSettings u = s;
    change(u);
    EXPECT_NE(h, reference_hash(scene, "", u, 256));
  }
  EXPECT_NE(reference_seed(0), 0u);
  EXPECT_NE(reference_seed(7), 7u);
  EXPECT_EQ(fnv1a_hex(""), "cbf29ce484222325");  // FNV-1a 64 offset basis
  EXPECT_EQ(fnv1a_hex("a"), "af63dc4c8601ec8c");  // the published FNV-1a 64 test vector
  // An earlier result continues: the hash of "ab" then "cd" is that of "abcd".
  EXPECT_EQ(fnv1a_hex("cd", fnv1a_hex("ab")), fnv1a_hex("abcd"));
  EXPECT_EQ(fnv1a_hex("", fnv1a_hex("ab")), fnv1a_hex("ab"));
  EXPECT_THROW(fnv1a_hex("cd", "af63dc4c8601ec8"), std::invalid_argument);   // 15 digits
  EXPECT_THROW(fnv1a_hex("cd", "af63dc4c8601ec8g"), std::invalid_argument);  // not a hex digit
}

// A file is hashed in 1 MiB pieces: the result is the hash of its whole contents, across the pieces' seams.
TEST(CompareReference, FileHashEqualsTheHashOfItsContents) {
  std::string bytes(3 * (size_t{1} << 20) + 17, '\0');
  uint32_t x = 12345;
  for (char& c : bytes) c = static_cast<char>((x = x * 1664525u + 1013904223u) >> 24);
  const std::string path = ::testing::TempDir() + "lumis_fnv_file.bin";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
    std::fclose(f);
  }
  EXPECT_EQ(fnv1a_file_hex(path), fnv1a_hex(bytes));
  EXPECT_EQ(fnv1a_hex("\ntail", fnv1a_file_hex(path)), fnv1a_hex(bytes + "\ntail"));
  bytes.back() ^= 1;  // the last byte of the last piece counts
  EXPECT_NE(fnv1a_file_hex(path), fnv1a_hex(bytes));
  std::remove(path.c_str());
  EXPECT_EQ(fnv1a_file_hex(path), fnv1a_hex(""));  // gone: hashed as empty, as before
}

// The error pictures share one scale: the worst variant's 99.5th percentile, ignoring NaN and one firefly.
TEST(CompareReport, ErrorScaleIsTheWorstVariantsHighPercentile) {
  std::vector<float> good(1000), bad(1000);
  for (int i = 0; i < 1000; ++i) {
    good[i] = 0.001f * static_cast<float>(i);  // 0, 0.001, ..., 0.999
    bad[i] = 0.002f * static_cast<float>(i);
  }
  bad[17] = 1e6f;  // a firefly
  good[3] = NAN;
  // The 99.5th percentile of n values: the one at index floor(0.995 n) when sorted.
  EXPECT_FLOAT_EQ(shared_error_scale({good}), 0.001f * 995);  // the NaN removed: 999 values, index 994
  EXPECT_FLOAT_EQ(shared_error_scale({bad}), 0.002f * 996);   // 0.034 moved to the end as the firefly: index 995
  EXPECT_FLOAT_EQ(shared_error_scale({good, bad}), 0.002f * 996);
  EXPECT_FLOAT_EQ(shared_error_scale({bad, good}), 0.002f * 996);
  EXPECT_EQ(shared_error_scale({std::vector<float>(10, 0.0f)}), 1e-6);  // no error at all: a scale above zero
  EXPECT_EQ(shared_error_scale({}), 1e-6);
}

// Efficiency 1 / (relMSE x time): an exact match (relMSE 0) is infinitely efficient and a non-finite relMSE has no
// efficiency; neither may read 0, which ranks a variant worst.
TEST(CompareReport, EfficiencyOfAnExactOrNonFiniteResultIsNotZero) {
  VariantResult v;
  v.seconds = 0.5;
  v.rel_mse = 0.02;
  EXPECT_DOUBLE_EQ(v.efficiency(), 100);
  v.rel_mse = 0;
  EXPECT_EQ(v.efficiency(), std::numeric_limits<double>::infinity());
  v.rel_mse = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(v.efficiency()));
  v.seconds = 0;
  v.rel_mse = 0.02;
  EXPECT_TRUE(std::isnan(v.efficiency()));
}

TEST(CompareReport, JsonMarkdownAndSelfContainedHtml) {
  {  // JsonAndMarkdown
    const CompareReport r = sample_report();
    const nlohmann::json j = report_json(r);
    EXPECT_EQ(j["mode"], "equal-spp");
    ASSERT_EQ(j["variants"].size(), 2u);
    EXPECT_DOUBLE_EQ(j["variants"][1]["efficiency"].get<double>(), 1 / (0.02 * 0.5));
    EXPECT_DOUBLE_EQ(j["variants"][0]["samples_per_second"].get<double>(), 16 * 32 * 32 / 0.5);
    EXPECT_EQ(j["variants"][0]["convergence"].size(), 2u);
    const std::string md = report_markdown(r);
    EXPECT_NE(md.find("| variant | spp | time (s) | samples/s | rays/s | MSE | relMSE | efficiency |"),
              std::string::npos);
    EXPECT_NE(md.find("| nee_mis | 16 | 0.500 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| 100 |"), std::string::npos) << md;  // efficiency of nee_mis
  }
  {  // HtmlIsSelfContained
    CompareReport r = sample_report();
    r.scene = "evil</script><b>.json";
    const std::string html = report_html(r);
    EXPECT_EQ(html.find("http://"), std::string::npos);
    EXPECT_EQ(html.find("https://"), std::string::npos);
    EXPECT_EQ(html.find("</script><b>"), std::string::npos);  // escaped both in text and in the embedded JSON
    EXPECT_NE(html.find("image-rendering: pixelated"), std::string::npos);
    EXPECT_NE(html.find("data-ready"), std::string::npos);
    EXPECT_NE(html.find("uniform.png"), std::string::npos);
    EXPECT_NE(html.find("reference.png"), std::string::npos);
  }
}

// report.json's "settings" holds everything the images depend on (the options only one variant reads when that variant
// is compared); the top-level keys scripts read stay; report.md and index.html show the same settings in a line.
TEST(CompareReport, SettingsHoldWhatDeterminesTheImages) {
  CompareReport r = sample_report();
  r.settings.max_depth = 2;
  r.settings.rr_depth = 0;
  r.settings.sampler = SamplerType::Sobol;
  r.settings.seed = 7;
  r.settings.light_selection = LightSelection::Power;
  r.settings.mis_heuristic = MisHeuristic::Power;
  r.settings.uniform_measure = UniformMeasure::SolidAngle;
  const nlohmann::json j = report_json(r);
  EXPECT_EQ(j["spp"], 16);
  EXPECT_EQ(j["width"], 32);
  EXPECT_EQ(j["scene"], r.scene);
  const nlohmann::json& s = j["settings"];
  EXPECT_EQ(s["mode"], "equal-spp");
  EXPECT_EQ(s["spp"], 16);
  EXPECT_EQ(s["width"], 32);
  EXPECT_EQ(s["height"], 32);
  EXPECT_EQ(s["integrators"], (nlohmann::json{"uniform", "nee_mis"}));
  EXPECT_EQ(s["max_depth"], 2);
  EXPECT_EQ(s["rr_depth"], 0);
  EXPECT_EQ(s["sampler"], "sobol");
  EXPECT_EQ(s["seed"], 7);
  EXPECT_EQ(s["light_selection"], "power");
  EXPECT_EQ(s["mis_heuristic"], "power");
  EXPECT_EQ(s["uniform_measure"], "solid-angle");
  EXPECT_FALSE(s.contains("mis_light_probability"));  // no mis variant
  EXPECT_EQ(s["reference_spp"], 256);
  EXPECT_TRUE(s.contains("threads"));
  EXPECT_TRUE(s.contains("exposure"));
  const std::string line = "Settings: max depth 2, no Russian roulette, sobol sampler, seed 7, power light selection, "
                           "power MIS heuristic, uniform measure solid-angle.";
  EXPECT_NE(report_markdown(r).find(line), std::string::npos) << report_markdown(r);
  EXPECT_NE(report_html(r).find(line), std::string::npos);

  r.equal_time = true;
  r.time_budget = 2;
  r.reference_spp = 0;
  r.reference_source = "ref.exr";
  r.variants[0].name = "mis";
  const nlohmann::json t = report_json(r)["settings"];
  EXPECT_EQ(t["mode"], "equal-time");
  EXPECT_EQ(t["time_budget"], 2.0);
  EXPECT_FALSE(t.contains("spp"));
  EXPECT_EQ(t["mis_light_probability"], 0.5);
  EXPECT_FALSE(t.contains("uniform_measure"));
  EXPECT_EQ(t["reference_file"], "ref.exr");
  EXPECT_FALSE(t.contains("reference_spp"));
  // At equal time the thread count is in the line too (it decides how many samples fit); an exposure always is.
  r.settings.threads = 2;
  r.settings.exposure = -1.5f;
  EXPECT_NE(report_markdown(r).find("MIS heuristic, mis light probability 0.5, 2 threads, exposure -1.5."),
            std::string::npos) << report_markdown(r);
  r.settings.threads = 0;
  EXPECT_NE(report_html(r).find("mis light probability 0.5, all cores, exposure -1.5."), std::string::npos);
}

TEST(ComparePictures, MontageAndLogLogPlot) {
  {  // LayoutAndCropRow
    Image a = make_canvas(32, 32, Color(0.5f)), b = make_canvas(32, 32, Color(0.25f));
    a.at(10, 12, 0) = 1.0f;
    MontageOptions o;
    const Image plain = make_montage({{&a, {"A", "1 SPP"}}, {&b, {"REFERENCE"}}}, o);
    // 32-pixel images are enlarged 6x (to 192) and placed side by side with 6-pixel gaps.
    EXPECT_EQ(plain.width, 6 + 2 * (192 + 6));
    EXPECT_NEAR(plain.at(6 + 10 * 6 + 3, 6 + 12 * 6 + 3, 0), 1.0f, 1e-6);
    EXPECT_NEAR(plain.at(6 + 192 + 6 + 50, 6 + 50, 0), 0.25f, 1e-6);
    o.crop_x = 8, o.crop_y = 8, o.crop_w = 8, o.crop_h = 8;
    const Image cropped = make_montage({{&a, {"A", "1 SPP"}}, {&b, {"REFERENCE"}}}, o);
    EXPECT_EQ(cropped.width, plain.width);
    EXPECT_EQ(cropped.height, plain.height + 8 * 24 + 6);  // crops fill the 192-pixel column: 24x
    o.exposure = 1;
    const Image brighter = make_montage({{&b, {}}}, o);
    EXPECT_NEAR(brighter.at(6 + 100, 6 + 100, 0), 0.5f, 1e-6);
  }
  {  // CropRowShowsTheCropRegion: x 8..11 and y 10..13 (not 10..13 and 8..11) hold the marked pixel (10, 12)
    Image a = make_canvas(32, 32, Color(0.5f));
    a.at(10, 12, 1) = 1.0f;  // green 1: no label, outline or background has it
    MontageOptions o;
    o.crop_x = 8, o.crop_y = 10, o.crop_w = 4, o.crop_h = 4;
    const Image m = make_montage({{&a, {"A"}}}, o);
    // The image at 6x (192 pixels), then below it the crop at 48x (its 4 pixels fill the 192-pixel column): the
    // marked pixel is its third column and row.
    int in_tile = 0, in_crop = 0, crop_x0 = m.width, crop_y0 = m.height;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        if (m.at(x, y, 1) != 1.0f) continue;
        if (y < 6 + 192) {
          ++in_tile;
        } else {
          ++in_crop;
          crop_x0 = std::min(crop_x0, x), crop_y0 = std::min(crop_y0, y);
        }
      }
    EXPECT_EQ(in_tile, 6 * 6);
    EXPECT_EQ(in_crop, 48 * 48);
    EXPECT_EQ(crop_x0, 6 + 2 * 48);
    EXPECT_EQ(crop_y0, m.height - 6 - 192 + 2 * 48);
  }
  {  // AWideCropWidensTheColumns: at 2x a 150-pixel crop of a 200-pixel image needs 300; each stays in its column
    const Image a = make_canvas(200, 100, Color(0, 1, 0)), b = make_canvas(200, 100, Color(0, 0, 1));
    MontageOptions o;
    o.crop_x = 0, o.crop_y = 0, o.crop_w = 150, o.crop_h = 50;
    const Image m = make_montage({{&a, {}}, {&b, {}}}, o);
    EXPECT_EQ(m.width, 6 + 2 * (300 + 6));
    int n[2] = {0, 0}, lo[2] = {m.width, m.width}, hi[2] = {-1, -1};
    for (int y = 6 + 100; y < m.height; ++y)  // the crop row, below the tiles (no labels)
      for (int x = 0; x < m.width; ++x)
        for (int t = 0; t < 2; ++t)
          if (m.at(x, y, 1 + t) == 1.0f) ++n[t], lo[t] = std::min(lo[t], x), hi[t] = std::max(hi[t], x);
    for (int t = 0; t < 2; ++t) {
      EXPECT_EQ(n[t], 300 * 100) << "tile " << t;
      EXPECT_EQ(lo[t], 6 + t * 306) << "tile " << t;
      EXPECT_EQ(hi[t], 6 + t * 306 + 299) << "tile " << t;
    }
  }
  {  // LogLogCurvesInTheirColours
    const Color c0 = series_colour(0), c1 = series_colour(1);
    ASSERT_NE(c0, c1);
    const Image img = plot_loglog({{"A", c0, {{0.01, 1}, {0.1, 0.1}, {1, 0.01}}}, {"B", c1, {{0.02, 0.5}, {-1, 2}}}},
                                  "TIME", "ERR", 400, 300);
    EXPECT_EQ(img.width, 400);
    EXPECT_EQ(img.height, 300);
    int n0 = 0, n1 = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        n0 += img.rgb(x, y) == c0;
        n1 += img.rgb(x, y) == c1;
      }
    EXPECT_GT(n0, 200);  // a two-pixel line across most of the plot
    EXPECT_GT(n1, 25);   // one marker (the point with x < 0 is skipped) plus its legend swatch
    const Image empty = plot_loglog({}, "X", "Y", 200, 150);
    EXPECT_EQ(empty.width, 200);
  }
}
