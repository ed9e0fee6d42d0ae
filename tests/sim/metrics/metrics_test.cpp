// Metrics of a run, computed from synthetic truth and pose CSV files with known errors.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "io/input_error.hpp"
#include "host_sim/metrics/metrics.hpp"
#include "host_sim/run/pipeline_process.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

class MetricsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Six frames; the robot at (seq, 0) with yaw 3.1 (near the wrap).
    std::string truth = "seq,t_ns,x,y,z,roll,pitch,yaw\n";
    for (int seq = 0; seq < 6; ++seq) {
      truth += std::to_string(seq) + "," + std::to_string(1'000'000'000 + seq * 50'000'000) + "," +
               std::to_string(seq) + ",0,0,0,0,3.1\n";
    }
    write(dir_ / "truth.csv", truth);
    // Attempts on the LED-on frames 0, 2, 4 and one on frame 5:
    //   0: 0.03 m and 0.0832 rad off across the wrap (-3.1 vs 3.1), marker 7 in view;
    //   2: none;
    //   4: 0.4 m off (gross), marker 9 not in view (wrong ID);
    //   5: 0.04 m off, square source.
    write(dir_ / "pose.csv",
          "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source\n"
          "0,1000000000,ok,0.03,0,0,0,0,-3.1,7,0.9,dot\n"
          "2,1100000000,none,,,,,,,-1,0,dot\n"
          "4,1200000000,ok,4,0.4,0,0,0,3.1,9,0.5,dot\n"
          "5,1250000000,ok,5,0.04,0,0,0,3.1,-1,0.7,square\n");
  }
  test::TempDir dir_;
};

TEST_F(MetricsTest, CountsErrorsAndRates) {
  const VisibleMarkers visible = {{0, {7}}, {4, {7}}, {5, {}}};
  const MetricsSpec thresholds{0.25, 0.2};
  const Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "pose.csv"), visible, thresholds);
  EXPECT_EQ(m.frames, 6u);
  EXPECT_EQ(m.attempts, 4u);
  EXPECT_EQ(m.poses_ok, 3u);
  EXPECT_DOUBLE_EQ(m.detection_rate, 0.75);
  EXPECT_EQ(m.gross_errors, 1u);
  EXPECT_EQ(m.wrong_ids, 1u);
  EXPECT_EQ(m.poses_by_source.at("dot"), 2u);
  EXPECT_EQ(m.poses_by_source.at("square"), 1u);
  EXPECT_NEAR(m.position.max, 0.4, 1e-12);
  EXPECT_NEAR(m.position.rmse, std::sqrt((0.03 * 0.03 + 0.4 * 0.4 + 0.04 * 0.04) / 3), 1e-12);
  EXPECT_NEAR(m.position_inliers.rmse, std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2), 1e-12);
  const double wrap_error = 2 * std::numbers::pi - 6.2;
  EXPECT_NEAR(m.yaw.max, wrap_error, 1e-9);
  EXPECT_NEAR(m.yaw.rmse, std::sqrt(wrap_error * wrap_error / 3), 1e-9);
  ASSERT_EQ(m.errors.size(), 3u);
  EXPECT_NEAR(m.errors[1].t, 0.2, 1e-12);
  EXPECT_TRUE(m.errors[1].gross);
  EXPECT_TRUE(m.errors[1].wrong_id);
  EXPECT_FALSE(m.errors[0].wrong_id);
}

TEST_F(MetricsTest, NoPosesGiveZeroDetectionAndNoErrors) {
  write(dir_ / "none.csv", "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source\n"
                           "0,1000000000,none,,,,,,,-1,0,dot\n");
  const Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "none.csv"), {}, {});
  EXPECT_EQ(m.detection_rate, 0);
  EXPECT_EQ(m.position.count, 0u);
  EXPECT_EQ(m.position.rmse, 0);
}

