// irlocd replay, run as a user runs it: the binary, a dataset, its exit status, stderr, pose CSV.

#include <sys/stat.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "algo/pipeline/localizer.hpp"
#include "io/config/config_file.hpp"
#include "io/config/config_reference.hpp"
#include "io/files/pose_csv_writer.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/file_size_limited_run.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

using ::testing::HasSubstr;
using test::read_text;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

using test::ProcessResult;

class IrlocdReplay : public ::testing::Test {
 protected:
  std::filesystem::path dataset() const { return dir_ / "dataset"; }
  std::filesystem::path pose_csv() const { return dir_ / "pose.csv"; }

  void make_dataset(int frames, std::vector<std::uint64_t> dropped_seqs = {}, bool sixteen_bit = false) {
    sim::SyntheticDatasetOptions options;
    options.frames = frames;
    options.dropped_seqs = std::move(dropped_seqs);
    options.sixteen_bit = sixteen_bit;
    sim::write_synthetic_dataset(dataset(), options);
  }

  ProcessResult irlocd(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), IRLOCD_PATH);
    return test::run_to_end(std::move(arguments), dir_ / "stderr.txt");
  }
  // A replay of the dataset with `more` options.
  ProcessResult replay_with(const std::vector<std::string>& more) {
    std::vector<std::string> arguments = {"--config", (dataset() / "config.yaml").string(), "--camera",
                                          "dir:" + dataset().string(), "--serial", "none"};
    arguments.insert(arguments.end(), more.begin(), more.end());
    return irlocd(std::move(arguments));
  }
  // A replay writing the pose CSV, with `more` options.
  ProcessResult replay(std::vector<std::string> more = {}) {
    more.insert(more.begin(), {"--pose-csv", pose_csv().string()});
    return replay_with(more);
  }
  // The run failed with exactly one line on stderr, which names `file` and says `problem`.
  void expect_one_error_line(const ProcessResult& run, const std::filesystem::path& file, const std::string& problem) {
    EXPECT_NE(run.status, 0);
    const std::vector<std::string> lines = lines_of(run.stderr_text);
    ASSERT_EQ(lines.size(), 1u) << run.stderr_text;
    EXPECT_THAT(lines[0], HasSubstr(file.string()));
    EXPECT_THAT(lines[0], HasSubstr(problem));
  }
  void replace_in(const std::filesystem::path& file, const std::string& from, const std::string& to) {
    std::string text = read_text(file);
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    std::ofstream(file, std::ios::binary) << text.replace(at, from.size(), to);
  }

  test::TempDir dir_;
};

TEST_F(IrlocdReplay, WritesOneRowPerLedOnFrame) {
  make_dataset(10);
  const ProcessResult run = replay();
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::vector<std::string> rows = lines_of(read_text(pose_csv()));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0], "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source");
  for (int i = 0; i < 5; ++i) {
    // LED on for even seq in the synthetic dataset; no marker path yet, so `none`.
    EXPECT_THAT(rows[static_cast<std::size_t>(i) + 1], ::testing::StartsWith(std::to_string(2 * i) + ","));
    EXPECT_THAT(rows[static_cast<std::size_t>(i) + 1], HasSubstr(",none,,,,,,,-1,0,"));
  }
  EXPECT_THAT(run.stderr_text, HasSubstr("10 frames, 5 pose attempts (0 without an LED-off partner)"));
}

// --calibrate on a drive without a single dot pose: one line naming the option and why, a
// non-zero status, the pose CSV written all the same (docs/calibration.md).
TEST_F(IrlocdReplay, CalibrateWithoutDotPosesIsAnErrorThatKeepsThePoses) {
  make_dataset(10);
  const ProcessResult run = replay({"--calibrate", (dir_ / "calibrated").string()});
  EXPECT_NE(run.status, 0);
  const std::vector<std::string> lines = lines_of(run.stderr_text);
  ASSERT_EQ(lines.size(), 1u) << run.stderr_text;
  EXPECT_THAT(lines[0], HasSubstr("--calibrate: no calibration from this drive: the drive gave 0 poses with dots"));
  EXPECT_EQ(lines_of(read_text(pose_csv())).size(), 6u);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "calibrated" / "config.yaml"));
}

