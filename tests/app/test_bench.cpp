// `lumis bench`'s statistics that need no timing: the median every figure is reported as (tests/cli/bench.sh runs
// the benchmark itself, with one repetition, where the median is the one value); the report's sections on a report
// made by hand.
#include <gtest/gtest.h>

#include <string>

#include "app/bench.h"

using namespace lumis;

TEST(BenchStatistics, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median_of({}), 0.0);
  EXPECT_EQ(median_of({7}), 7.0);
  EXPECT_EQ(median_of({5, 1, 3}), 3.0);         // unsorted input
  EXPECT_EQ(median_of({4, 1, 3, 2}), 2.5);      // an even count: the mean of the middle two
  EXPECT_EQ(median_of({10, 1, 1000, 2}), 6.0);  // robust to one outlier
}

TEST(BenchStatistics, RawRatesAreMediansFieldByField) {
  std::vector<RawThroughput> runs(4);
  for (int r = 0; r < 4; ++r) {
    runs[r].camera1 = {1.0 + r, 10.0 * (4 - r)};  // wall 1..4, cpu 40..10
    runs[r].shadow16 = {r == 2 ? 1e9 : 5.0, 2.0};
    runs[r].light_query = {double(r * r), 0.5};
  }
  const RawThroughput m = median_raw(runs);
  EXPECT_EQ(m.camera1.wall, 2.5);
  EXPECT_EQ(m.camera1.cpu, 25.0);
  EXPECT_EQ(m.shadow16.wall, 5.0);
  EXPECT_EQ(m.shadow16.cpu, 2.0);
  EXPECT_EQ(m.light_query.wall, 2.5);  // 0, 1, 4, 9
  EXPECT_EQ(median_raw({}).camera1.wall, 0.0);
}

// The budget section is nee_mis's: with --integrator bsdf there is nothing to put under its heading, so neither is
// printed (the heading once stood alone).
TEST(BenchReportText, BudgetHeadingOnlyWithRows) {
  const std::string heading = "What the rays/s target leaves lumis's own code";
  BenchReport r;
  SceneResult s;
  s.name = "cornell-sphere";
  BenchVariantResult v;
  v.integrator = "bsdf";
  v.samples = 1024;
  v.cpu_seconds = 0.5;
  v.ratio = 0.5;
  v.embree_share = 0.25;
  s.variants = {v};
  r.scenes = {s};
  testing::internal::CaptureStdout();
  print_bench_report(r);
  EXPECT_EQ(testing::internal::GetCapturedStdout().find(heading), std::string::npos);
  r.scenes[0].variants[0].integrator = "nee_mis";
  testing::internal::CaptureStdout();
  print_bench_report(r);
  const std::string out = testing::internal::GetCapturedStdout();
  const size_t at = out.find(heading);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NE(out.find("cornell-sphere", at), std::string::npos) << out;
}