TEST_F(MetricsTest, JsonHasTheNumbers) {
  const Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "pose.csv"), {}, {});
  write_metrics_json(dir_ / "metrics.json", m, {}, "s.yaml", {"a note"});
  std::ifstream in(dir_ / "metrics.json");
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"detection_rate\": 0.75"), std::string::npos) << json;
  EXPECT_NE(json.find("\"wrong_ids\": 2"), std::string::npos) << json;  // no visibility known: every ID is wrong
  EXPECT_NE(json.find("\"notes\": [\"a note\"]"), std::string::npos) << json;
}

TEST_F(MetricsTest, StageTimesFromIrlocdReachJsonAndSummary) {
  // As irlocd --stats writes it (firmware/stats_file.hpp).
  std::ofstream(dir_ / "stats.json")
      << R"({"frames": 199, "pose_attempts": 100, "poses_ok": 100, "stages": [)"
         R"({"name": "front_end", "total_ms": 21.37, "mean_ms": 0.2137},)"
         R"({"name": "decoding", "total_ms": 2.72, "mean_ms": 0.0272},)"
         R"({"name": "pose", "total_ms": 6.49, "mean_ms": 0.0649}]})";
  const std::vector<std::pair<std::string, double>> stages = read_stage_times(dir_ / "stats.json");
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_EQ(stages[1].first, "decoding");
  EXPECT_DOUBLE_EQ(stages[2].second, 0.0649);
  std::ofstream(dir_ / "not_stats.json") << R"({"frames": 4})";
  EXPECT_THROW(read_stage_times(dir_ / "not_stats.json"), io::InputError);
  EXPECT_THROW(read_stage_times(dir_ / "missing.json"), io::InputError);

  Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "pose.csv"), {}, {});
  m.stage_ms = stages;
  write_metrics_json(dir_ / "metrics.json", m, {}, "s.yaml", {});
  std::ifstream in(dir_ / "metrics.json");
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"stages_ms\": {\"front_end\": 0.2137, \"decoding\": 0.0272, \"pose\": 0.0649}"),
            std::string::npos)
      << json;
  const std::string summary = summarize(m);
  EXPECT_NE(summary.find("stages (ms per pose attempt): front_end 0.214 decoding 0.027 pose 0.065"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("max 400.00 mm (3 poses)"), std::string::npos) << summary;
}

TEST_F(MetricsTest, SourceOutcomesFromIrlocdReachJsonAndSummary) {
  std::ofstream(dir_ / "stats.json") << R"({"frames": 8, "stages": [],)"
                                        R"( "sources": {"led": {"found": 3, "ambiguous": 1}, "dot": {"found": 4}}})";
  const SourceOutcomes outcomes = read_source_outcomes(dir_ / "stats.json");
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_EQ(outcomes.at("led").at("ambiguous"), 1u);
  std::ofstream(dir_ / "not_stats.json") << R"({"frames": 4})";
  EXPECT_THROW(read_source_outcomes(dir_ / "not_stats.json"), io::InputError);

  Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "pose.csv"), {}, {});
  m.source_outcomes = outcomes;
  write_metrics_json(dir_ / "metrics.json", m, {}, "s.yaml", {});
  std::ifstream in(dir_ / "metrics.json");
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find(R"("source_outcomes": {"dot": {"found": 4}, "led": {"ambiguous": 1, "found": 3}})"),
            std::string::npos)
      << json;
  EXPECT_NE(summarize(m).find("  led attempts: ambiguous 1, found 3\n"), std::string::npos) << summarize(m);
}

TEST_F(MetricsTest, SummarySaysNotApplicableWithoutPoses) {
  write(dir_ / "none.csv", "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source\n"
                           "0,1000000000,none,,,,,,,-1,0,dot\n");
  const Metrics m = compute_metrics(read_truth_csv(dir_ / "truth.csv"), read_pose_csv(dir_ / "none.csv"), {}, {});
  EXPECT_NE(summarize(m).find("position and yaw error: n/a (no pose)"), std::string::npos);
}

TEST_F(MetricsTest, MalformedRowsNameFileAndLine) {
  write(dir_ / "bad.csv", "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source\n"
                          "0,1000000000,ok,0.1,zero,0,0,0,0,7,0.9,dot\n");
  try {
    read_pose_csv(dir_ / "bad.csv");
    FAIL() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2: y: not a number"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace irloc::sim