TEST_F(IrlocdReplay, NeverPairsAcrossDroppedFrames) {
  // On-frames 4 and 6 lose both neighbours (3, 5, 7 dropped); 8 loses 7 but pairs with 9.
  make_dataset(12, {3, 5, 7}, true);
  const ProcessResult run = replay();
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_EQ(lines_of(read_text(pose_csv())).size(), 7u);  // header + on-frames 0, 2, 4, 6, 8, 10
  EXPECT_THAT(run.stderr_text, HasSubstr("9 frames, 6 pose attempts (2 without an LED-off partner)"));
}

TEST_F(IrlocdReplay, StatsFileCountsWhatThePoseCsvShows) {
  make_dataset(12, {3, 5, 7}, true);
  const std::filesystem::path stats = dir_ / "stats.json";
  const ProcessResult run = replay({"--stats", stats.string()});
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const nlohmann::json json = nlohmann::json::parse(read_text(stats));
  EXPECT_EQ(json.at("frames").get<int>(), 9);
  EXPECT_EQ(json.at("pose_attempts").get<std::size_t>(), lines_of(read_text(pose_csv())).size() - 1);
  EXPECT_EQ(json.at("unpaired").get<int>(), 2);
  EXPECT_EQ(json.at("poses_ok").get<int>(), 0);  // the synthetic dataset's map has no landmarks
  EXPECT_FALSE(json.at("stopped").get<bool>());
  EXPECT_TRUE(json.at("stages").is_array());
  EXPECT_TRUE(json.at("sources").is_object());
  // The stages are timed inside the attempts' wall time, so they cannot add up to more.
  double stages_ms = 0;
  for (const nlohmann::json& stage : json.at("stages")) stages_ms += stage.at("total_ms").get<double>();
  EXPECT_GT(stages_ms, 0);
  EXPECT_LE(stages_ms, json.at("attempts_wall").at("total_ms").get<double>());
  // The four paired attempts: the first one is sampled (one in FrontEndProbe::kEvery), its front
  // end against a copy of its pair.
  const nlohmann::json& probe = json.at("front_end_vs_memcpy");
  EXPECT_EQ(probe.at("samples").get<int>(), 1);
  EXPECT_GT(probe.at("front_end_ms").get<double>(), 0);
  EXPECT_GT(probe.at("memcpy_pair_ms").get<double>(), 0);
  EXPECT_DOUBLE_EQ(probe.at("ratio").get<double>(),
                   probe.at("front_end_ms").get<double>() / probe.at("memcpy_pair_ms").get<double>());
  for (const auto& entry : std::filesystem::directory_iterator(dir_.path())) {  // no temporary left behind
    EXPECT_THAT(entry.path().filename().string(), ::testing::AnyOf("dataset", "pose.csv", "stats.json", "stderr.txt"));
  }
}

// A replay is paced only on request; then each frame is delivered at its recorded time and the
// capture-to-write latency is measured as on a robot (StarGazer answers every attempt, so each
// counts); as fast as it can, the frames' capture has no time on the link's clock and none is.
TEST_F(IrlocdReplay, APacedReplayMeasuresCaptureToWriteLatency) {
  make_dataset(20);
  test::PseudoTerminal pty;  // nobody reads it: the serial port drops what does not fit
  const std::filesystem::path stats = dir_ / "stats.json";
  const auto latency = [&](bool paced) {
    std::vector<std::string> arguments{"--config", (dataset() / "config.yaml").string(), "--camera", "dir:" + dataset().string(),
                                       "--serial", pty.slave_path(), "--protocol", "stargazer", "--stats", stats.string()};
    if (paced) arguments.push_back("--paced");
    const ProcessResult run = irlocd(arguments);
    EXPECT_EQ(run.status, 0) << run.stderr_text;
    const nlohmann::json json = nlohmann::json::parse(read_text(stats));
    return json.contains("capture_to_write_ms") ? json.at("capture_to_write_ms") : nlohmann::json();
  };
  EXPECT_TRUE(latency(false).is_null());
  const nlohmann::json paced = latency(true);
  ASSERT_TRUE(paced.is_object());
  EXPECT_EQ(paced.at("poses").get<int>(), 10);  // every LED-on frame's attempt
  EXPECT_GT(paced.at("median").get<double>(), 0.0);
  EXPECT_GE(paced.at("p99").get<double>(), paced.at("median").get<double>());

  const ProcessResult live = irlocd({"--config", (dataset() / "config.yaml").string(), "--camera", "sim:4", "--paced"});
  expect_one_error_line(live, "--paced", "only for a recording");
}

// The rolling shutter the sources assume (docs/formats.md): the config's camera.line_time_ns,
// else the board's; --stats names the one used.
TEST_F(IrlocdReplay, TheBoardsLineTimeHoldsWhereTheConfigGivesNone) {
  make_dataset(4);
  std::ofstream(dir_ / "board.yaml") << "name: test\ndescription: a rolling-shutter board\n"
                                        "camera: {driver: libcamera, formats: [R8], frame_duration_us: 16667,\n"
                                        "         exposure_us: 1000, analogue_gain: 1, line_time_ns: 30000,\n"
                                        "         calibration: " << (dataset() / "calib.yaml").string() << "}\n"
                                        "strobe: {chip: gpiochip0, line: 17, active_low: false, latency_frames: 1,\n"
                                        "         noise_level: 12, min_contrast_ratio: 3}\n";
  const std::filesystem::path stats = dir_ / "stats.json";
  const auto line_time_used = [&] {
    const ProcessResult run = replay_with({"--board", (dir_ / "board.yaml").string(), "--stats", stats.string()});
    EXPECT_EQ(run.status, 0) << run.stderr_text;
    return nlohmann::json::parse(read_text(stats)).at("line_time_ns").get<std::int64_t>();
  };
  EXPECT_EQ(line_time_used(), 30000);
  replace_in(dataset() / "config.yaml", "camera:\n", "camera:\n  line_time_ns: 20000\n");
  EXPECT_EQ(line_time_used(), 20000);
}

// Under the default board's rolling shutter, a drive that starts under one marker (a 1.38 m circle
// at 0.70 m/s): its first pose rests on a motion its frame does not decide, and irlocd writes it
// one attempt late, as the next attempt revised it (Localizer::revised_previous), in its own
// place: the pose CSV has one row per attempt in frame order, the first row is the Localizer's
// revision (against the truth: its yaw closer than the unrevised first pose's), and --stats
// counts it.
TEST_F(IrlocdReplay, AFirstPoseUnderOneMarkerIsWrittenRevisedInItsPlace) {
  sim::Scenario scenario = sim::load_scenario(std::filesystem::path(IRLOC_SCENARIOS_DIR) / "dot_rolling_board.yaml");
  scenario.frames = 8;
  scenario.trajectory.centre = Eigen::Vector2d(-0.051, -0.439);
  scenario.trajectory.radius = 1.382;
  scenario.trajectory.speed = 0.698;
  scenario.trajectory.clockwise = false;
  const std::vector<sim::TruthRow> truth = sim::render_dataset(scenario, dataset());
  const std::filesystem::path stats = dir_ / "stats.json";
  const ProcessResult run = replay({"--stats", stats.string()});
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_EQ(nlohmann::json::parse(read_text(stats)).at("poses_revised").get<int>(), 1);

  // The same frames through a Localizer: its first estimate and the revision the next attempt gives.
  io::RobotConfig config = io::load_robot_config(dataset() / "config.yaml");
  hal::DatasetCamera frames(dataset(), config.setup.camera.width, config.setup.camera.height, "calib.yaml");
  Localizer localizer(std::move(config.setup));
  StrobePairer pairer;
  std::vector<PoseEstimate> attempts;
  std::optional<PoseEstimate> revised;
  for (Frame frame; frames.next(frame);) {
    if (const std::optional<StrobePair> pair = pairer.push(frame)) {
      attempts.push_back(localizer.process(*pair));
      if (attempts.size() == 2) revised = localizer.revised_previous();
    }
  }
  ASSERT_EQ(attempts.size(), 4u);
  ASSERT_TRUE(attempts[0].revisable);
  ASSERT_TRUE(revised.has_value());

  const std::vector<PoseEstimate> rows = sim::read_pose_csv(pose_csv());
  ASSERT_EQ(rows.size(), attempts.size());
  for (std::size_t k = 0; k < rows.size(); ++k) EXPECT_EQ(rows[k].seq, attempts[k].seq) << "row " << k;
  EXPECT_NEAR(rows[0].x, revised->x, 1e-6);
  EXPECT_NEAR(rows[0].y, revised->y, 1e-6);
  EXPECT_NEAR(rows[0].yaw, revised->yaw, 1e-6);
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_NEAR(rows[k].x, attempts[k].x, 1e-6) << "row " << k;
  const auto at = std::find_if(truth.begin(), truth.end(), [&](const sim::TruthRow& row) { return row.seq == attempts[0].seq; });
  ASSERT_NE(at, truth.end());
  EXPECT_LT(std::abs(wrap_angle(rows[0].yaw - at->yaw)), 0.6 * std::abs(wrap_angle(attempts[0].yaw - at->yaw)));
}

// A disk that fills while recording and writing the pose CSV (every file limited to 2 KiB): each
// output stops with one line saying what it holds, the loop goes on to the last frame, the pose
// CSV holds whole rows only, the recording is a dataset of the frames before, frame for frame
// those replayed; the exit status says that data was lost.
TEST_F(IrlocdReplay, AFullDiskStopsTheOutputsNotTheLoopAndLeavesThemValid) {
  sim::SyntheticDatasetOptions options;
  options.width = 48;  // 1.5 KiB frames: each fits, frames.csv and the pose CSV outgrow 2 KiB
  options.height = 32;
  options.frames = 120;
  sim::write_synthetic_dataset(dataset(), options);
  const std::filesystem::path recording = dir_ / "recording";
  const test::ProcessResult run = test::run_with_file_size_limit(
      {IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera", "dir:" + dataset().string(), "--serial",
       "none", "--pose-csv", pose_csv().string(), "--record", recording.string()},
      2048);
  EXPECT_EQ(run.status, 1) << run.stderr_text;
  const std::vector<std::string> lines = lines_of(run.stderr_text);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back(), "irlocd: 120 frames, 60 pose attempts (0 without an LED-off partner), 0 poses ok; an output "
                          "failed (above): data was lost");

  std::smatch match;
  const std::regex recording_stopped(": cannot write: File too large: recording stopped at frame (\\d+); the dataset "
                                     "holds the (\\d+) frames before it");
  ASSERT_TRUE(std::regex_search(run.stderr_text, match, recording_stopped)) << run.stderr_text;
  const std::uint64_t recorded = std::stoull(match[2]);
  EXPECT_EQ(std::stoull(match[1]), recorded);
  EXPECT_THAT(run.stderr_text, HasSubstr("irlocd: --record " + recording.string() + ": " +
                                         (recording / "frames.csv").string() + ": cannot write: File too large"));
  EXPECT_GT(recorded, 10u);
  EXPECT_LT(recorded, 120u);
  hal::DatasetCamera source(dataset(), 48, 32, "calib.yaml");
  hal::DatasetCamera copy(recording, 48, 32, "calib.yaml");
  EXPECT_EQ(copy.frame_count(), recorded);
  Frame original;
  Frame recorded_frame;
  for (std::uint64_t k = 0; k < recorded; ++k) {
    ASSERT_TRUE(source.next(original));
    ASSERT_TRUE(copy.next(recorded_frame));
    EXPECT_EQ(recorded_frame.seq, original.seq);
    EXPECT_EQ(recorded_frame.t_ns, original.t_ns);
    EXPECT_EQ(recorded_frame.led_on, original.led_on);
    const ImageView8& a = std::get<ImageView8>(original.image);
    const ImageView8& b = std::get<ImageView8>(recorded_frame.image);
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 48; ++x) ASSERT_EQ(b.at(x, y), a.at(x, y)) << "frame " << k << " pixel " << x << "," << y;
    }
  }
  EXPECT_FALSE(copy.next(recorded_frame));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(recording), std::filesystem::directory_iterator()),
            static_cast<std::ptrdiff_t>(recorded + 1));  // no partial frame left beside frames.csv

  const std::regex rows_stopped(": cannot write: File too large: pose rows stopped at frame (\\d+); the file holds "
                                "the (\\d+) whole rows before it");
  ASSERT_TRUE(std::regex_search(run.stderr_text, match, rows_stopped)) << run.stderr_text;
  const std::size_t rows = std::stoull(match[2]);
  EXPECT_EQ(std::stoull(match[1]), 2 * rows);  // LED on for even seq
  EXPECT_THAT(run.stderr_text, HasSubstr("irlocd: --pose-csv " + pose_csv().string() + ": " + pose_csv().string()));
  const std::string text = read_text(pose_csv());
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const std::vector<std::string> pose_lines = lines_of(text);
  ASSERT_EQ(pose_lines.size(), rows + 1);
  EXPECT_EQ(pose_lines[0], io::PoseCsvWriter::kHeader);
  for (std::size_t k = 1; k < pose_lines.size(); ++k) {
    EXPECT_EQ(std::count(pose_lines[k].begin(), pose_lines[k].end(), ','), 11) << pose_lines[k];
    EXPECT_THAT(pose_lines[k], ::testing::StartsWith(std::to_string(2 * (k - 1)) + ",")) << pose_lines[k];
  }
  EXPECT_EQ(lines.size(), 4u) << run.stderr_text;  // the two lines, the stage times, the summary
}

// What a user copies and edits: the reference config (docs/config.md), status 0, nothing else.
TEST_F(IrlocdReplay, PrintConfigWritesTheReferenceConfig) {
  const std::filesystem::path printed = dir_ / "printed.yaml";
  test::ChildOptions options;
  options.stdout_file = printed;
  options.stderr_file = dir_ / "stderr.txt";
  test::ChildProcess irlocd({IRLOCD_PATH, "--print-config"}, options);
  EXPECT_EQ(irlocd.wait(), 0);
  EXPECT_EQ(read_text(printed), io::reference_config_yaml());
  EXPECT_EQ(read_text(dir_ / "stderr.txt"), "");
}

TEST_F(IrlocdReplay, MissingConfig) {
  expect_one_error_line(irlocd({"--config", (dir_ / "nope.yaml").string(), "--camera", "dir:x", "--serial", "none"}),
                        dir_ / "nope.yaml", "cannot open");
}

TEST_F(IrlocdReplay, MalformedYaml) {
  make_dataset(4);
  replace_in(dataset() / "map.yaml", "origin: [1.0, 2.0, 2.6]", "origin: [1.0, 2.0, 2.6");
  expect_one_error_line(replay(), dataset() / "map.yaml", "malformed YAML");
}

TEST_F(IrlocdReplay, BadValueAndUnknownKey) {
  make_dataset(4);
  replace_in(dataset() / "config.yaml", "dof: 3", "dof: 2");
  expect_one_error_line(replay(), dataset() / "config.yaml", ":5: robot.dof: must be 3, 4 or 6, got 2");
  replace_in(dataset() / "config.yaml", "dof: 2", "dof: 3\n  wheels: 4");
  expect_one_error_line(replay(), dataset() / "config.yaml", ":6: robot.wheels: unknown key");
}

TEST_F(IrlocdReplay, MapTheMarkerPathsCannotUse) {
  make_dataset(4);
  replace_in(dataset() / "map.yaml", "origin: [1.0, 2.0, 2.6]", "origin: [1.0, 2.0, 0.1]");
  expect_one_error_line(replay(), dataset() / "map.yaml", "not above the camera");
}

TEST_F(IrlocdReplay, FrameSizeDifferentFromCalibration) {
  make_dataset(4);
  replace_in(dataset() / "calib.yaml", "image_width: 320", "image_width: 640");
  expect_one_error_line(replay(), dataset() / "frame_000000.pgm", "frame is 320x240 but the calibration");
}

TEST_F(IrlocdReplay, TruncatedFrameKeepsTheRowsAlreadyWritten) {
  make_dataset(10);
  const std::filesystem::path frame = dataset() / "frame_000007.pgm";
  std::filesystem::resize_file(frame, std::filesystem::file_size(frame) - 100);
  expect_one_error_line(replay(), frame, "truncated");
  // On-frames 0, 2, 4, 6 were paired and written before frame 7 was read.
  EXPECT_EQ(lines_of(read_text(pose_csv())).size(), 5u);
}

TEST_F(IrlocdReplay, NonMonotonicSeq) {
  make_dataset(4);
  replace_in(dataset() / "frames.csv", "\n2,", "\n0,");
  expect_one_error_line(replay(), dataset() / "frames.csv", ":4: seq: 0 does not increase");
}

TEST_F(IrlocdReplay, UnknownCameraAndProtocol) {
  make_dataset(4);
  const std::string config = (dataset() / "config.yaml").string();
  expect_one_error_line(irlocd({"--config", config, "--camera", "usb:0", "--serial", "none"}), "--camera usb:0",
                        "unknown camera");
  const ProcessResult run = irlocd({"--config", config, "--camera", "dir:x", "--protocol", "nmea"});
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.stderr_text, HasSubstr("--protocol"));
}

TEST_F(IrlocdReplay, DuplicateKeyInTheConfig) {
  make_dataset(4);
  replace_in(dataset() / "config.yaml", "dof: 3", "dof: 3\n  dof: 6");
  expect_one_error_line(replay(), dataset() / "config.yaml", ":6: dof: duplicate key (first given on line 5)");
}

// A principal point off the image left no pixel looking at the ceiling, which the square path
// reported against the map.
TEST_F(IrlocdReplay, BadCalibrationIsBlamedOnTheCalibration) {
  make_dataset(4);
  std::ofstream(dataset() / "map.yaml", std::ios::app)
      << "square_markers:\n  - name: a\n    corners: [[0, 0, 2.6], [2, 0, 2.6], [2, 2, 2.6], [0, 2, 2.6]]\n";
  replace_in(dataset() / "calib.yaml", "159.500000", "5000");
  expect_one_error_line(replay(), dataset() / "calib.yaml", "camera_matrix: cx: must be in [-1280, 1600], got 5000");
}

TEST_F(IrlocdReplay, FramesCsvAsFifoIsRefusedWithoutHanging) {
  make_dataset(4);
  const std::filesystem::path index = dataset() / "frames.csv";
  std::filesystem::remove(index);
  ASSERT_EQ(::mkfifo(index.c_str(), 0600), 0);
  expect_one_error_line(replay(), index, "is a special file (FIFO, device or socket), expected a regular file");
}

TEST_F(IrlocdReplay, OutputsNeverOverwriteInputs) {
  make_dataset(4);
  const std::string config_text = read_text(dataset() / "config.yaml");
  for (const char* input : {"config.yaml", "calib.yaml", "map.yaml", "frames.csv", "frame_000002.pgm"}) {
    const std::filesystem::path file = dataset() / input;
    const std::string before = read_text(file);
    expect_one_error_line(replay_with({"--pose-csv", file.string()}), file, "refusing to overwrite it");
    EXPECT_EQ(read_text(file), before) << input;
  }
  // --record into the dataset being replayed (or any folder in use).
  expect_one_error_line(replay_with({"--record", dataset().string()}), dataset(), "the folder is not empty");
  EXPECT_EQ(read_text(dataset() / "config.yaml"), config_text);
}

TEST_F(IrlocdReplay, EmptyFileNamesAreErrorsNotNone) {
  make_dataset(4);
  for (const char* option : {"--pose-csv", "--serial", "--record", "--camera"}) {
    const ProcessResult run = irlocd({"--config", (dataset() / "config.yaml").string(), option, ""});
    EXPECT_EQ(run.status, 2) << option;
    EXPECT_THAT(run.stderr_text, HasSubstr(std::string(option) + ": must not be empty"));
  }
}

// The replay loop of irlocd, piece by piece: after start-up, frames go through without a single
// heap allocation.
TEST_F(IrlocdReplay, PerFrameLoopAllocatesNothing) {
  make_dataset(40, {9, 20});
  io::RobotConfig config = io::load_robot_config(dataset() / "config.yaml");
  hal::DatasetCamera camera(dataset(), config.setup.camera.width, config.setup.camera.height, "calib.yaml");
  io::PoseCsvWriter writer(pose_csv());
  Localizer localizer(std::move(config.setup));
  StrobePairer pairer;
  Frame frame;
  int attempts = 0;
  test::AllocationCounter counter;
  while (camera.next(frame)) {
    if (const std::optional<StrobePair> pair = pairer.push(frame)) {
      writer.write(localizer.process(*pair));
      ++attempts;
    }
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(attempts, 19);  // on-frames 0, 2, ..., 38 but the dropped 20
}

}  // namespace
}  // namespace irloc
